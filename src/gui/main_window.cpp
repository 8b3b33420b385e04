#include "gui/main_window.h"

#include <QCloseEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QRegularExpression>
#include <QSettings>
#include <QSplitter>
#include <QStatusBar>
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "gui/environment_entry.h"
#include "gui/geometry_view.h"
#include "gui/light_commands.h"
#include "gui/light_details.h"
#include "gui/light_dialog.h"
#include "gui/light_list_model.h"
#include "gui/lights_panel.h"
#include "gui/photo_panel.h"
#include "gui/photo_view.h"
#include "gui/scenes_from_photo.h"
#include "gui/task_status.h"
#include "gui/tone_map.h"
#include "io/image_io.h"
#include "io/scene_io.h"

namespace relight::gui {

namespace {

constexpr int kMaxRecent = 8;
const QString kRecentScenes = QStringLiteral("recent_scenes");
const QString kRecentRigs = QStringLiteral("recent_rigs");

// "NAME copy", or "NAME copy N" with the first N from 2 that no light of
// `rig` is named; a copy of a copy counts on from the original's name.
std::string copy_name(const Rig& rig, const std::string& name) {
  static const QRegularExpression copy_suffix(QStringLiteral(" copy( \\d+)?$"));
  const QString stem = QString::fromStdString(name).remove(copy_suffix) + QStringLiteral(" copy");
  const auto taken = [&](const QString& candidate) {
    return std::any_of(rig.lights.begin(), rig.lights.end(),
                       [&](const Light& l) { return l.name == candidate.toStdString(); });
  };
  QString candidate = stem;
  for (int n = 2; taken(candidate); ++n) candidate = QStringLiteral("%1 %2").arg(stem).arg(n);
  return candidate.toStdString();
}

}  // namespace

StudioOptions default_studio_options() {
  StudioOptions options;
  options.session.backend = Backend::gl;
  return options;
}

MainWindow::MainWindow(StudioOptions options, QWidget* parent)
    : QMainWindow(parent), options_(options), lights_(new LightsPanel), photo_panel_(new PhotoPanel) {
  connect_panels();
  auto* splitter = new QSplitter(Qt::Horizontal);
  splitter->addWidget(lights_);
  splitter->addWidget(photo_panel_);
  splitter->setStretchFactor(0, 0);
  splitter->setStretchFactor(1, 1);
  splitter->setSizes({430, 900});
  setCentralWidget(splitter);
  make_menus();

  task_status_ = new TaskStatus(task_);
  mode_label_ = new QLabel(mode_text());
  mode_label_->setMinimumWidth(mode_label_->fontMetrics().horizontalAdvance(mode_text()) + 16);
  statusBar()->addPermanentWidget(mode_label_);
  statusBar()->addPermanentWidget(task_status_);

  connect(&undo_, &QUndoStack::cleanChanged, this, [this] { update_title(); });
  update_actions();
  update_title();
  resize(1500, 900);
}

GeometryView& MainWindow::geometry_view() const { return lights_->geometry_view(); }
PhotoView& MainWindow::photo_view() const { return photo_panel_->photo_view(); }
LightListModel& MainWindow::light_model() const { return lights_->model(); }

MainWindow::~MainWindow() {
  task_.cancel();
  task_.wait();
  undo_.clear();
  lights_->set_document(nullptr);
  photo_view().set_document(nullptr);
}

void MainWindow::connect_panels() {
  GeometryView* geometry = &lights_->geometry_view();
  connect(geometry, &GeometryView::lightClicked, this, &MainWindow::select_light);
  // A drag in either view edits the light live and is one undo step when let go.
  const auto dragged = [this](int index, const Light& light) { document_->set_light(index, light); };
  const auto dropped = [this](int index, const Light& before, const Light& after) {
    undo_.push(new EditLightCommand(*document_, index, before, after, tr("Drag light")));
  };
  connect(geometry, &GeometryView::lightDragged, this, dragged);
  connect(geometry, &GeometryView::lightDropped, this, dropped);
  connect(&photo_view(), &PhotoView::lightDragged, this, dragged);
  connect(&photo_view(), &PhotoView::lightDropped, this, dropped);
  connect(geometry, &GeometryView::moveRequested, this, &MainWindow::move_selected_light);
  connect(geometry, &GeometryView::deleteRequested, this, [this] {
    if (selected_ >= 0) delete_light(selected_);
  });
  connect(&lights_->details(), &LightDetails::colourEdited, this, &MainWindow::set_selected_colour);
  connect(&lights_->details(), &LightDetails::powerEdited, this, &MainWindow::set_selected_power);
  connect(&lights_->model(), &LightListModel::enabledToggleRequested, this, &MainWindow::set_light_enabled);
  connect(&lights_->model(), &LightListModel::soloToggleRequested, this, &MainWindow::toggle_solo);
  connect(lights_, &LightsPanel::lightSelected, this, &MainWindow::select_light);
  connect(lights_, &LightsPanel::newRequested, this, &MainWindow::new_light_dialog);
  connect(lights_, &LightsPanel::changeRequested, this, &MainWindow::change_light_dialog);
  connect(lights_, &LightsPanel::deleteRequested, this, [this] { delete_light(selected_); });

  EnvironmentEntry* environment = &lights_->environment();
  connect(environment, &EnvironmentEntry::imageRequested, this, [this] {
    const QString folder = QFileInfo(rig_path_.isEmpty() ? scene_path_ : rig_path_).path();
    const QString path =
        QFileDialog::getOpenFileName(this, tr("A new sky"), folder, tr("HDR images (*.exr *.hdr);;All files (*)"));
    if (!path.isEmpty()) open_sky(path);
  });
  connect(environment, &EnvironmentEntry::enabledToggled, this, &MainWindow::set_sky_enabled);
  connect(environment, &EnvironmentEntry::turnEdited, this, &MainWindow::turn_sky);
  // A drag turns the sky live and is one undo step when let go.
  connect(environment, &EnvironmentEntry::turnDragged, this, [this](float turn_deg) {
    if (!document_) return;
    SkyEdit sky = document_->sky();
    sky.turn_deg = turn_deg;
    document_->set_sky(sky);
  });
  connect(environment, &EnvironmentEntry::turnDropped, this, [this](float before_deg, float after_deg) {
    if (!document_) return;
    SkyEdit before = document_->sky(), after = before;
    before.turn_deg = before_deg;
    after.turn_deg = after_deg;
    undo_.push(new EnvironmentCommand(*document_, before, after, tr("Drag the sky")));
  });
  connect(environment, &EnvironmentEntry::strengthEdited, this, [this](float scale) {
    if (document_ && scale != document_->rig().environment_scale)
      undo_.push(new EnvironmentScaleCommand(*document_, document_->rig().environment_scale, scale));
  });

  connect(&photo_panel_->photo_view(), &PhotoView::photoClicked, this, &MainWindow::photo_clicked);
  connect(photo_panel_, &PhotoPanel::ambientEdited, this, [this](float scale) {
    if (document_ && scale != document_->rig().environment_scale)
      undo_.push(new EnvironmentScaleCommand(*document_, document_->rig().environment_scale, scale));
  });
}

void MainWindow::make_menus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  file->addAction(tr("&Open Scene\u2026"), QKeySequence::Open, this, [this] {
    if (!maybe_keep_changes()) return;
    const QString path =
        QFileDialog::getOpenFileName(this, tr("Open scene"), QFileInfo(scene_path_).path(), tr("Scenes (*.json)"));
    if (!path.isEmpty()) open_scene(path);
  });
  file->addAction(tr("Open &Analysis\u2026"), this, [this] {
    if (!maybe_keep_changes()) return;
    QString scene = scene_path_;
    if (scene.isEmpty()) scene = QFileDialog::getOpenFileName(this, tr("Open scene"), QString(), tr("Scenes (*.json)"));
    if (scene.isEmpty()) return;
    const QString folder = QFileDialog::getExistingDirectory(
        this, tr("Open the analysis folder 'relight analyze' made for %1").arg(QFileInfo(scene).fileName()),
        QFileInfo(scene).path());
    if (!folder.isEmpty()) open_scene(scene, {}, folder);
  });
  QMenu* recent_scenes = file->addMenu(tr("Recent &Scenes"));
  connect(recent_scenes, &QMenu::aboutToShow, this,
          [this, recent_scenes] { fill_recent_menu(recent_scenes, kRecentScenes); });
  file->addSeparator();
  open_rig_action_ = file->addAction(tr("Open &Rig\u2026"), QKeySequence(tr("Ctrl+Shift+O")), this, [this] {
    if (!maybe_keep_changes()) return;
    const QString path =
        QFileDialog::getOpenFileName(this, tr("Open rig"), QFileInfo(scene_path_).path(), tr("Rigs (*.json)"));
    if (!path.isEmpty()) open_rig(path);
  });
  QMenu* recent_rigs = file->addMenu(tr("Recent R&igs"));
  connect(recent_rigs, &QMenu::aboutToShow, this, [this, recent_rigs] { fill_recent_menu(recent_rigs, kRecentRigs); });
  save_rig_action_ = file->addAction(tr("&Save Rig"), QKeySequence::Save, this, [this] {
    if (rig_path_.isEmpty())
      save_rig_as_action_->trigger();
    else
      save_rig(rig_path_);
  });
  save_rig_as_action_ = file->addAction(tr("Save Rig &As\u2026"), QKeySequence::SaveAs, this, [this] {
    const QString path = QFileDialog::getSaveFileName(
        this, tr("Save rig"), rig_path_.isEmpty() ? QFileInfo(scene_path_).dir().filePath("rig.json") : rig_path_,
        tr("Rigs (*.json)"));
    if (!path.isEmpty()) save_rig(path);
  });
  file->addSeparator();
  export_action_ = file->addAction(tr("&Export Image\u2026"), QKeySequence(tr("Ctrl+E")), this, [this] {
    const QString path = QFileDialog::getSaveFileName(this, tr("Export the re-lit photo"),
                                                      QFileInfo(scene_path_).dir().filePath("relit.exr"),
                                                      tr("OpenEXR, linear (*.exr);;PNG, with the exposure (*.png)"));
    if (!path.isEmpty()) export_image(path);
  });
  find_materials_action_ = file->addAction(tr("Find the Surfaces That &Shine…"), this, [this] {
    const QFileInfo scene(scene_path_);
    const QString path = QFileDialog::getSaveFileName(
        this, tr("Save the scene with the surfaces that shine"),
        scene.dir().filePath(scene.completeBaseName() + "_materials.json"), tr("Scenes (*.json)"));
    if (!path.isEmpty() && maybe_keep_changes()) find_materials(path);
  });
  find_materials_action_->setToolTip(
      tr("Estimate from the photo's highlights which surfaces are glossy, and how (relight materials)"));
  match_scene_action_ = file->addAction(tr("&Match the Scene to the Photo…"), this, [this] {
    const QFileInfo scene(scene_path_);
    const QString path = QFileDialog::getSaveFileName(this, tr("Save the scene matched to the photo"),
                                                      scene.dir().filePath(scene.completeBaseName() + "_matched.json"),
                                                      tr("Scenes (*.json)"));
    if (!path.isEmpty() && maybe_keep_changes()) match_scene(path);
  });
  match_scene_action_->setToolTip(
      tr("Register the camera to the photo's edges, then fit the lights' power and colour and move them to where "
         "their shadows fall (relight fit --register --refine-placement)"));
  file->addSeparator();
  file->addAction(tr("&Quit"), QKeySequence::Quit, this, &QWidget::close);

  QMenu* edit = menuBar()->addMenu(tr("&Edit"));
  QAction* undo = undo_.createUndoAction(this, tr("&Undo"));
  undo->setShortcut(QKeySequence::Undo);
  QAction* redo = undo_.createRedoAction(this, tr("&Redo"));
  redo->setShortcut(QKeySequence::Redo);
  edit->addAction(undo);
  edit->addAction(redo);
  edit->addSeparator();
  new_light_action_ =
      edit->addAction(tr("&New Light\u2026"), QKeySequence(Qt::Key_Insert), this, &MainWindow::new_light_dialog);
  change_light_action_ =
      edit->addAction(tr("&Change Light\u2026"), QKeySequence(Qt::Key_Return), this, &MainWindow::change_light_dialog);
  duplicate_light_action_ = edit->addAction(tr("D&uplicate Light"), QKeySequence(tr("Ctrl+D")), this,
                                            [this] { duplicate_light(selected_); });
  solo_light_action_ =
      edit->addAction(tr("&Solo Light"), QKeySequence(tr("Ctrl+L")), this, [this] { toggle_solo(selected_); });
  solo_light_action_->setCheckable(true);
  delete_light_action_ = edit->addAction(tr("&Delete Light\tDel"), this, [this] { delete_light(selected_); });
  lights_->set_list_menu({change_light_action_, duplicate_light_action_, solo_light_action_, delete_light_action_});
  edit->addSeparator();
  // A click on the photo selects; placing is a tool picked on purpose, so
  // that a click to focus the window never moves a light.
  place_tool_action_ = edit->addAction(tr("&Place Light Tool"), QKeySequence(Qt::Key_P), this,
                                       [this] { mode_label_->setText(mode_text()); });
  place_tool_action_->setCheckable(true);
  // Insert and Enter act where the lights are handled, not in the spin boxes.
  for (QAction* action : {new_light_action_, change_light_action_}) {
    action->setShortcutContext(Qt::WidgetShortcut);
    lights_->geometry_view().addAction(action);
  }

  QMenu* view = menuBar()->addMenu(tr("&View"));
  GeometryView& geometry = lights_->geometry_view();
  // Single keys, for the geometry view only (they are text elsewhere).
  for (QAction* action :
       {view->addAction(tr("&Camera's View"), QKeySequence(Qt::Key_C), &geometry, &GeometryView::reset_orbit),
        view->addAction(tr("Frame &All"), QKeySequence(Qt::Key_A), &geometry, &GeometryView::frame_all),
        view->addAction(tr("Frame &Selected"), QKeySequence(Qt::Key_F), &geometry, &GeometryView::frame_selected)}) {
    action->setShortcutContext(Qt::WidgetShortcut);
    geometry.addAction(action);
  }
  view->addSeparator();
  QAction* shapes = view->addAction(tr("Show &Light Shapes on the Photo"));
  shapes->setCheckable(true);
  shapes->setChecked(photo_view().shapes_shown());
  connect(shapes, &QAction::toggled, &photo_view(), &PhotoView::set_shapes_shown);
  QAction* geometry_over_photo = view->addAction(tr("Show the &Geometry Over the Photo"), QKeySequence(tr("Ctrl+G")));
  geometry_over_photo->setObjectName("show_geometry");
  geometry_over_photo->setCheckable(true);
  geometry_over_photo->setChecked(photo_view().geometry_shown());
  geometry_over_photo->setToolTip(tr("The model's edges as the photo's camera sees them, over the photo"));
  connect(geometry_over_photo, &QAction::toggled, &photo_view(), &PhotoView::set_geometry_shown);
}

void MainWindow::run_task(const QString& label, BackgroundTask::Work work, std::function<void(const QString&)> done) {
  task_status_->show_task(label);
  auto connection = std::make_shared<QMetaObject::Connection>();
  *connection = connect(&task_, &BackgroundTask::finished, this, [this, done, connection](const QString& error) {
    disconnect(*connection);
    update_actions();
    done(error);
  });
  task_.start(std::move(work));
  update_actions();
}

void MainWindow::open_scene(const QString& scene_path, const QString& rig_path, const QString& analysis_folder) {
  if (busy()) return;
  auto loaded = std::make_shared<std::shared_ptr<const StudioScene>>();
  StudioLoad load = studio_load();
  load.analysis_folder = analysis_folder.toStdString();
  load.preview_above_pixels = options_.preview_above_pixels;
  const std::string path = scene_path.toStdString();
  run_task((analysis_folder.isEmpty() ? tr("Analysing %1\u2026") : tr("Opening %1\u2026"))
               .arg(QFileInfo(scene_path).fileName()),
           [loaded, load, path](Progress& progress) { *loaded = load_studio_scene(path, load, progress); },
           [this, loaded, scene_path, rig_path](const QString& error) {
             if (!error.isEmpty()) {
               show_error(error == "cancelled" ? tr("Opening %1 was cancelled.").arg(scene_path) : error);
               emit openFailed(error);
               return;
             }
             install_scene(*loaded, scene_path, rig_path);
             emit sceneOpened();
             if (scene_->preview) replace_preview();
           });
}

void MainWindow::replace_preview() {
  auto loaded = std::make_shared<std::shared_ptr<const StudioScene>>();
  const StudioLoad load = studio_load();
  const std::string path = scene_path_.toStdString();
  run_task(
      tr("Analysing %1 in full (the preview meanwhile)\u2026").arg(QFileInfo(scene_path_).fileName()),
      [loaded, load, path](Progress& progress) { *loaded = load_studio_scene(path, load, progress); },
      [this, loaded](const QString& error) {
        if (!error.isEmpty()) {
          statusBar()->showMessage(
              error == "cancelled"
                  ? tr("The full analysis was cancelled: the preview stays (reopen the scene to analyse it)")
                  : tr("The full analysis failed (%1): the preview stays").arg(error),
              8000);
          emit fullAnalysisDone(error);
          return;
        }
        scene_ = *loaded;
        document_->replace_scene(scene_, options_.session);
        show_analysis();
        select_light(selected_);
        emit fullAnalysisDone({});
      });
}

StudioLoad MainWindow::studio_load() const {
  StudioLoad load;
  load.analysis = options_.analysis;
  load.max_view_width = options_.max_view_width;
  return load;
}

void MainWindow::install_scene(std::shared_ptr<const StudioScene> scene, const QString& scene_path,
                               const QString& rig_path) {
  Rig rig = rig_from_scene(scene->analysed->scene());
  QString loaded_rig_path;
  if (!rig_path.isEmpty()) {
    try {
      rig = load_rig(rig_path.toStdString());
      loaded_rig_path = rig_path;
    } catch (const InputError& e) {
      show_error(QString::fromStdString(e.what()) + tr(" (the scene's own lights are used instead)"));
    }
  }
  undo_.clear();
  lights_->set_document(nullptr);
  photo_view().set_document(nullptr);
  document_.reset();
  scene_ = std::move(scene);
  document_ = std::make_unique<LightingDocument>(scene_, rig, options_.session);
  scene_path_ = scene_path;
  rig_path_ = loaded_rig_path;

  lights_->set_document(document_.get());
  photo_view().set_document(document_.get());
  connect(document_.get(), &LightingDocument::lightChanged, this, [this](int index) {
    if (index == selected_) lights_->show_details(index);
  });
  connect(document_.get(), &LightingDocument::lightInserted, this, &MainWindow::select_light);
  connect(document_.get(), &LightingDocument::lightRemoved, this,
          [this](int index) { select_light(std::min(index, document_->light_count() - 1)); });
  connect(document_.get(), &LightingDocument::rigReset, this, [this] {
    select_light(document_->light_count() > 0 ? 0 : -1);
    photo_panel_->show_ambient(document_->rig().environment_scale);
  });
  connect(document_.get(), &LightingDocument::environmentScaleChanged, photo_panel_, &PhotoPanel::show_ambient);
  connect(document_.get(), &LightingDocument::soloChanged, this, &MainWindow::update_actions);
  connect(document_.get(), &LightingDocument::frameReady, this, [this] { refresh_frame(); });
  photo_panel_->show_ambient(rig.environment_scale);
  photo_panel_->set_exposure(scene_->display_exposure);
  show_analysis();
  select_light(document_->light_count() > 0 ? 0 : -1);
  remember(kRecentScenes, scene_path);
  if (!rig_path_.isEmpty()) remember(kRecentRigs, rig_path_);
  note_animation(rig);
  geometry_view().setFocus();
  update_actions();
  update_title();
}

void MainWindow::show_analysis() {
  // Not a copy (the scene's own photo is 288 MB at 24 Mpixel): the pointer keeps the scene alive.
  photo_view().set_photo(std::shared_ptr<const Image>(scene_, &scene_->shown_photo()));
  photo_view().set_relit(nullptr);
  photo_view().set_geometry_edges(scene_->geometry_edges);
  QString opened =
      scene_->preview ? tr("A preview analysis (a reduced photo, few paths); the full one follows")
      : scene_->from_cache
          ? tr("Analysis read from %1").arg(QString::fromStdString(scene_->analysis_folder.filename().string()))
          : tr("Scene analysed; the analysis is kept next to the scene for next time");
  if (scene_->analysed->analysis().registered_camera)
    opened += tr(". The camera was off the photo: the analysis sees through it registered to the photo's edges "
                 "(Ctrl+G shows the geometry over the photo)");
  statusBar()->showMessage(opened, 8000);
  if (!document_->session().backend_note().empty())
    statusBar()->showMessage(QString::fromStdString(document_->session().backend_note()), 8000);
}

void MainWindow::note_animation(const Rig& rig) {
  const auto animated =
      std::count_if(rig.lights.begin(), rig.lights.end(), [](const Light& l) { return !l.keys.empty(); });
  if (animated)
    statusBar()->showMessage(tr("%1 of the rig's lights animated. %2").arg(animated).arg(animated_light_note()), 15000);
}

bool MainWindow::open_rig(const QString& path) {
  if (!document_) return false;
  try {
    const Rig rig = load_rig(path.toStdString());
    undo_.clear();
    document_->reset_rig(rig);
    rig_path_ = path;
    remember(kRecentRigs, path);
    update_title();
    note_animation(rig);
    return true;
  } catch (const InputError& e) {
    show_error(QString::fromStdString(e.what()));
    return false;
  }
}

void MainWindow::edit_sky(const QString& text, EnvironmentCommand::Merge merge,
                          const std::function<void(SkyEdit&)>& change) {
  if (!document_) return;
  SkyEdit after = document_->sky();
  change(after);
  if (after == document_->sky()) return;
  undo_.push(new EnvironmentCommand(*document_, document_->sky(), after, text, merge));
}

bool MainWindow::open_sky(const QString& image_path) {
  if (!document_) return false;
  try {
    const RigEnvironment sky = load_environment_image(image_path.toStdString());
    edit_sky(tr("New sky %1").arg(QFileInfo(image_path).fileName()), EnvironmentCommand::Merge::never,
             [&](SkyEdit& edit) { edit = SkyEdit{sky}; });
    return true;
  } catch (const std::exception& e) {
    show_error(QString::fromStdString(e.what()));
    return false;
  }
}

void MainWindow::turn_sky(float turn_deg) {
  edit_sky(tr("Turn the sky"), EnvironmentCommand::Merge::turn, [&](SkyEdit& sky) { sky.turn_deg = turn_deg; });
}

void MainWindow::set_sky_enabled(bool enabled) {
  edit_sky(enabled ? tr("Show the new sky") : tr("Switch the new sky off"), EnvironmentCommand::Merge::never,
           [&](SkyEdit& sky) { sky.enabled = enabled; });
}

bool MainWindow::save_rig(const QString& path) {
  if (!document_) return false;
  try {
    relight::save_rig(path.toStdString(), document_->rig());
  } catch (const std::exception& e) {
    show_error(tr("%1: cannot save the rig (%2)").arg(path, QString::fromStdString(e.what())));
    return false;
  }
  rig_path_ = path;
  undo_.setClean();
  remember(kRecentRigs, path);
  update_title();
  statusBar()->showMessage(tr("Saved %1").arg(path), 5000);
  return true;
}

void MainWindow::export_image(const QString& path) {
  if (!document_ || busy()) return;
  const QString suffix = QFileInfo(path).suffix().toLower();
  if (suffix != "exr" && suffix != "png") {
    show_error(tr("%1: export writes .exr (linear) or .png (with the exposure); name the file so").arg(path));
    emit exportFinished(last_error_);
    return;
  }
  const std::shared_ptr<const StudioScene> scene = scene_;
  const Rig rig = document_->shown_rig();  // with a light soloed, that light's own picture
  const RenderOptions render = options_.session.final_render;
  const float exposure = photo_view().exposure();
  const std::string target = path.toStdString();
  const bool png = suffix == "png";
  run_task(
      tr("Rendering %1\u2026").arg(QFileInfo(path).fileName()),
      [scene, rig, render, exposure, target, png](Progress& progress) {
        const Image image = render_rig(*scene->analysed, rig, render, progress);
        if (png)
          write_png(target, image, exposure);
        else
          write_exr(target, image);
      },
      [this, path](const QString& error) {
        if (error.isEmpty())
          statusBar()->showMessage(tr("Exported %1").arg(path), 8000);
        else
          show_error(error == "cancelled" ? tr("The export of %1 was cancelled.").arg(path) : error);
        emit exportFinished(error);
      });
}

void MainWindow::add_light(const Light& light) {
  if (document_) undo_.push(new AddLightCommand(*document_, light));
}

void MainWindow::change_light(int index, const Light& light) {
  if (document_ && index >= 0)
    undo_.push(new EditLightCommand(*document_, index, document_->light(index), light, tr("Change light")));
}

void MainWindow::delete_light(int index) {
  if (document_ && index >= 0 && index < document_->light_count())
    undo_.push(new DeleteLightCommand(*document_, index));
}

void MainWindow::duplicate_light(int index) {
  if (!document_ || index < 0 || index >= document_->light_count()) return;
  Light copy = document_->light(index);
  copy.name = copy_name(document_->rig(), copy.name);
  auto* command = new AddLightCommand(*document_, copy);
  command->setText(tr("Duplicate light \u201c%1\u201d").arg(QString::fromStdString(document_->light(index).name)));
  undo_.push(command);
}

void MainWindow::solo_light(int index) {
  if (!document_ || index >= document_->light_count()) return;
  document_->set_solo(index);
  if (index >= 0)
    statusBar()->showMessage(tr("Only \u201c%1\u201d is lit; Solo Light again (Ctrl+L) lights the others")
                                 .arg(QString::fromStdString(document_->light(index).name)),
                             8000);
}

void MainWindow::toggle_solo(int index) {
  if (document_) solo_light(document_->solo() == index ? -1 : index);
}

void MainWindow::set_light_enabled(int index, bool enabled) {
  if (!document_) return;
  Light light = document_->light(index);
  light.enabled = enabled;
  undo_.push(new EditLightCommand(*document_, index, document_->light(index), light,
                                  enabled ? tr("Switch light on") : tr("Switch light off")));
}

void MainWindow::edit_selected_light(const QString& text, EditLightCommand::Merge merge,
                                     const std::function<void(Light&)>& change) {
  if (!document_ || selected_ < 0) return;
  Light after = document_->light(selected_);
  change(after);
  undo_.push(new EditLightCommand(*document_, selected_, document_->light(selected_), after, text, merge));
}

void MainWindow::set_selected_colour(const Vec3& colour) {
  edit_selected_light(tr("Colour temperature"), EditLightCommand::Merge::colour,
                      [&](Light& light) { light.color = colour; });
}

void MainWindow::set_selected_power(float power) {
  edit_selected_light(tr("Power in stops"), EditLightCommand::Merge::power, [&](Light& light) {
    (light.type == LightType::directional ? light.irradiance : light.power) = power;
  });
}

void MainWindow::move_selected_light(const Vec3& delta) {
  if (!document_ || selected_ < 0) return;
  if (document_->light(selected_).type == LightType::directional) {
    statusBar()->showMessage(tr("A sun has no position: change its direction with Change\u2026"), 5000);
    return;
  }
  edit_selected_light(tr("Move light"), EditLightCommand::Merge::key_move,
                      [&](Light& light) { light.position += delta; });
}

QString MainWindow::mode_text() const {
  return place_tool_action_ && place_tool_action_->isChecked()
             ? tr("Place: a click puts the selected light there (P ends)")
             : tr("Select: a click picks a light (Ctrl+click or P places)");
}

void MainWindow::photo_clicked(const QPointF& image_position, Qt::KeyboardModifiers modifiers) {
  if (place_tool_action_->isChecked() || modifiers.testFlag(Qt::ControlModifier)) {
    place_selected_light(image_position);
  } else if (const int light = light_at(image_position); light >= 0) {
    select_light(light);
  }
}

int MainWindow::light_at(const QPointF& image_position) const {
  constexpr double kPickRadiusPx = 24.0;  // in the re-lit image's pixels
  if (!document_) return -1;
  const Camera& camera = document_->session().view().camera();
  int nearest = -1;
  double best = kPickRadiusPx;
  for (int i = 0; i < document_->light_count(); ++i) {
    const Light& light = document_->light(i);
    if (light.type == LightType::directional) continue;
    const auto shown = camera.project(light.position);
    if (!shown) continue;
    const double d = std::hypot(shown->x() - image_position.x(), shown->y() - image_position.y());
    if (d < best) best = d, nearest = i;
  }
  return nearest;
}

void MainWindow::place_selected_light(const QPointF& image_position) {
  if (!document_) return;
  if (selected_ < 0) {
    statusBar()->showMessage(tr("Select a light first (or add one with New\u2026), then click where it should shine"),
                             5000);
    return;
  }
  if (document_->light(selected_).type == LightType::directional) {
    statusBar()->showMessage(tr("A sun has no position: change its direction with Change\u2026"), 5000);
    return;
  }
  const Camera& camera = document_->session().view().camera();
  const Vec3 dir = camera.ray_direction(float(image_position.x()), float(image_position.y()));
  SurfacePoint hit;
  if (!scene_->analysed->rays().intersect(camera.position(), dir, hit)) {
    statusBar()->showMessage(tr("No modelled surface there to place the light in front of"), 5000);
    return;
  }
  // In front of the surface, a fifth of the way back to the camera's distance.
  const Light& before = document_->light(selected_);
  Light after = before;
  after.position = hit.position + 0.2f * hit.distance * hit.normal;
  if (before.type != LightType::point) after.direction = -hit.normal;  // spots and areas face it
  undo_.push(new EditLightCommand(*document_, selected_, before, after, tr("Place light")));
}

void MainWindow::select_light(int index) {
  if (!document_ || index >= document_->light_count()) index = -1;
  selected_ = index;
  lights_->show_selection(index);
  photo_view().set_selected(index);
  update_actions();
}

bool MainWindow::refresh_frame() {
  if (!document_) return false;
  const Frame frame = document_->session().frame();
  if (!frame.image || frame.image == photo_view().relit()) return false;
  photo_view().set_relit(frame.image);
  photo_panel_->show_quality(frame.quality, document_->session().backend());
  return true;
}

void MainWindow::find_materials(const QString& out_path) {
  if (!document_ || busy()) return;
  const auto fail = [this](const QString& message) {
    show_error(message);
    emit materialsFound(message, 0);
  };
  if (const QString refusal = refuse_to_write_scene(out_path, tr("find the surfaces that shine")); !refusal.isEmpty())
    return fail(refusal);
  namespace fs = std::filesystem;
  const fs::path out = fs::absolute(out_path.toStdString()), scene_file = fs::absolute(scene_path_.toStdString());
  const std::shared_ptr<const StudioScene> scene = scene_;
  auto estimates = std::make_shared<std::vector<MaterialEstimate>>();
  run_task(
      tr("Finding the surfaces that shine…"),
      [scene, estimates, scene_file, out](Progress& progress) {
        *estimates = write_scene_with_materials(*scene, scene_file, out, progress);
      },
      [this, fail, estimates, out_path](const QString& error) {
        if (!error.isEmpty())
          return fail(error == "cancelled" ? tr("Finding the surfaces that shine was cancelled.") : error);
        QStringList lines;
        int found = 0;
        for (const MaterialEstimate& m : *estimates) {
          lines << QString::fromStdString(describe_estimate(m));
          found += bool(m.gloss);
        }
        const QString heading =
            found ? (found == 1 ? tr("One surface shines.") : tr("%1 surfaces shine.").arg(found)) +
                        tr(" The scene with them is %1; it opens now, analysed with their highlights taken off the "
                           "photo (Show Details says what was found on each).")
                            .arg(QFileInfo(out_path).fileName())
                  : tr("No surface was found to shine; nothing was written.");
        report(heading, lines);
        emit materialsFound({}, found);
        if (found) open_scene(out_path, rig_path_);
      });
}

QString MainWindow::refuse_to_write_scene(const QString& out_path, const QString& doing) const {
  if (scene_->preview) return tr("The full analysis is still running: %1 once it is done").arg(doing);
  namespace fs = std::filesystem;
  std::error_code ignored;
  if (fs::weakly_canonical(fs::absolute(out_path.toStdString()), ignored) ==
      fs::weakly_canonical(fs::absolute(scene_path_.toStdString()), ignored))
    return tr("%1 is the open scene: name another file for the scene to write").arg(out_path);
  return {};
}

void MainWindow::report(const QString& heading, const QStringList& lines) {
  auto* box = new QMessageBox(QMessageBox::Information, tr("relight studio"), heading, QMessageBox::Ok, this);
  box->setDetailedText(lines.join('\n'));
  box->setAttribute(Qt::WA_DeleteOnClose);
  box->open();
  statusBar()->showMessage(heading, 15000);
}

void MainWindow::match_scene(const QString& out_path) {
  if (!document_ || busy()) return;
  const auto fail = [this](const QString& message) {
    show_error(message);
    emit sceneMatched(message);
  };
  if (const QString refusal = refuse_to_write_scene(out_path, tr("match the scene to the photo")); !refusal.isEmpty())
    return fail(refusal);
  namespace fs = std::filesystem;
  const fs::path out = fs::absolute(out_path.toStdString()), scene_file = fs::absolute(scene_path_.toStdString());
  const AnalysisOptions analysis = scene_->analysed->analysis().options;
  auto matched = std::make_shared<SceneMatch>();
  run_task(
      tr("Matching the scene to the photo…"),
      [scene_file, out, analysis, matched](Progress& progress) {
        *matched = write_scene_matched_to_photo(scene_file, out, analysis, progress);
      },
      [this, fail, matched, out_path](const QString& error) {
        if (!error.isEmpty())
          return fail(error == "cancelled" ? tr("Matching the scene to the photo was cancelled.") : error);
        QStringList lines;
        for (const std::string& line : matched->lines) lines << QString::fromStdString(line);
        const QString camera =
            matched->camera_moved_px
                ? tr("the camera moved %1 px on the photo").arg(double(*matched->camera_moved_px), 0, 'f', 1)
                : tr("the camera kept as given");
        report(tr("The scene matched to the photo is %1: %2, %3. It opens now (Show Details says what was fitted).")
                   .arg(QFileInfo(out_path).fileName(), camera,
                        matched->lights_moved ? tr("%n light(s) moved", "", matched->lights_moved)
                                              : tr("the lights where they were")),
               lines);
        emit sceneMatched({});
        open_scene(out_path, rig_path_);
      });
}

void MainWindow::update_actions() {
  const bool open = document_ != nullptr && !busy();
  const bool has = open && selected_ >= 0;
  for (QAction* a : {save_rig_action_, save_rig_as_action_, open_rig_action_, export_action_, find_materials_action_,
                     match_scene_action_, new_light_action_, place_tool_action_})
    a->setEnabled(open);
  for (QAction* a : {change_light_action_, duplicate_light_action_, solo_light_action_, delete_light_action_})
    a->setEnabled(has);
  solo_light_action_->setChecked(has && document_->solo() == selected_);
  lights_->enable_buttons(open, has);
  photo_panel_->enable_ambient(open);
}

void MainWindow::update_title() {
  QString title = tr("relight studio");
  if (!scene_path_.isEmpty()) {
    title += QStringLiteral(" \u2014 ") + QFileInfo(scene_path_).fileName();
    title += QStringLiteral(" \u2014 ") + (rig_path_.isEmpty() ? tr("untitled rig") : QFileInfo(rig_path_).fileName());
    title += QStringLiteral("[*]");
  }
  setWindowTitle(title);
  setWindowModified(!undo_.isClean());
}

void MainWindow::show_error(const QString& text) {
  last_error_ = text;
  statusBar()->showMessage(text, 15000);
  // Not modal to the event loop: long work and tests go on.
  auto* box = new QMessageBox(QMessageBox::Warning, tr("relight studio"), text, QMessageBox::Ok, this);
  box->setAttribute(Qt::WA_DeleteOnClose);
  box->open();
}

bool MainWindow::maybe_keep_changes() {
  if (!document_ || undo_.isClean()) return true;
  const auto answer =
      QMessageBox::question(this, tr("Unsaved changes"), tr("The rig has changes that are not saved. Save them first?"),
                            QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, QMessageBox::Save);
  if (answer == QMessageBox::Cancel) return false;
  if (answer == QMessageBox::Discard) return true;
  save_rig_action_->trigger();
  return undo_.isClean();
}

void MainWindow::closeEvent(QCloseEvent* event) {
  if (maybe_keep_changes()) {
    task_.cancel();
    event->accept();
  } else {
    event->ignore();
  }
}

Light MainWindow::default_new_light() const {
  Light light;
  light.type = LightType::point;
  light.name = tr("light %1").arg(document_->light_count() + 1).toStdString();
  const CameraSpec& camera = scene_->analysed->scene().camera.spec();
  // Above the point the camera looks at, as bright as the first light there is.
  light.position =
      camera.look_at + 0.1f * scene_->analysed->scene().mesh.bounds().diagonal().norm() * camera.up.normalized();
  light.power = 100.0f;
  for (const Light& l : document_->rig().lights)
    if (l.type != LightType::directional && l.power > 0.0f) {
      light.power = l.power;
      break;
    }
  light.color = Vec3(1.0f, 0.93f, 0.85f);
  return light;
}

void MainWindow::new_light_dialog() {
  if (!document_) return;
  LightDialog dialog(this);
  dialog.setWindowTitle(tr("New light"));
  dialog.set_light(default_new_light());
  if (dialog.exec() == QDialog::Accepted) add_light(dialog.light());
  geometry_view().setFocus();
}

void MainWindow::change_light_dialog() {
  if (!document_ || selected_ < 0) return;
  LightDialog dialog(this);
  dialog.setWindowTitle(tr("Change light"));
  dialog.set_light(document_->light(selected_));
  if (dialog.exec() == QDialog::Accepted) change_light(selected_, dialog.light());
  geometry_view().setFocus();
}

void MainWindow::remember(const QString& key, const QString& path) {
  if (!options_.remember_recent) return;
  QSettings settings;
  QStringList paths = settings.value(key).toStringList();
  const QString absolute = QFileInfo(path).absoluteFilePath();
  paths.removeAll(absolute);
  paths.prepend(absolute);
  while (paths.size() > kMaxRecent) paths.removeLast();
  settings.setValue(key, paths);
}

void MainWindow::fill_recent_menu(QMenu* menu, const QString& key) {
  menu->clear();
  const QStringList paths = options_.remember_recent ? QSettings().value(key).toStringList() : QStringList();
  for (const QString& path : paths)
    menu->addAction(path, this, [this, key, path] {
      if (!maybe_keep_changes()) return;
      if (key == kRecentScenes)
        open_scene(path);
      else
        open_rig(path);
    });
  if (paths.isEmpty()) menu->addAction(tr("(none yet)"))->setEnabled(false);
}

}  // namespace relight::gui
