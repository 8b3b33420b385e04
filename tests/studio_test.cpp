// relight studio (src/gui) on a copy of the example room, offscreen: opening
// a scene (analysis cached next to it), adding, editing, moving by keys and
// mouse, switching off, deleting, undo, rig files, export, that the picture
// on screen follows the lights, and the Environment entry's new sky.
#include <QDoubleSpinBox>
#include <QFile>
#include <QLabel>
#include <QLineEdit>
#include <QListView>
#include <QMessageBox>
#include <QMouseEvent>
#include <QProcess>
#include <QPushButton>
#include <QSettings>
#include <QSignalSpy>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QTimer>
#include <QToolButton>
#include <QtTest/QtTest>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include <unistd.h>

#include "analysis/camera_registration.h"
#include "gui/colour_temperature.h"
#include "gui/environment_entry.h"
#include "gui/geometry_overlay.h"
#include "gui/geometry_view.h"
#include "gui/light_dialog.h"
#include "gui/light_list_model.h"
#include "gui/light_shapes.h"
#include "gui/main_window.h"
#include "gui/photo_view.h"
#include "gui/sky_strip.h"
#include "gui/tone_map.h"
#include "io/image_io.h"
#include "io/scene_io.h"

using namespace relight;
using namespace relight::gui;
namespace fs = std::filesystem;

// Exact equality (QCOMPARE compares floats fuzzily).
#define EXPECT_EXACT(a, b)                                                    \
  QVERIFY2((a) == (b), qPrintable(QStringLiteral("%1 = %2, expected %3 = %4") \
                                      .arg(#a)                                \
                                      .arg(double(a), 0, 'g', 9)              \
                                      .arg(#b)                                \
                                      .arg(double(b), 0, 'g', 9)))

namespace {

std::string file_text(const fs::path& file) {
  std::ostringstream text;
  text << std::ifstream(file).rdbuf();
  return text.str();
}

// Cheap analysis and refinement: the tests check the wiring, not the quality.
StudioOptions quick_options() {
  StudioOptions o;
  o.analysis.paths_per_pixel = 4;
  o.analysis.interreflection = false;
  o.session.backend = Backend::cpu;
  o.session.soft_light_samples = 4;
  o.session.bounce_paths = 1;
  o.session.final_render.paths_per_pixel = 1;
  o.session.final_render.max_bounces = 1;
  o.session.settle = std::chrono::milliseconds(20);
  o.remember_recent = false;
  return o;
}

void expect_same_light(const Light& a, const Light& b) {
  QCOMPARE(a.name, b.name);
  QCOMPARE(a.type, b.type);
  QCOMPARE(a.enabled, b.enabled);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EXACT(a.color[i], b.color[i]);
    EXPECT_EXACT(a.position[i], b.position[i]);
    EXPECT_EXACT(a.direction[i], b.direction[i]);
  }
  EXPECT_EXACT(a.power, b.power);
  EXPECT_EXACT(a.irradiance, b.irradiance);
  EXPECT_EXACT(a.radius, b.radius);
  EXPECT_EXACT(a.spot_angle_deg, b.spot_angle_deg);
  EXPECT_EXACT(a.blend, b.blend);
  EXPECT_EXACT(a.size.x(), b.size.x());
  EXPECT_EXACT(a.size.y(), b.size.y());
}

// Where to write pictures of widgets for a look (RELIGHT_TEST_IMAGES=folder), if anywhere.
void keep_picture(const QString& name, QWidget& widget) {
  if (const char* folder = std::getenv("RELIGHT_TEST_IMAGES")) {
    fs::create_directories(folder);
    QVERIFY(widget.grab().save(QString::fromLocal8Bit(folder) + "/" + name + ".png"));
  }
}

// Whether a pixel within one of `at` has about `colour` (antialiased lines
// blend at their edges).
bool shows_colour(const QImage& image, QPointF at, const QColor& colour) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const QColor c = image.pixelColor(int(std::floor(at.x())) + dx, int(std::floor(at.y())) + dy);
      if (std::abs(c.red() - colour.red()) + std::abs(c.green() - colour.green()) +
              std::abs(c.blue() - colour.blue()) < 40)
        return true;
    }
  return false;
}

// Pixels whose colour differs between two images of one size.
int differing_pixels(const QImage& a, const QImage& b) {
  int n = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) n += a.pixel(x, y) != b.pixel(x, y);
  return n;
}

}  // namespace

class StudioTest : public QObject {
  Q_OBJECT

 private:
  QTemporaryDir folder_;
  QString scene_, evening_, sky_rig_;
  std::unique_ptr<MainWindow> window_;

  // A window on the room; with `rig`, that rig instead of the scene's lamp.
  void open(const QString& rig = {}) {
    window_ = std::make_unique<MainWindow>(quick_options());
    window_->resize(1200, 800);
    window_->show();
    QVERIFY(QTest::qWaitForWindowExposed(window_.get()));
    QSignalSpy opened(window_.get(), &MainWindow::sceneOpened);
    window_->open_scene(scene_, rig);
    QVERIFY(opened.wait(240000));
  }
  LightingDocument& document() { return *window_->document(); }
  // The session draws on the view the opened scene brought (made in the task
  // that opened it, off the window's thread), of this size; the photo beside
  // it ("before") and the geometry's edges over it are at that size too, and
  // the frame's exposure is the one chosen for the photo there.
  void expect_the_scenes_view_at(int width, int height) {
    QCOMPARE(&document().session().view(), document().studio_scene().session_view.get());
    QCOMPARE(document().session().view().width(), width);
    QCOMPARE(document().session().view().height(), height);
    const Image& shown = document().studio_scene().shown_photo();
    QCOMPARE(shown.width, width);
    QCOMPARE(shown.height, height);
    QCOMPARE(document().studio_scene().geometry_edges.size(), QSize(width, height));
    QCOMPARE(window_->photo_view().exposure(), display_exposure_for(shown));
  }
  // The session has drawn every edit so far at final quality; the window shows it.
  void show_converged_frame() {
    document().session().wait_until_converged();
    window_->refresh_frame();
  }
  QWidget& lights_environment() { return *window_->findChild<EnvironmentEntry*>(); }
  // Presses the mouse on the geometry view at `at`, moves it by `by` and
  // lets go; `before_release` runs while the button is still down.
  void drag_in_geometry_view(QPoint at, QPoint by, const std::function<void()>& before_release = [] {}) {
    GeometryView& view = window_->geometry_view();
    const auto send = [&](QEvent::Type type, QPoint p, Qt::MouseButtons buttons) {
      QMouseEvent event(type, p, view.mapToGlobal(p), Qt::LeftButton, buttons, Qt::NoModifier);
      QApplication::sendEvent(&view, &event);
    };
    send(QEvent::MouseButtonPress, at, Qt::LeftButton);
    send(QEvent::MouseMove, at + by, Qt::LeftButton);
    before_release();
    send(QEvent::MouseButtonRelease, at + by, Qt::NoButton);
  }
  // Presses the mouse on the photo at `from`, moves it to `to` and lets go.
  void drag_on_photo(QPoint from, QPoint to) {
    PhotoView& view = window_->photo_view();
    QTest::mousePress(&view, Qt::LeftButton, {}, from);
    QMouseEvent move(QEvent::MouseMove, QPointF(to), view.mapToGlobal(QPointF(to)), Qt::NoButton, Qt::LeftButton, {});
    QCoreApplication::sendEvent(&view, &move);
    QTest::mouseRelease(&view, Qt::LeftButton, {}, to);
  }
  // Light 0 made a `type` light without radius, 40 % of the way from the
  // surface the middle of the view shows back towards the camera, aimed at
  // that surface.
  Light light_facing_the_middle_of_the_view(LightType type) {
    const Camera& camera = document().session().view().camera();
    SurfacePoint hit;
    [&] {
      QVERIFY(document().studio_scene().analysed->rays().intersect(
          camera.position(), camera.ray_direction(0.5f * float(camera.width()), 0.5f * float(camera.height())), hit));
    }();
    Light light = document().light(0);
    light.type = type;
    light.radius = 0.0f;
    light.position = hit.position + 0.4f * (camera.position() - hit.position);
    light.direction = (hit.position - light.position).normalized();
    return light;
  }
  // Light 0 made a 1.6 x 1 m area light facing down where it is, selected
  // and framed in the geometry view.
  Light selected_framed_area_light() {
    Light area = document().light(0);
    area.type = LightType::area;
    area.direction = Vec3(0, 0, -1);
    area.up = Vec3(0, 1, 0);
    area.size = Vec2(1.6f, 1.0f);
    document().set_light(0, area);
    window_->select_light(0);
    window_->geometry_view().frame_selected();
    return area;
  }
  // Where light `index`'s dot is in the geometry view.
  QPoint dot_of(int index) {
    GeometryView& view = window_->geometry_view();
    const auto dot = view.project(view.marker_position(document().light(index)));
    return dot ? dot->toPoint() : QPoint(-1, -1);
  }

 private slots:
  void initTestCase() {
    QVERIFY(folder_.isValid());
    // Recent files go to an ini file in the test's folder, not the user's settings.
    QCoreApplication::setOrganizationName("relight-test");
    QSettings::setDefaultFormat(QSettings::IniFormat);
    QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, folder_.filePath("settings"));
    const fs::path room = fs::path(RELIGHT_SOURCE_DIR) / "examples/room";
    const fs::path copy = folder_.path().toStdString();
    for (const char* f : {"scene.json", "photo.exr", "geometry.obj"}) fs::copy_file(room / f, copy / f);
    fs::copy_file(room / "rigs/evening.json", copy / "evening.json");
    scene_ = QString::fromStdString((copy / "scene.json").string());
    evening_ = QString::fromStdString((copy / "evening.json").string());
    // The evening rig under a new sky: blue above the horizon, a bright
    // patch low on the right of its forward, dark ground.
    Image sky(64, 32);
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 64; ++x)
        sky.at(x, y) = y < 16 ? (x >= 40 && x < 46 && y >= 10 ? Vec3(40, 36, 30) : Vec3(0.3f, 0.45f, 0.8f))
                              : Vec3(0.05f, 0.05f, 0.04f);
    fs::create_directories(copy / "skies");
    write_exr(copy / "skies" / "sky.exr", sky);
    Rig under_sky = load_rig(copy / "evening.json");
    under_sky.environment = load_environment_image(copy / "skies" / "sky.exr");
    save_rig(copy / "sky.json", under_sky);
    sky_rig_ = QString::fromStdString((copy / "sky.json").string());
    // The first open analyses the scene and leaves the analysis beside it.
    open();
    QVERIFY(!document().studio_scene().from_cache);
    QVERIFY(fs::exists(copy / "scene.analysis" / "analysis.json"));
  }

  void init() { open(); }
  void cleanup() { window_.reset(); }

  void reopening_reads_the_cached_analysis() {
    QVERIFY(document().studio_scene().from_cache);
    QCOMPARE(document().light_count(), 1);
    QCOMPARE(document().light(0).name, std::string("lamp"));
    QCOMPARE(window_->selected_light(), 0);
    expect_the_scenes_view_at(320, 240);  // the photo's size: it fits the window's view
  }

  // A folder `relight analyze` made is used as it is, with no analysis run;
  // one for other inputs is refused with a message naming it, and the open
  // scene stays.
  void an_analysis_folder_given_is_used_and_a_stale_one_refused() {
    const fs::path copy = folder_.path().toStdString();
    const fs::path given = copy / "given_analysis";
    fs::remove_all(given);
    fs::copy(copy / "scene.analysis", given);
    QSignalSpy opened(window_.get(), &MainWindow::sceneOpened);
    window_->open_scene(scene_, {}, QString::fromStdString(given.string()));
    QVERIFY(opened.wait(60000));
    QVERIFY(document().studio_scene().from_cache);
    QCOMPARE(document().studio_scene().analysis_folder, given);
    QVERIFY(window_->statusBar()->currentMessage().contains("given_analysis"));

    nlohmann::json meta = nlohmann::json::parse(std::ifstream(given / "analysis.json"));
    meta["seed"] = meta["seed"].get<int>() + 1;  // another analysis's settings: stale for this scene
    std::ofstream(given / "analysis.json") << meta.dump(2);
    QSignalSpy failed(window_.get(), &MainWindow::openFailed);
    window_->open_scene(scene_, {}, QString::fromStdString(given.string()));
    QVERIFY(failed.wait(60000));
    QVERIFY(failed.at(0).at(0).toString().contains("analysis is stale"));
    QVERIFY(failed.at(0).at(0).toString().contains("given_analysis"));
    QCOMPARE(document().light_count(), 1);  // the open scene stays
  }

  void a_missing_scene_is_a_message_naming_it() {
    QSignalSpy failed(window_.get(), &MainWindow::openFailed);
    window_->open_scene(folder_.filePath("nowhere.json"));
    QVERIFY(failed.wait(60000));
    QVERIFY(failed.at(0).at(0).toString().contains("nowhere.json"));
    QCOMPARE(document().light_count(), 1);  // the open scene stays
  }

  void the_display_encodes_like_a_png_export() {
    // A ramp over [-0.1, 1.2) through +1 stop: 8-bit sRGB as write_png does it.
    Image ramp(4096, 1);
    for (int x = 0; x < ramp.width; ++x) ramp.at(x, 0) = Vec3::Constant(-0.1f + 1.3f * float(x) / ramp.width);
    const QImage shown = to_qimage(ramp, 1.0f);
    for (int x = 0; x < ramp.width; ++x) {
      const float v = std::clamp(2.0f * ramp.at(x, 0).x(), 0.0f, 1.0f);
      QCOMPARE(qRed(shown.pixel(x, 0)), int(std::lround(255.0f * srgb_encode(v))));
    }
    QCOMPARE(colour_hex(Vec3(1.0f, srgb_decode(128.0f / 255.0f), 0.0f)), QStringLiteral("#ff8000"));
    // Every decade from 1e-6 to 2, finely: the code rounded, but for values
    // within a hair of a code's boundary (where float rounding picks a side).
    Image sweep(1 << 20, 1);
    for (int x = 0; x < sweep.width; ++x)
      sweep.at(x, 0) = Vec3::Constant(1e-6f * std::pow(2e6f, float(x) / float(sweep.width - 1)));
    const QImage swept = to_qimage(sweep, 0.0f);
    int off = 0;
    for (int x = 0; x < sweep.width; ++x) {
      const float encoded = 255.0f * srgb_encode(std::min(sweep.at(x, 0).x(), 1.0f));
      const bool on_boundary = std::abs(encoded - std::floor(encoded) - 0.5f) < 1e-3f;
      off += !on_boundary && qRed(swept.pixel(x, 0)) != int(std::lround(encoded));
    }
    QCOMPARE(off, 0);
    const float odd[] = {std::numeric_limits<float>::quiet_NaN(), -1.0f, -0.0f, std::numeric_limits<float>::infinity()};
    Image odd_values(4, 1);
    for (int x = 0; x < 4; ++x) odd_values.at(x, 0) = Vec3::Constant(odd[x]);
    const QImage odd_shown = to_qimage(odd_values, 0.0f);
    QCOMPARE(qRed(odd_shown.pixel(0, 0)), 0);
    QCOMPARE(qRed(odd_shown.pixel(1, 0)), 0);
    QCOMPARE(qRed(odd_shown.pixel(2, 0)), 0);
    QCOMPARE(qRed(odd_shown.pixel(3, 0)), 255);
  }

  void cancelling_the_analysis_keeps_the_open_scene() {
    const fs::path other = fs::path(folder_.path().toStdString()) / "other";
    fs::create_directories(other);
    for (const char* f : {"scene.json", "photo.exr", "geometry.obj"})
      fs::copy_file(fs::path(folder_.path().toStdString()) / f, other / f);
    QSignalSpy failed(window_.get(), &MainWindow::openFailed);
    window_->open_scene(QString::fromStdString((other / "scene.json").string()));
    QVERIFY(window_->busy());
    window_->cancel_task();
    QVERIFY(failed.wait(240000));
    QCOMPARE(failed.at(0).at(0).toString(), QStringLiteral("cancelled"));
    QVERIFY(!fs::exists(other / "scene.analysis"));
    QVERIFY(!window_->busy());
    QCOMPARE(document().light(0).name, std::string("lamp"));
  }

  // A photo over preview_above_pixels opens with a preview analysis; the
  // full one runs meanwhile and takes its place, the lights moved meanwhile
  // kept, and is what the cache keeps.
  void a_large_photo_opens_with_a_preview_and_the_full_analysis_keeps_its_edits() {
    StudioOptions options = quick_options();
    options.preview_above_pixels = 1;  // the test scene's photo counts as large
    options.max_view_width = 160;      // and is wider than the view (320x240)
    window_ = std::make_unique<MainWindow>(options);
    const fs::path other = fs::path(folder_.path().toStdString()) / "large";
    fs::remove_all(other);
    fs::create_directories(other);
    for (const char* f : {"scene.json", "photo.exr", "geometry.obj"})
      fs::copy_file(fs::path(folder_.path().toStdString()) / f, other / f);
    QSignalSpy opened(window_.get(), &MainWindow::sceneOpened);
    QSignalSpy full(window_.get(), &MainWindow::fullAnalysisDone);
    window_->open_scene(QString::fromStdString((other / "scene.json").string()));
    QVERIFY(opened.wait(240000));
    QVERIFY(document().studio_scene().preview);
    QCOMPARE(document().studio_scene().analysed->analysis().options.paths_per_pixel, 4);  // 4 / 8, at least 4
    QCOMPARE(document().studio_scene().analysed->analysis().options.gbuffer_samples, 1);
    QVERIFY(window_->busy());  // the full analysis
    expect_the_scenes_view_at(160, 120);
    const Light start = document().light(0);
    Light moved = start;
    moved.position += Vec3(0.1f, 0.0f, 0.0f);
    window_->change_light(0, moved);
    const LightingDocument* edited = &document();
    QVERIFY(full.wait(240000));
    QCOMPARE(full.at(0).at(0).toString(), QString());
    QVERIFY(!document().studio_scene().preview);
    QCOMPARE(document().studio_scene().analysed->analysis().options.gbuffer_samples, 9);
    QCOMPARE(&document(), edited);  // the same design, its views and history
    expect_the_scenes_view_at(160, 120);
    expect_same_light(document().light(0), moved);
    expect_same_light(document().session().rig().lights[0], moved);
    // The edit made on the preview is undone on the full analysis.
    QCOMPARE(window_->undo_stack().count(), 1);
    window_->undo_stack().undo();
    expect_same_light(document().light(0), start);
    expect_same_light(document().session().rig().lights[0], start);
    QVERIFY(fs::exists(other / "scene.analysis" / "analysis.json"));
    QVERIFY(!window_->busy());
  }

  void saved_rigs_are_remembered_as_recent() {
    StudioOptions options = quick_options();
    options.remember_recent = true;
    window_ = std::make_unique<MainWindow>(options);
    QSignalSpy opened(window_.get(), &MainWindow::sceneOpened);
    window_->open_scene(scene_);
    QVERIFY(opened.wait(240000));
    const QString first = folder_.filePath("first.json"), second = folder_.filePath("second.json");
    QVERIFY(window_->save_rig(first));
    QVERIFY(window_->save_rig(second));
    QVERIFY(window_->save_rig(first));
    QCOMPARE(QSettings().value("recent_rigs").toStringList(), QStringList({first, second}));
    QCOMPARE(QSettings().value("recent_scenes").toStringList().value(0), QFileInfo(scene_).absoluteFilePath());
  }

  void the_program_reports_a_bad_scene_in_one_line() {
    QProcess studio;
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    env.insert("QT_QPA_PLATFORM", "offscreen");
    studio.setProcessEnvironment(env);
    studio.start(RELIGHT_STUDIO, {"--screenshot", folder_.filePath("shot.png"), folder_.filePath("nowhere.json")});
    QVERIFY(studio.waitForFinished(120000));
    QCOMPARE(studio.exitCode(), 2);
    const QStringList lines = QString::fromLocal8Bit(studio.readAllStandardError()).split('\n', Qt::SkipEmptyParts);
    QVERIFY(!lines.isEmpty());
    QVERIFY2(lines.last().startsWith("relight-studio: " + folder_.filePath("nowhere.json") + ": "),
             qPrintable(lines.last()));
    QVERIFY(!QFile::exists(folder_.filePath("shot.png")));
  }

  void closing_with_unsaved_changes_asks_first() {
    QTest::keyClick(&window_->geometry_view(), Qt::Key_Up);
    const Vec3 moved = document().light(0).position;
    // Answer the question the window asks (a modal message box) with `button`.
    const auto answer = [](QMessageBox::StandardButton button) {
      QTimer::singleShot(0, [button] {
        auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
        QVERIFY(box);
        QVERIFY(box->text().contains("not saved"));
        box->button(button)->click();
      });
    };
    answer(QMessageBox::Cancel);
    QVERIFY(!window_->close());
    QVERIFY(window_->isVisible());
    QVERIFY(document().light(0).position == moved);
    answer(QMessageBox::Discard);
    QVERIFY(window_->close());
  }

  void adding_a_light_and_undo() {
    Light spot;
    spot.type = LightType::spot;
    spot.name = "key";
    spot.position = Vec3(0.5f, -1.0f, 1.8f);
    spot.direction = Vec3(0.0f, 0.6f, -0.8f);
    spot.power = 400.0f;
    spot.spot_angle_deg = 35.0f;
    window_->add_light(spot);
    QCOMPARE(document().light_count(), 2);
    expect_same_light(document().light(1), spot);
    QCOMPARE(window_->selected_light(), 1);
    QCOMPARE(window_->light_model().rowCount(), 2);
    QCOMPARE(window_->light_model().data(window_->light_model().index(1), Qt::DisplayRole).toString(),
             QStringLiteral("key \u2014 spot, 400 W"));
    window_->undo_stack().undo();
    QCOMPARE(document().light_count(), 1);
    QCOMPARE(document().session().rig().lights.size(), size_t(1));
    window_->undo_stack().redo();
    expect_same_light(document().light(1), spot);
    QCOMPARE(document().session().rig().lights.size(), size_t(2));
  }

  void the_dialog_keeps_untouched_values_and_takes_edits() {
    const Light lamp = document().light(0);  // colour (1, 0.9, 0.75): not exact in hex
    LightDialog dialog;
    dialog.set_light(lamp);
    expect_same_light(dialog.light(), lamp);
    dialog.findChild<QDoubleSpinBox*>("position_x")->setValue(1.5);
    dialog.findChild<QLineEdit*>("colour")->setText("#ff8000");
    dialog.findChild<QDoubleSpinBox*>("power")->setValue(320.0);
    const Light edited = dialog.light();
    EXPECT_EXACT(edited.position.x(), 1.5f);
    EXPECT_EXACT(edited.position.y(), lamp.position.y());
    EXPECT_EXACT(edited.position.z(), lamp.position.z());
    EXPECT_EXACT(edited.color.x(), 1.0f);
    EXPECT_EXACT(edited.color.y(), srgb_decode(128.0f / 255.0f));
    EXPECT_EXACT(edited.color.z(), 0.0f);
    EXPECT_EXACT(edited.power, 320.0f);
    EXPECT_EXACT(edited.radius, lamp.radius);
    QVERIFY(dialog.validation_error().isEmpty());

    window_->change_light(0, edited);
    expect_same_light(document().light(0), edited);
    window_->undo_stack().undo();
    expect_same_light(document().light(0), lamp);
  }

  void the_dialog_explains_what_is_wrong() {
    LightDialog dialog;
    Light area;
    area.type = LightType::area;
    area.name = "softbox";
    area.direction = Vec3(0, 1, 0);
    dialog.set_light(area);
    QVERIFY(dialog.validation_error().isEmpty());
    keep_picture("light_dialog_area", dialog);
    auto* ok = dialog.findChildren<QPushButton*>().first();
    dialog.findChild<QLineEdit*>("colour")->setText("#12zz45");
    QVERIFY(dialog.validation_error().startsWith("Colour: \u201c#12zz45\u201d is not a colour"));
    QVERIFY(!ok->isEnabled());
    keep_picture("light_dialog_error", dialog);
    dialog.findChild<QLineEdit*>("colour")->setText("#123456");
    dialog.findChild<QDoubleSpinBox*>("width")->setValue(0.0);
    QVERIFY(dialog.validation_error().startsWith("Area size"));
    dialog.findChild<QDoubleSpinBox*>("width")->setValue(0.5);
    dialog.findChild<QDoubleSpinBox*>("direction_y")->setValue(0.0);
    QVERIFY(dialog.validation_error().startsWith("Direction: must not be zero"));
    dialog.findChild<QDoubleSpinBox*>("direction_z")->setValue(1.0);  // along up (0, 0, 1)
    QVERIFY(dialog.validation_error().startsWith("Direction: an area light must not point along its up axis"));
    dialog.findChild<QDoubleSpinBox*>("direction_z")->setValue(-1.0);
    dialog.findChild<QDoubleSpinBox*>("direction_y")->setValue(1.0);
    dialog.findChild<QLineEdit*>("description")->setText("  ");
    QVERIFY(dialog.validation_error().startsWith("Description"));
  }

  void keys_move_the_selected_light_by_exact_steps() {
    GeometryView& view = window_->geometry_view();
    view.setFocus();
    const Light start = document().light(0);
    const GeometryView::MoveFrame f = view.move_frame();
    const float step = view.move_step();
    EXPECT_EXACT(step, 0.05f);  // the room is 4 x 4 x 2.5 m: about 6 cm, rounded to 5 cm
    QVERIFY(std::abs(f.right.dot(f.up)) < 1e-6f);
    QVERIFY(std::abs(f.forward.dot(f.up)) < 1e-6f);

    Vec3 expected = start.position;
    const auto press = [&](Qt::Key key, Qt::KeyboardModifiers modifiers, const Vec3& delta) {
      QTest::keyClick(&view, key, modifiers);
      expected += delta;
      const Vec3 p = document().light(0).position;
      EXPECT_EXACT(p.x(), expected.x());
      EXPECT_EXACT(p.y(), expected.y());
      EXPECT_EXACT(p.z(), expected.z());
    };
    press(Qt::Key_Right, Qt::NoModifier, Vec3(step * f.right));
    press(Qt::Key_Left, Qt::NoModifier, Vec3(-step * f.right));
    press(Qt::Key_Up, Qt::NoModifier, Vec3(step * f.up));
    press(Qt::Key_Down, Qt::ShiftModifier, Vec3(-10.0f * step * f.up));
    press(Qt::Key_Home, Qt::NoModifier, Vec3(step * f.forward));
    press(Qt::Key_End, Qt::ShiftModifier, Vec3(-10.0f * step * f.forward));
    EXPECT_EXACT(document().session().rig().lights[0].position.z(), expected.z());

    // A run of key moves of one light is one undo step, back to the exact start.
    QCOMPARE(window_->undo_stack().count(), 1);
    window_->undo_stack().undo();
    expect_same_light(document().light(0), start);
  }

  void the_eye_switches_a_light_off_and_on() {
    LightListModel& model = window_->light_model();
    QVERIFY(model.flags(model.index(0)) & Qt::ItemIsUserCheckable);
    QCOMPARE(model.data(model.index(0), Qt::CheckStateRole).toInt(), int(Qt::Checked));
    QVERIFY(model.setData(model.index(0), Qt::Unchecked, Qt::CheckStateRole));
    QVERIFY(!document().light(0).enabled);
    QVERIFY(!document().session().rig().lights[0].enabled);
    QCOMPARE(model.data(model.index(0), Qt::CheckStateRole).toInt(), int(Qt::Unchecked));
    window_->undo_stack().undo();
    QVERIFY(document().light(0).enabled);
    QCOMPARE(model.data(model.index(0), Qt::CheckStateRole).toInt(), int(Qt::Checked));
  }

  void clicking_the_eye_icon_toggles_the_light() {
    auto* list = window_->findChild<QListView*>("light_list");
    QVERIFY(list);
    const auto* eye = qobject_cast<const EyeToggleDelegate*>(list->itemDelegate());
    QVERIFY(eye);
    const QModelIndex row = list->model()->index(0, 0);
    const QRect icon = eye->eye_rect(*list, row);
    QVERIFY(!icon.isEmpty());
    QVERIFY(document().light(0).enabled);
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {}, icon.center());
    QVERIFY(!document().light(0).enabled);
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {}, icon.center());
    QVERIFY(document().light(0).enabled);
    // Beside the eye and the checkbox (on the name) a click selects, and switches nothing.
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {}, QPoint(icon.right() + 60, icon.center().y()));
    QVERIFY(document().light(0).enabled);
    QCOMPARE(window_->undo_stack().count(), 2);
  }

  void delete_key_deletes_and_undo_puts_it_back_in_place() {
    QVERIFY(window_->open_rig(evening_));
    const Rig rig = document().rig();
    QCOMPARE(rig.lights.size(), size_t(2));
    RelightSession& session = document().session();
    session.wait_for_edit(session.last_edit());
    const uint64_t renders = session.stats().interactive_renders;
    window_->select_light(0);
    QTest::keyClick(&window_->geometry_view(), Qt::Key_Delete);
    QCOMPARE(document().light_count(), 1);
    QCOMPARE(document().light(0).name, std::string("cool spot"));
    QCOMPARE(window_->selected_light(), 0);
    window_->undo_stack().undo();
    QCOMPARE(document().light_count(), 2);
    // Only the light put back is rendered; the one behind it keeps its image.
    session.wait_for_edit(session.last_edit());
    QCOMPARE(session.stats().interactive_renders, renders + 1);
    expect_same_light(document().light(0), rig.lights[0]);
    expect_same_light(document().light(1), rig.lights[1]);
    const Rig session_rig = document().session().rig();
    QCOMPARE(session_rig.lights[0].name, std::string("lamp"));
    QCOMPARE(session_rig.lights[1].name, std::string("cool spot"));
  }

  void opening_a_rig_keeps_the_images_of_lights_that_did_not_move() {
    QVERIFY(window_->open_rig(evening_));
    RelightSession& session = document().session();
    session.wait_until_converged();
    const SessionStats before = session.stats();
    QVERIFY(window_->open_rig(evening_));
    QCOMPARE(&document().session(), &session);
    session.wait_until_converged();
    // Nothing moved: only the final render is made again.
    QCOMPARE(session.stats().interactive_renders, before.interactive_renders);
    QCOMPARE(session.stats().refinements, before.refinements + 1);
  }

  void a_rig_saves_and_loads_back_the_same() {
    QVERIFY(window_->open_rig(evening_));
    window_->select_light(1);
    QTest::keyClick(&window_->geometry_view(), Qt::Key_Up);
    QVERIFY(!window_->undo_stack().isClean());
    const Rig edited = document().rig();
    const QString path = folder_.filePath("saved.json");
    QVERIFY(window_->save_rig(path));
    QVERIFY(window_->undo_stack().isClean());
    QCOMPARE(window_->rig_path(), path);
    QFile file(path);
    QVERIFY(file.open(QIODevice::ReadOnly));
    QCOMPARE(file.readAll().toStdString(), rig_to_json(edited));

    window_->undo_stack().undo();  // away from what was saved
    QVERIFY(window_->open_rig(path));
    QCOMPARE(rig_to_json(document().rig()), rig_to_json(edited));
    expect_same_light(document().light(1), edited.lights[1]);
    EXPECT_EXACT(document().rig().environment_scale, edited.environment_scale);
    QVERIFY(!window_->open_rig(folder_.filePath("scene.json")));
    QVERIFY(window_->last_error().contains("scene.json"));
  }

  // An animated rig's lights are edited as the rig gives them outside their
  // keys: the list and the status bar say so, and a saved rig keeps the keys.
  void an_animated_rig_is_edited_outside_its_keys_and_saved_with_them() {
    Rig animated = load_rig(evening_.toStdString());
    LightKey first, last;
    first.frame = 1;
    first.power = 10.0f;
    last.frame = 24;
    last.power = 90.0f;
    animated.lights[0].keys = {first, last};
    const QString path = folder_.filePath("animated.json");
    std::ofstream(path.toStdString()) << rig_to_json(animated);
    QVERIFY(window_->open_rig(path));
    QVERIFY(window_->statusBar()->currentMessage().contains("1 of the rig's lights animated"));
    const QString row = window_->light_model().data(window_->light_model().index(0), Qt::DisplayRole).toString();
    QVERIFY2(row.endsWith("animated (2 keys)"), qPrintable(row));
    window_->select_light(0);
    QTest::keyClick(&window_->geometry_view(), Qt::Key_Up);
    const QString saved = folder_.filePath("animated_saved.json");
    QVERIFY(window_->save_rig(saved));
    const Rig back = load_rig(saved.toStdString());
    QCOMPARE(back.lights[0].keys.size(), size_t(2));
    EXPECT_EXACT(*back.lights[0].keys[1].power, 90.0f);
    EXPECT_EXACT(back.lights[0].position.z(), document().light(0).position.z());
  }

  // Undoing every edit made since a save is back at the saved rig: the
  // window says so. A run of key moves that a save interrupts is two undo
  // steps, so that undo can stop at what was saved.
  void undo_back_to_the_saved_rig_is_saved() {
    QVERIFY(window_->open_rig(evening_));
    window_->select_light(1);
    GeometryView& view = window_->geometry_view();
    QTest::keyClick(&view, Qt::Key_Up);
    QVERIFY(window_->save_rig(folder_.filePath("clean.json")));
    const Rig saved = document().rig();
    QVERIFY(!window_->isWindowModified());

    QTest::keyClick(&view, Qt::Key_Up);  // the same light, the same kind of move as the saved one
    QTest::keyClick(&view, Qt::Key_Right);
    drag_in_geometry_view(dot_of(1), QPoint(30, -20));
    Light typed = document().light(1);
    typed.radius = 0.1f;
    window_->change_light(1, typed);
    window_->findChild<QDoubleSpinBox*>("stops")->setValue(1.0);
    window_->findChild<QDoubleSpinBox*>("temperature")->setValue(3000.0);
    QVERIFY(window_->isWindowModified());
    QVERIFY(document().light(1).position != saved.lights[1].position);

    // The saved move, the two keys (one step), the drag, the dialog, the stops, the temperature.
    QCOMPARE(window_->undo_stack().index(), 6);
    for (int i = 0; i < 5; ++i) window_->undo_stack().undo();
    QVERIFY(window_->undo_stack().isClean());
    QVERIFY(!window_->isWindowModified());
    QCOMPARE(rig_to_json(document().rig()), rig_to_json(saved));
    window_->undo_stack().undo();  // past the save: changed again
    QVERIFY(window_->isWindowModified());
    window_->undo_stack().redo();
    QVERIFY(!window_->isWindowModified());
  }

  // A drag on the sky strip turns the new sky (the strip's width a full
  // turn, the sky following the mouse) in one undo step, and the picture
  // follows; undo is the saved rig again, byte for byte. The turn field's
  // steps are one step, the eye switches the sky off, Save writes the turn
  // with the image's path relative to the rig.
  void dragging_the_sky_strip_turns_it_and_undo_is_the_saved_rig() {
    QVERIFY(window_->open_rig(sky_rig_));
    const std::string saved = rig_to_json(document().rig(), folder_.path().toStdString());
    QVERIFY(saved.find("\"skies/sky.exr\"") != std::string::npos);
    auto* strip = window_->findChild<SkyStrip*>("environment_strip");
    QVERIFY(strip && strip->isVisible() && strip->isEnabled());
    QCOMPARE(window_->findChild<QLabel*>("environment_name")->text(), QStringLiteral("sky.exr"));
    keep_picture("environment_entry", lights_environment());
    const Image before = *document().session().wait_for_edit(document().session().last_edit()).image;

    const QPoint at(strip->width() / 2, strip->height() / 2), by(strip->width() / 4, 0);
    const auto send = [&](QEvent::Type type, QPoint p, Qt::MouseButtons buttons) {
      QMouseEvent event(type, p, strip->mapToGlobal(p), Qt::LeftButton, buttons, Qt::NoModifier);
      QApplication::sendEvent(strip, &event);
    };
    send(QEvent::MouseButtonPress, at, Qt::LeftButton);
    send(QEvent::MouseMove, at + by / 2, Qt::LeftButton);
    send(QEvent::MouseMove, at + by, Qt::LeftButton);
    send(QEvent::MouseButtonRelease, at + by, Qt::NoButton);
    const float expected = -360.0f * float(by.x()) / float(strip->width());  // dragged right: clockwise
    QVERIFY(std::abs(document().sky().turn_deg - expected) < 1e-4f);
    QCOMPARE(window_->undo_stack().index(), 1);
    QCOMPARE(window_->undo_stack().text(0), QStringLiteral("Drag the sky"));
    const float t = expected * kPi / 180.0f;
    const Vec3 forward = document().rig().environment->image->forward;
    QVERIFY2((forward - Vec3(std::cos(t), std::sin(t), 0.0f)).norm() < 1e-5f, qPrintable(QString::number(forward.y())));
    QCOMPARE(document().session().rig().environment->image, document().rig().environment->image);
    const Image turned = *document().session().wait_for_edit(document().session().last_edit()).image;
    double change = 0.0;
    for (size_t i = 0; i < turned.size(); ++i) change += (turned.pixels[i] - before.pixels[i]).cwiseAbs().sum();
    std::printf("[ figures  ] studio: the sky dragged %.1f degrees changes the picture by %.4f per pixel\n",
                double(expected), change / double(turned.size()));
    QVERIFY(change / double(turned.size()) > 1e-3);

    window_->undo_stack().undo();
    QVERIFY(window_->undo_stack().isClean());
    EXPECT_EXACT(document().sky().turn_deg, 0.0f);
    QCOMPARE(rig_to_json(document().rig(), folder_.path().toStdString()), saved);
    QCOMPARE(strip->turn_deg(), 0.0f);

    auto* turn = window_->findChild<QDoubleSpinBox*>("environment_turn");
    turn->setValue(40.0);
    turn->setValue(45.0);
    QCOMPARE(window_->undo_stack().index(), 1);  // one step
    EXPECT_EXACT(document().sky().turn_deg, 45.0f);
    const QString path = folder_.filePath("turned.json");
    QVERIFY(window_->save_rig(path));
    const Rig reloaded = load_rig(path.toStdString());
    QVERIFY(reloaded.environment && reloaded.environment->image);
    QCOMPARE(reloaded.environment->image->path, (fs::path(folder_.path().toStdString()) / "skies/sky.exr").string());
    QVERIFY((reloaded.environment->image->forward - Vec3(std::cos(kPi / 4), std::sin(kPi / 4), 0)).norm() < 1e-5f);

    window_->findChild<QToolButton*>("environment_eye")->click();
    QVERIFY(!document().rig().environment);
    QVERIFY(!document().session().rig().environment);
    QVERIFY(window_->findChild<QLabel*>("environment_name")->text().endsWith("(off)"));
    window_->undo_stack().undo();
    QVERIFY(document().rig().environment);

    QVERIFY(!window_->open_sky(folder_.filePath("scene.json")));
    QVERIFY(window_->last_error().contains("scene.json"));
    QVERIFY(window_->open_sky(folder_.filePath("skies/sky.exr")));
    EXPECT_EXACT(document().sky().turn_deg, 0.0f);
  }

  void a_temperature_gives_a_blackbody_colour() {
    const Vec3 daylight = colour_from_temperature(6500.0f, 0.0f);
    QVERIFY2(daylight.minCoeff() > 0.93f && daylight.maxCoeff() == 1.0f,
             qPrintable(colour_hex(daylight)));  // near white: D65 sits close to the locus there
    const Vec3 warm = colour_from_temperature(2700.0f, 0.0f);
    QVERIFY(warm.x() == 1.0f && warm.x() > warm.y() && warm.y() > warm.z());
    QVERIFY(warm.y() < 0.6f && warm.z() < 0.2f);
    const Vec3 cool = colour_from_temperature(12000.0f, 0.0f);
    QVERIFY(cool.z() == 1.0f && cool.z() > cool.y() && cool.y() > cool.x());
    // Tint: + towards green, - towards magenta.
    const auto greenness = [](const Vec3& c) { return c.y() / (c.x() + c.z()); };
    QVERIFY(greenness(colour_from_temperature(5000.0f, 0.02f)) > greenness(colour_from_temperature(5000.0f, 0.0f)));
    QVERIFY(greenness(colour_from_temperature(5000.0f, -0.02f)) < greenness(colour_from_temperature(5000.0f, 0.0f)));
    // Back from a colour: the temperature and tint it was made with, and
    // white is D65's (6504 K, Duv +0.0032).
    const auto back = temperature_of_colour(colour_from_temperature(3200.0f, 0.01f));
    QVERIFY(back && std::abs(back->kelvin - 3200.0f) < 2.0f && std::abs(back->tint - 0.01f) < 1e-4f);
    const auto white = temperature_of_colour(Vec3::Ones());
    QVERIFY(white && std::abs(white->kelvin - 6504.0f) < 10.0f && std::abs(white->tint - 0.0032f) < 3e-4f);
    QVERIFY(!temperature_of_colour(Vec3::Zero()));
  }

  // Typing a temperature and tint in the selected light's details sets its
  // colour (one undo step) and the rig saves it; a temperature out of range
  // is set to the nearest end of it.
  void the_temperature_field_sets_the_colour_saved_in_the_rig() {
    QVERIFY(window_->open_rig(evening_));
    const Rig opened = document().rig();
    window_->select_light(1);
    window_->select_light(0);
    QCOMPARE(window_->undo_stack().count(), 0);  // showing a colour as a temperature changes nothing
    auto* kelvin = window_->findChild<QDoubleSpinBox*>("temperature");
    auto* tint = window_->findChild<QDoubleSpinBox*>("tint");
    QVERIFY(kelvin && tint && kelvin->isEnabled());
    tint->setValue(0.0);
    kelvin->setValue(2700.0);
    expect_same_light(document().light(1), opened.lights[1]);
    const Vec3 warm = colour_from_temperature(2700.0f, 0.0f);
    for (int i = 0; i < 3; ++i) EXPECT_EXACT(document().light(0).color[i], warm[i]);
    QCOMPARE(window_->undo_stack().count(), 1);
    QCOMPARE(window_->undo_stack().undoText(), QStringLiteral("Colour temperature"));
    QCOMPARE(int(std::lround(kelvin->value())), 2700);
    keep_picture("temperature", *window_);

    const QString path = folder_.filePath("warm.json");
    QVERIFY(window_->save_rig(path));
    const Rig saved = load_rig(path.toStdString());
    for (int i = 0; i < 3; ++i) {
      EXPECT_EXACT(saved.lights[0].color[i], warm[i]);
      EXPECT_EXACT(saved.lights[1].color[i], opened.lights[1].color[i]);  // as typed, untouched
    }

    kelvin->setFocus();  // Enter in the geometry view would open Change…
    kelvin->selectAll();
    QTest::keyClicks(kelvin, "500");
    QTest::keyClick(kelvin, Qt::Key_Return);
    QCOMPARE(kelvin->value(), double(kMinKelvin));
    const Vec3 coolest = colour_from_temperature(kMinKelvin, 0.0f);
    for (int i = 0; i < 3; ++i) EXPECT_EXACT(document().light(0).color[i], coolest[i]);
    QCOMPARE(window_->undo_stack().count(), 2);  // the save ended the run
    window_->undo_stack().undo();
    window_->undo_stack().undo();
    for (int i = 0; i < 3; ++i) EXPECT_EXACT(document().light(0).color[i], opened.lights[0].color[i]);
  }

  // Stops: +1 doubles the power the light had when it was selected, typed
  // values count from it too, and a run of them is one undo step.
  void the_stops_field_doubles_the_power_per_stop() {
    QVERIFY(window_->open_rig(evening_));
    window_->select_light(1);
    const float start = document().light(1).power;  // 300 W
    auto* stops = window_->findChild<QDoubleSpinBox*>("stops");
    QVERIFY(stops && stops->isEnabled());
    QCOMPARE(stops->value(), 0.0);
    QCOMPARE(window_->findChild<QLabel*>("stops_reference")->text(), QStringLiteral("EV 0 = 300 W"));
    stops->stepUp();
    EXPECT_EXACT(document().light(1).power, 2.0f * start);
    stops->stepUp();
    EXPECT_EXACT(document().light(1).power, 4.0f * start);
    stops->setFocus();
    stops->selectAll();
    QTest::keyClicks(stops, "-1");
    QTest::keyClick(stops, Qt::Key_Return);
    EXPECT_EXACT(document().light(1).power, 0.5f * start);
    EXPECT_EXACT(document().session().rig().lights[1].power, 0.5f * start);
    QCOMPARE(window_->undo_stack().count(), 1);
    // Selected again, its power now is EV 0.
    window_->select_light(0);
    window_->select_light(1);
    QCOMPARE(stops->value(), 0.0);
    QCOMPARE(window_->findChild<QLabel*>("stops_reference")->text(), QStringLiteral("EV 0 = 150 W"));
    window_->undo_stack().undo();
    EXPECT_EXACT(document().light(1).power, start);
    QCOMPARE(stops->value(), 1.0);  // 300 W is a stop above EV 0
  }

  // Ctrl+D (or the list's right-click menu) adds a copy of the selected light
  // under a new name, selected, as one undo step.
  void duplicating_a_light_copies_it_under_a_new_name() {
    QVERIFY(window_->open_rig(evening_));
    const Light lamp = document().light(0);
    window_->select_light(0);
    QTest::keyClick(&window_->geometry_view(), Qt::Key_D, Qt::ControlModifier);
    QCOMPARE(document().light_count(), 3);
    QCOMPARE(window_->selected_light(), 2);
    Light expected = lamp;
    expected.name = "lamp copy";
    expect_same_light(document().light(2), expected);
    QCOMPARE(document().session().rig().lights.size(), size_t(3));
    QCOMPARE(window_->undo_stack().count(), 1);
    QCOMPARE(window_->undo_stack().undoText(), QStringLiteral("Duplicate light \u201clamp\u201d"));

    // From the list's menu: a copy of the copy, and another of the lamp, each a name of its own.
    auto* list = window_->findChild<QListView*>("light_list");
    QCOMPARE(list->contextMenuPolicy(), Qt::ActionsContextMenu);
    QAction* duplicate = nullptr;
    for (QAction* a : list->actions())
      if (a->text().remove('&').startsWith("Duplicate")) duplicate = a;
    QVERIFY(duplicate);
    duplicate->trigger();
    QCOMPARE(document().light(3).name, std::string("lamp copy 2"));
    window_->select_light(0);
    duplicate->trigger();
    QCOMPARE(document().light(4).name, std::string("lamp copy 3"));
    QCOMPARE(window_->selected_light(), 4);

    for (int i = 0; i < 3; ++i) window_->undo_stack().undo();
    QCOMPARE(document().light_count(), 2);
    QCOMPARE(document().session().rig().lights.size(), size_t(2));
    expect_same_light(document().light(0), lamp);
  }

  // Solo (Ctrl+L) draws one light alone and the others off, without
  // touching the rig: not an edit, saved as it was; again, it lights them.
  void solo_shows_one_light_alone_and_leaves_the_rig() {
    QVERIFY(window_->open_rig(evening_));
    const Rig rig = document().rig();
    show_converged_frame();
    const QImage both = window_->photo_view().displayed_image();
    window_->select_light(0);
    QTest::keyClick(&window_->geometry_view(), Qt::Key_L, Qt::ControlModifier);
    QCOMPARE(document().solo(), 0);
    const Rig shown = document().session().rig();
    QVERIFY(shown.lights[0].enabled && !shown.lights[1].enabled);
    QCOMPARE(rig_to_json(document().rig()), rig_to_json(rig));
    QCOMPARE(window_->undo_stack().count(), 0);
    QVERIFY(!window_->isWindowModified());
    LightListModel& model = window_->light_model();
    QVERIFY(model.data(model.index(0), Qt::DisplayRole).toString().endsWith("solo"));
    QVERIFY(model.data(model.index(1), Qt::ForegroundRole).isValid());  // greyed: off for now
    QCOMPARE(model.data(model.index(1), Qt::CheckStateRole).toInt(), int(Qt::Checked));  // its own switch

    show_converged_frame();
    keep_picture("solo", *window_);
    const QImage lamp_alone = window_->photo_view().displayed_image();
    QVERIFY(differing_pixels(lamp_alone, both) > 0);
    const QString path = folder_.filePath("solo.json");
    QVERIFY(window_->save_rig(path));
    QCOMPARE(rig_to_json(load_rig(path.toStdString())), rig_to_json(rig));

    // A switched-off light soloed is lit; un-solo puts every switch back.
    window_->set_light_enabled(1, false);
    window_->select_light(1);
    QTest::keyClick(&window_->geometry_view(), Qt::Key_L, Qt::ControlModifier);
    QCOMPARE(document().solo(), 1);
    QVERIFY(!document().session().rig().lights[0].enabled && document().session().rig().lights[1].enabled);
    QTest::keyClick(&window_->geometry_view(), Qt::Key_L, Qt::ControlModifier);
    QCOMPARE(document().solo(), -1);
    QVERIFY(document().session().rig().lights[0].enabled && !document().session().rig().lights[1].enabled);
    window_->undo_stack().undo();
    show_converged_frame();
    QCOMPARE(differing_pixels(window_->photo_view().displayed_image(), both), 0);

    // Ctrl+click on an eye solos its light, and again ends the solo; its switch stays.
    auto* list = window_->findChild<QListView*>("light_list");
    const auto* eye = qobject_cast<const EyeToggleDelegate*>(list->itemDelegate());
    const QPoint spot_eye = eye->eye_rect(*list, list->model()->index(1, 0)).center();
    QTest::mouseClick(list->viewport(), Qt::LeftButton, Qt::ControlModifier, spot_eye);
    QCOMPARE(document().solo(), 1);
    QTest::mouseClick(list->viewport(), Qt::LeftButton, Qt::ControlModifier, spot_eye);
    QCOMPARE(document().solo(), -1);
    QVERIFY(document().light(1).enabled);
    QCOMPARE(window_->undo_stack().count(), 1);  // only the switch undone above

    // A light added while one is soloed is off like the others; deleting the soloed light ends the solo.
    window_->solo_light(1);
    window_->duplicate_light(0);  // appended after it
    QCOMPARE(document().solo(), 1);
    QVERIFY(!document().session().rig().lights[2].enabled);
    window_->undo_stack().undo();
    window_->delete_light(1);
    QCOMPARE(document().solo(), -1);
    QVERIFY(document().session().rig().lights[0].enabled);
    window_->undo_stack().undo();
    QVERIFY(document().session().rig().lights[1].enabled);
  }

  void the_picture_changes_when_a_light_moves() {
    show_converged_frame();
    const QImage before = window_->photo_view().displayed_image();
    QCOMPARE(before.size(), QSize(320, 240));
    QCOMPARE(before, to_qimage(*window_->photo_view().relit(), window_->photo_view().exposure()));
    QTest::keyClick(&window_->geometry_view(), Qt::Key_Left, Qt::ShiftModifier);  // 50 cm
    show_converged_frame();
    const QImage after = window_->photo_view().displayed_image();
    // The lamp lights the whole room: most of the picture changes.
    QVERIFY2(differing_pixels(before, after) > before.width() * before.height() / 2,
             qPrintable(QString::number(differing_pixels(before, after))));
    // Renders are deterministic: undo brings back the very same picture.
    window_->undo_stack().undo();
    show_converged_frame();
    QCOMPARE(differing_pixels(window_->photo_view().displayed_image(), before), 0);
  }

  // The window shows each frame the session makes as it comes, nobody
  // asking for it: the moved lamp's first frame, then its converged one.
  void a_new_frame_is_shown_as_soon_as_it_is_made() {
    show_converged_frame();
    QTest::keyClick(&window_->geometry_view(), Qt::Key_Left, Qt::ShiftModifier);
    const Frame first = document().session().wait_for_edit(document().session().last_edit());
    QTRY_VERIFY_WITH_TIMEOUT(window_->photo_view().relit() == document().session().frame().image &&
                                 document().session().frame().edit >= first.edit,
                             60000);
    const Frame converged = document().session().wait_until_converged();
    QTRY_COMPARE_WITH_TIMEOUT(window_->photo_view().relit(), converged.image, 60000);
    window_->undo_stack().undo();
  }

  void the_split_shows_the_photo_left_and_the_relit_image_right() {
    show_converged_frame();
    PhotoView& view = window_->photo_view();
    view.set_exposure(1.0f);
    view.set_split(0.5);
    const QImage shown = view.displayed_image();
    const QImage photo = to_qimage(document().scene().photo, 1.0f);
    const QImage relit = to_qimage(*view.relit(), 1.0f);
    for (int y = 0; y < shown.height(); y += 7) {
      QCOMPARE(shown.pixel(159, y), photo.pixel(159, y));
      QCOMPARE(shown.pixel(160, y), relit.pixel(160, y));
    }
    QVERIFY(differing_pixels(photo, relit) > 0);
  }

  // The first view shows the lights and the camera; Frame Selected puts
  // the selected light in the middle, nearer; Frame All the whole geometry.
  // Labels of markers close together do not overlap: four at one point
  // take four sides, and each still touches its marker's neighbourhood.
  void labels_of_markers_close_together_do_not_overlap() {
    const std::vector<QPointF> anchors{{100, 100}, {100, 100}, {103, 101}, {100, 99}};
    const std::vector<QSizeF> sizes(4, QSizeF(60, 16));
    const std::vector<QRectF> boxes = place_labels(anchors, sizes);
    QCOMPARE(boxes.size(), size_t(4));
    for (size_t i = 0; i < boxes.size(); ++i) {
      QVERIFY(QLineF(boxes[i].center(), anchors[i]).length() < 60.0);
      for (size_t j = 0; j < i; ++j) QVERIFY(!boxes[i].intersects(boxes[j]));
    }
  }

  void the_views_frame_what_the_camera_sees_the_selected_light_and_all() {
    QVERIFY(window_->open_rig(evening_));
    GeometryView& view = window_->geometry_view();
    view.reset_orbit();
    const QRectF inside = QRectF(view.rect());
    for (int i = 0; i < document().light_count(); ++i) {
      const auto dot = view.project(view.marker_position(document().light(i)));
      QVERIFY(dot && inside.contains(*dot));
    }
    const auto camera = view.project(document().scene().camera.position());
    QVERIFY(camera && inside.contains(*camera));

    window_->select_light(1);
    const auto before = view.project(view.marker_position(document().light(1)));
    view.frame_selected();
    const auto framed = view.project(view.marker_position(document().light(1)));
    QVERIFY(framed.has_value());
    QVERIFY(QLineF(*framed, inside.center()).length() < 1.0);
    QVERIFY(QLineF(*before, inside.center()).length() > 1.0);
    QCOMPARE(window_->undo_stack().count(), 0);

    view.frame_all();
    const Eigen::AlignedBox3f bounds = document().scene().mesh.bounds();
    const auto middle = view.project(bounds.center());
    QVERIFY(middle && QLineF(*middle, inside.center()).length() < 1.0);
    for (int corner = 0; corner < 8; ++corner) {
      const auto c = view.project(bounds.corner(Eigen::AlignedBox3f::CornerType(corner)));
      QVERIFY(c && inside.contains(*c));
    }
  }

  void clicking_a_dot_selects_its_light_and_dragging_moves_it() {
    QVERIFY(window_->open_rig(evening_));
    GeometryView& view = window_->geometry_view();
    const auto dot = view.project(view.marker_position(document().light(1)));
    QVERIFY(dot.has_value());
    const QPoint at = dot->toPoint();
    QTest::mouseClick(&view, Qt::LeftButton, {}, at);
    QCOMPARE(window_->selected_light(), 1);

    const Light start = document().light(1);
    uint64_t moved_edit = 0;
    drag_in_geometry_view(at, QPoint(40, 0), [&] { moved_edit = document().session().last_edit(); });
    // The drop makes the drag one undo step but no new edit: it does not
    // cancel the render of where the drag left the light.
    QCOMPARE(document().session().last_edit(), moved_edit);
    QCOMPARE(window_->undo_stack().count(), 1);
    // Dragged sideways on screen: the light moved, and its dot with the mouse.
    const Vec3 moved = document().light(1).position;
    QVERIFY((moved - start.position).norm() > 0.05f);
    const auto new_dot = view.project(moved);
    QVERIFY(std::abs(new_dot->x() - (dot->x() + 40.0)) < 0.5);
    QVERIFY(std::abs(new_dot->y() - dot->y()) < 0.5);
    window_->undo_stack().undo();
    expect_same_light(document().light(1), start);
  }

  // Ctrl+click, or a click with the Place Light tool, puts the selected
  // light in front of the surface.
  void placing_a_light_from_the_photo_is_a_tool_or_ctrl_click() {
    show_converged_frame();
    PhotoView& view = window_->photo_view();
    const QPoint centre = view.rect().center();
    const auto pixel = view.image_position(centre);
    QVERIFY(pixel.has_value());
    const Camera& camera = document().session().view().camera();
    SurfacePoint hit;
    QVERIFY(document().studio_scene().analysed->rays().intersect(
        camera.position(), camera.ray_direction(float(pixel->x()), float(pixel->y())), hit));
    const auto expect_placed = [&] {
      const Vec3 offset = document().light(0).position - hit.position;
      // A fifth of the camera's distance out along the surface normal.
      QVERIFY(std::abs(offset.norm() - 0.2f * hit.distance) < 1e-4f);
      QVERIFY(offset.normalized().dot(hit.normal) > 0.9999f);
      QCOMPARE(window_->undo_stack().undoText(), QStringLiteral("Place light"));
    };
    QTest::mouseClick(&view, Qt::LeftButton, Qt::ControlModifier, centre);
    expect_placed();
    window_->undo_stack().undo();
    QCOMPARE(window_->undo_stack().index(), 0);

    QVERIFY(window_->mode_text().startsWith("Select"));
    window_->place_tool().trigger();
    QVERIFY(window_->mode_text().startsWith("Place"));
    QTest::mouseClick(&view, Qt::LeftButton, {}, centre);
    keep_picture("place_tool", *window_);
    expect_placed();
    window_->place_tool().trigger();
    QVERIFY(window_->mode_text().startsWith("Select"));
  }

  // A plain click on the photo (to focus the window, say) never moves a
  // light: on a light it selects it, elsewhere it does nothing.
  void a_plain_click_on_the_photo_selects_and_moves_nothing() {
    QVERIFY(window_->open_rig(evening_));
    show_converged_frame();
    PhotoView& view = window_->photo_view();
    const Camera& camera = document().session().view().camera();
    int shown = -1;
    Vec2 at = Vec2::Zero();
    for (int i = 0; i < document().light_count() && shown < 0; ++i)
      if (document().light(i).type != LightType::directional)
        if (const std::optional<Vec2> p = camera.project(document().light(i).position)) shown = i, at = *p;
    QVERIFY(shown >= 0);
    window_->select_light(-1);
    const std::string rig_before = rig_to_json(document().rig());
    const QPointF widget = view.widget_position(QPointF(at.x(), at.y()));
    QTest::mouseClick(&view, Qt::LeftButton, {}, widget.toPoint());
    QCOMPARE(window_->selected_light(), shown);
    QCOMPARE(window_->undo_stack().count(), 0);
    QCOMPARE(rig_to_json(document().rig()), rig_before);
    // Far from every light: nothing selected anew, nothing moved.
    window_->select_light(-1);
    QTest::mouseClick(&view, Qt::LeftButton, {}, QPoint(2, 2));
    QCOMPARE(window_->undo_stack().count(), 0);
    QCOMPARE(rig_to_json(document().rig()), rig_before);
  }

  // With a light soloed the export is that light's own picture: less light
  // than the whole rig's, all of it from the soloed light.
  void exporting_while_soloed_renders_that_light_alone() {
    QVERIFY(window_->open_rig(evening_));
    const auto exported = [&](const QString& name) {
      QSignalSpy done(window_.get(), &MainWindow::exportFinished);
      window_->export_image(folder_.filePath(name));
      [&] { QVERIFY(done.wait(240000)); }();
      return read_image(folder_.filePath(name).toStdString());
    };
    const auto total = [](const Image& image) {
      Vec3 sum = Vec3::Zero();
      for (const Vec3& p : image.pixels) sum += p;
      return sum;
    };
    const Vec3 both = total(exported("both.exr"));
    window_->solo_light(1);  // the cool spot: bluer than the warm lamp
    const Vec3 spot = total(exported("spot.exr"));
    window_->solo_light(-1);
    QVERIFY(spot.sum() < 0.8f * both.sum());
    QVERIFY(spot.z() / spot.x() > both.z() / both.x());
    QCOMPARE(total(exported("again.exr")), both);  // renders are deterministic
  }

  // The shapes' geometry: a spot's ring at its reach, of radius reach x
  // tan(angle/2), with four lines from the apex to it; an area light's
  // corners ±size/2 along its sides; a sun's arrow the way it shines.
  void light_shapes_have_the_lights_dimensions() {
    Light spot;
    spot.type = LightType::spot;
    spot.position = Vec3(1, 2, 3);
    spot.direction = Vec3(0, 2, 0);  // not unit: the shapes normalise it
    spot.spot_angle_deg = 50.0f;
    const Vec3 eye(5, -4, 6);
    std::vector<Polyline> lines = light_shape(spot, spot.position, eye, 2.0f);
    QCOMPARE(lines.size(), size_t(5));  // no radius: no circle
    const Vec3 centre(1, 4, 3);
    const float ring = 2.0f * std::tan(radians(25.0f));
    for (const Vec3& p : lines[0]) {
      QVERIFY(std::abs((p - centre).norm() - ring) < 1e-5f);
      QVERIFY(std::abs((p - centre).y()) < 1e-5f);
    }
    for (size_t i = 1; i < 5; ++i) {
      QCOMPARE(lines[i].size(), size_t(2));
      QVERIFY((lines[i][0] - spot.position).norm() < 1e-6f);
      QVERIFY(std::abs((lines[i][1] - centre).norm() - ring) < 1e-5f);
    }
    spot.radius = 0.25f;
    lines = light_shape(spot, spot.position, eye, 2.0f);
    QCOMPARE(lines.size(), size_t(6));
    for (const Vec3& p : lines[0]) {
      QVERIFY(std::abs((p - spot.position).norm() - 0.25f) < 1e-5f);
      QVERIFY(std::abs((p - spot.position).dot((eye - spot.position).normalized())) < 1e-5f);  // faces the eye
    }

    Light area;
    area.type = LightType::area;
    area.position = Vec3(0, 0, 2);
    area.direction = Vec3(0, 0, -1);
    area.up = Vec3(0, 1, 0);
    area.size = Vec2(2.0f, 0.5f);
    lines = light_shape(area, area.position, eye, 1.0f);
    QCOMPARE(lines.size(), size_t(3));  // the rectangle, the normal's shaft and its head
    // w = direction x up = (1, 0, 0), h = w x direction = (0, 1, 0).
    const std::vector<Vec3> corners = {{-1, -0.25f, 2}, {1, -0.25f, 2}, {1, 0.25f, 2}, {-1, 0.25f, 2}, {-1, -0.25f, 2}};
    QCOMPARE(lines[0].size(), corners.size());
    for (size_t i = 0; i < corners.size(); ++i) QVERIFY((lines[0][i] - corners[i]).norm() < 1e-6f);
    QVERIFY((lines[1][0] - area.position).norm() < 1e-6f);
    QVERIFY((lines[1][1] - Vec3(0, 0, 1)).norm() < 1e-6f);  // half the longer side along the normal

    Light sun;
    sun.type = LightType::directional;
    sun.direction = Vec3(0, 3, -4);
    lines = light_shape(sun, Vec3(1, 1, 1), eye, 10.0f);
    QCOMPARE(lines.size(), size_t(2));
    QVERIFY((lines[0][1] - Vec3(1, 7, -7)).norm() < 1e-5f);
    QVERIFY((lines[1][1] - lines[0][1]).norm() < 1e-6f);  // the head at the tip
  }

  // The photo shows the selected spot's cone in the selected colour where
  // the camera sees its end, and not with the shapes switched off.
  void the_photo_shows_a_spots_cone_where_the_camera_sees_it() {
    show_converged_frame();
    PhotoView& view = window_->photo_view();
    const Camera& camera = document().session().view().camera();
    Light spot = light_facing_the_middle_of_the_view(LightType::spot);
    spot.spot_angle_deg = 30.0f;
    document().set_light(0, spot);
    window_->select_light(0);
    const std::vector<Polyline> lines = light_shape(spot, spot.position, camera.position(),
                                                    aim_reach(document(), spot));
    const auto end = camera.project(lines[1][1]);  // where a line from the apex meets the ring
    QVERIFY(end.has_value());
    const QPointF at = view.widget_position(QPointF(end->x(), end->y()));
    QVERIFY(view.rect().contains(at.toPoint()));
    keep_picture("spot_cone", view);
    QVERIFY(shows_colour(view.grab().toImage(), at, light_colour(true, true)));
    view.set_shapes_shown(false);
    QVERIFY(!shows_colour(view.grab().toImage(), at, light_colour(true, true)));
  }

  // Dragging the selected lamp's dot on the photo moves it across the
  // surface under the cursor at its height above the surface below it, one
  // undo step; dragging a spot's aim square aims it at the surface there.
  void dragging_handles_on_the_photo_moves_and_aims_the_light() {
    show_converged_frame();
    PhotoView& view = window_->photo_view();
    window_->select_light(0);
    const Light start = document().light(0);
    const Camera& camera = document().session().view().camera();
    const RayScene& rays = document().studio_scene().analysed->rays();
    const Vec3 up = document().scene().camera.spec().up.normalized();
    const auto surface = [&](QPoint widget) {
      const auto pixel = view.image_position(widget);
      SurfacePoint hit;
      [&] {
        QVERIFY(pixel.has_value());
        QVERIFY(rays.intersect(camera.position(), camera.ray_direction(float(pixel->x()), float(pixel->y())), hit));
      }();
      return hit.position;
    };
    SurfacePoint below;
    QVERIFY(rays.intersect(start.position, -up, below));
    const auto dot = camera.project(start.position);
    QVERIFY(dot.has_value());
    const QPoint from = view.widget_position(QPointF(dot->x(), dot->y())).toPoint();
    const QPoint to = from + QPoint(-80, 60);
    drag_on_photo(from, to);
    const Vec3 expected = surface(to) + below.distance * up;
    QVERIFY2((document().light(0).position - expected).norm() < 1e-4f,
             qPrintable(QString("moved %1 m off").arg((document().light(0).position - expected).norm())));
    QVERIFY((document().light(0).position - start.position).norm() > 0.1f);
    QCOMPARE(window_->undo_stack().count(), 1);
    QCOMPARE(window_->undo_stack().undoText(), QStringLiteral("Drag light"));
    window_->undo_stack().undo();
    expect_same_light(document().light(0), start);

    Light spot = start;
    spot.type = LightType::spot;
    spot.direction = -up;
    document().set_light(0, spot);
    const auto aim = camera.project(spot.position + aim_reach(document(), spot) * spot.direction);
    QVERIFY(aim.has_value());
    const QPoint aim_from = view.widget_position(QPointF(aim->x(), aim->y())).toPoint();
    const QPoint aim_to = aim_from + QPoint(70, 30);
    drag_on_photo(aim_from, aim_to);
    const Vec3 towards = (surface(aim_to) - spot.position).normalized();
    QVERIFY((document().light(0).direction - towards).norm() < 1e-4f);
    QVERIFY((document().light(0).position - spot.position).norm() == 0.0f);  // aimed, not moved
  }

  // Dragging the selected spot's aim square in the geometry view aims it
  // through where the mouse is let go, without moving it; one undo step.
  void dragging_the_aim_square_in_the_geometry_view_aims_the_spot() {
    Light spot = document().light(0);
    spot.type = LightType::spot;
    spot.direction = Vec3(0.3f, 0.2f, -1.0f).normalized();
    document().set_light(0, spot);
    window_->select_light(0);
    GeometryView& view = window_->geometry_view();
    const auto aim = view.aim_point(spot);
    QVERIFY(aim.has_value());
    const auto square = view.project(*aim);
    QVERIFY(square.has_value());
    const QPoint by(25, -15);
    drag_in_geometry_view(square->toPoint(), by);
    const Light aimed = document().light(0);
    QVERIFY((aimed.position - spot.position).norm() == 0.0f);
    QVERIFY(aimed.direction.dot(spot.direction) < 0.999f);
    // The new aim, seen from the view, runs from the light through the release point.
    const auto apex = view.project(aimed.position);
    const auto along = view.project(aimed.position + 1e-3f * aimed.direction);
    QVERIFY(apex && along);
    const QPointF seen = *along - *apex, wanted = QPointF(square->toPoint() + by) - *apex;
    const double cross = (seen.x() * wanted.y() - seen.y() * wanted.x()) / std::hypot(seen.x(), seen.y());
    QVERIFY2(std::abs(cross) < 1.0, qPrintable(QString("%1 px off").arg(cross)));  // within a pixel of the line
    QVERIFY(seen.x() * wanted.x() + seen.y() * wanted.y() > 0.0);
    QCOMPARE(window_->undo_stack().undoText(), QStringLiteral("Drag light"));
    window_->undo_stack().undo();
    expect_same_light(document().light(0), spot);
  }

  // The geometry view draws an area light's rectangle with its corners
  // where light_shape puts them.
  void the_geometry_view_draws_an_area_lights_rectangle() {
    const Light area = selected_framed_area_light();
    GeometryView& view = window_->geometry_view();
    keep_picture("area_rectangle", view);
    const QImage image = view.grab().toImage();
    const Vec3 eye = view.eye_position();
    const std::vector<Polyline> lines = light_shape(area, area.position, eye, 1.0f);
    for (size_t i = 0; i < 4; ++i) {
      const auto corner = view.project(lines[0][i]);
      QVERIFY(corner.has_value());
      QVERIFY2(shows_colour(image, *corner, light_colour(true, true)), qPrintable(QString::number(i)));
    }
  }

  // Dragging a sun's marker in the geometry view turns the sun round the
  // scene: the marker follows the cursor, the sun shines from there through
  // the middle, and the drag is one undo step.
  void dragging_a_suns_marker_turns_it_round_the_scene() {
    Light sun = document().light(0);
    sun.type = LightType::directional;
    sun.irradiance = 2.0f;
    sun.direction = Vec3(0.3f, 0.2f, -1.0f).normalized();
    document().set_light(0, sun);
    window_->select_light(0);
    GeometryView& view = window_->geometry_view();
    const QPoint at = dot_of(0), by(30, 12);
    QVERIFY(view.rect().contains(at));
    const int steps = window_->undo_stack().count();
    drag_in_geometry_view(at, by);
    const Light turned = document().light(0);
    QVERIFY(turned.direction.dot(sun.direction) < 0.999f);
    QVERIFY(turned.direction.z() < 0.0f);  // still shining down
    const auto now = view.project(view.marker_position(turned));
    QVERIFY(now.has_value());
    QVERIFY2((*now - QPointF(at + by)).manhattanLength() < 2.0,
             qPrintable(QString("%1 %2").arg(now->x()).arg(now->y())));
    QCOMPARE(window_->undo_stack().count(), steps + 1);
    window_->undo_stack().undo();
    QVERIFY((document().light(0).direction - sun.direction).norm() < 1e-5f);
  }

  // On the photo too, the selected area light's circle turns it about its
  // normal towards where the cursor's ray meets the rectangle's plane.
  void dragging_an_area_lights_circle_on_the_photo_turns_it() {
    show_converged_frame();
    PhotoView& view = window_->photo_view();
    const Camera& camera = document().session().view().camera();
    Light area = light_facing_the_middle_of_the_view(LightType::area);
    area.size = Vec2(0.8f, 0.5f);
    area.up = Vec3(0, 0, 1);
    document().set_light(0, area);
    window_->select_light(0);
    const auto circle = camera.project(*turn_handle_point(area));
    QVERIFY(circle.has_value());
    const QPoint from = view.widget_position(QPointF(circle->x(), circle->y())).toPoint(), to = from + QPoint(40, 0);
    QVERIFY(view.rect().contains(from));
    const int steps = window_->undo_stack().count();
    drag_on_photo(from, to);
    keep_picture("area_turned_on_photo", view);
    const Light turned = document().light(0);
    const float degrees = std::acos(std::clamp(turned.up.normalized().dot(area_light_sides(area).h), -1.0f, 1.0f)) *
                          57.2958f;
    QVERIFY2(degrees > 5.0f, qPrintable(QString::number(degrees)));
    QVERIFY((turned.direction - area.direction).norm() < 1e-6f);
    QVERIFY((turned.position - area.position).norm() < 1e-6f);
    // The circle now lies on the picture's line from the light's middle
    // towards where the cursor let go (the plane's point there, seen).
    const auto now = camera.project(*turn_handle_point(turned)), middle = camera.project(turned.position);
    QVERIFY(now.has_value() && middle.has_value());
    const QPointF at = view.widget_position(QPointF(now->x(), now->y()));
    const QPointF centre = view.widget_position(QPointF(middle->x(), middle->y()));
    const QPointF a = at - centre, b = QPointF(to) - centre;
    const double sine = std::abs(a.x() * b.y() - a.y() * b.x()) / (std::hypot(a.x(), a.y()) * std::hypot(b.x(), b.y()));
    QVERIFY2(sine < 0.05 && a.x() * b.x() + a.y() * b.y() > 0.0, qPrintable(QString::number(sine)));
    QCOMPARE(window_->undo_stack().count(), steps + 1);
    window_->undo_stack().undo();
    QVERIFY((document().light(0).up - area.up).norm() < 1e-6f);
  }

  // View > Show the Geometry Over the Photo draws the model's edges as the
  // camera sees them over the picture, at the G-buffer's edge pixels, and
  // takes them away again.
  void the_geometry_over_the_photo_is_a_view_toggle() {
    show_converged_frame();
    PhotoView& view = window_->photo_view();
    const auto edge_pixels = [&] {
      const QImage image = view.grab().toImage();
      int n = 0;
      for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) n += image.pixelColor(x, y) == kGeometryEdgeColour;
      return n;
    };
    // Made when the scene opened, as they would be now.
    const QImage& edges = document().studio_scene().geometry_edges;
    QCOMPARE(edges, geometry_edges_image(document().studio_scene().session_view->gbuffer()));
    int marked = 0;
    for (int y = 0; y < edges.height(); ++y)
      for (int x = 0; x < edges.width(); ++x) marked += qAlpha(edges.pixel(x, y)) != 0;
    QVERIFY2(marked > 200, qPrintable(QString::number(marked)));  // the room's walls, floor, table meet
    QCOMPARE(edge_pixels(), 0);
    QAction* toggle = window_->findChild<QAction*>("show_geometry");
    QVERIFY(toggle);
    toggle->trigger();
    QVERIFY(view.geometry_shown());
    keep_picture("geometry_over_photo", view);
    QVERIFY2(edge_pixels() > marked / 2, qPrintable(QString("%1 of %2").arg(edge_pixels()).arg(marked)));
    toggle->trigger();
    QCOMPARE(edge_pixels(), 0);
  }

  // A photo opens at the exposure that shows it (its brightest 1 % white),
  // in the panel and the view; a photo 4 times as bright opens 2 stops lower.
  void the_photo_opens_at_an_exposure_that_shows_it() {
    const Image& photo = document().studio_scene().analysed->scene().photo;
    const float stops = display_exposure_for(photo);
    QCOMPARE(window_->findChild<QDoubleSpinBox*>("exposure")->value(), double(stops));
    QCOMPARE(window_->photo_view().exposure(), stops);
    Image brighter = photo;
    for (Vec3& p : brighter.pixels) p *= 4.0f;
    QCOMPARE(display_exposure_for(brighter), stops - 2.0f);
    QCOMPARE(display_exposure_for(Image(8, 6, Vec3(0.5f, 0.5f, 0.5f))), 1.0f);
    QCOMPARE(display_exposure_for(Image(8, 6, Vec3::Zero())), 0.0f);
  }

  // The selected area light's circle, at the middle of the rectangle's side
  // `up` points to, dragged turns the rectangle about its normal towards the
  // point dragged to: `up` follows, the aim stays, one undo step.
  void dragging_an_area_lights_circle_turns_it_about_its_normal() {
    const Light area = selected_framed_area_light();
    GeometryView& view = window_->geometry_view();
    const auto circle = view.project(*turn_handle_point(area));
    QVERIFY(circle.has_value());
    QVERIFY(shows_colour(view.grab().toImage(), *circle + QPointF(5, 0), light_colour(true, true)));
    const int steps = window_->undo_stack().count();
    drag_in_geometry_view(circle->toPoint(), QPoint(40, 0));
    const Light turned = document().light(0);
    const float degrees = std::acos(std::clamp(turned.up.normalized().dot(area.up), -1.0f, 1.0f)) * 57.2958f;
    QVERIFY2(degrees > 5.0f, qPrintable(QString::number(degrees)));
    QVERIFY(std::abs(turned.up.dot(turned.direction)) < 1e-4f);  // in the rectangle's plane
    QVERIFY((turned.direction - area.direction).norm() < 1e-6f);
    QVERIFY((turned.position - area.position).norm() < 1e-6f);
    // The circle moved the way the cursor did.
    const auto now = view.project(*turn_handle_point(turned));
    QVERIFY(now.has_value() && now->x() > circle->x() + 5.0);
    QCOMPARE(window_->undo_stack().count(), steps + 1);
    window_->undo_stack().undo();
    QVERIFY((document().light(0).up - area.up).norm() < 1e-6f);
  }

  // File > Find the Surfaces That Shine on the glossy studio without its
  // materials: the ball and the floor are found, the scene with them written beside (never
  // over the open one) and opened; on the matte room nothing is found and
  // nothing written.
  void finding_the_surfaces_that_shine_writes_and_opens_a_new_scene() {
    const fs::path copy = fs::path(folder_.path().toStdString()) / "glossy";
    fs::remove_all(copy);
    fs::copy(fs::path(RELIGHT_SOURCE_DIR) / "tests/data/glossy/glossy_studio", copy, fs::copy_options::recursive);
    nlohmann::json scene = nlohmann::json::parse(std::ifstream(copy / "scene.json"));
    scene.erase("materials");
    std::ofstream(copy / "scene.json") << scene.dump(2);
    const std::string original = file_text(copy / "scene.json");

    QSignalSpy found(window_.get(), &MainWindow::materialsFound);
    window_->find_materials(folder_.filePath("room_materials.json"));
    QVERIFY(found.wait(240000));
    QCOMPARE(found.at(0).at(0).toString(), QString());
    QCOMPARE(found.at(0).at(1).toInt(), 0);
    QVERIFY(!fs::exists(folder_.filePath("room_materials.json").toStdString()));

    QSignalSpy opened(window_.get(), &MainWindow::sceneOpened);
    window_->open_scene(QString::fromStdString((copy / "scene.json").string()));
    QVERIFY(opened.wait(240000));
    window_->find_materials(QString::fromStdString((copy / "scene.json").string()));
    QVERIFY(found.wait(1000) || found.size() == 2);
    QVERIFY(found.at(1).at(0).toString().contains("is the open scene"));

    const fs::path out = copy / "scene_materials.json";
    window_->find_materials(QString::fromStdString(out.string()));
    QVERIFY(found.wait(240000));
    QCOMPARE(found.at(2).at(0).toString(), QString());
    QVERIFY(found.at(2).at(1).toInt() >= 1);
    if (const auto boxes = window_->findChildren<QMessageBox*>(); !boxes.empty())
      keep_picture("materials_found", *boxes.back());
    QVERIFY(opened.wait(240000));
    keep_picture("materials_opened", *window_);
    const nlohmann::json written = nlohmann::json::parse(std::ifstream(out));
    QVERIFY(written["materials"].contains("ball"));
    QVERIFY(written["materials"].contains("floor"));
    QVERIFY(!written["materials"].contains("back_wall"));
    QCOMPARE(file_text(copy / "scene.json"), original);
    QVERIFY(!document().studio_scene().analysed->scene().gloss.all_matte());
  }

  // The example room with its camera turned 1 degree: the scene matched to
  // the photo has the camera back (registration) and is opened; the scene
  // it came from is unchanged, and it is never the output. Matched again,
  // the camera stays.
  void matching_the_scene_to_the_photo_writes_and_opens_it() {
    const fs::path copy = fs::path(folder_.path().toStdString()) / "turned";
    fs::remove_all(copy);
    fs::create_directories(copy);
    const fs::path room = fs::path(RELIGHT_SOURCE_DIR) / "examples/room";
    for (const char* f : {"scene.json", "photo.exr", "geometry.obj"}) fs::copy_file(room / f, copy / f);
    Scene scene = load_scene(copy / "scene.json");
    CameraSpec turned = scene.camera.spec();
    turned.look_at =
        turned.position + Eigen::AngleAxisf(radians(1.0f), turned.up.normalized()) * (turned.look_at - turned.position);
    scene.camera = Camera(turned, scene.camera.width(), scene.camera.height());
    std::ofstream(copy / "scene.json") << scene_to_json(scene, copy);
    const std::string original = file_text(copy / "scene.json");
    const Scene truth = load_scene(room / "scene.json");
    const int w = truth.camera.width(), h = truth.camera.height();
    const float off_before =
        view_difference_px(truth.camera.spec(), load_scene(copy / "scene.json").camera.spec(), w, h);
    QVERIFY(off_before > 5.0f);

    QSignalSpy opened(window_.get(), &MainWindow::sceneOpened);
    window_->open_scene(QString::fromStdString((copy / "scene.json").string()));
    QVERIFY(opened.wait(240000));
    QSignalSpy matched(window_.get(), &MainWindow::sceneMatched);
    window_->match_scene(QString::fromStdString((copy / "scene.json").string()));
    QVERIFY(matched.wait(1000) || matched.size() == 1);
    QVERIFY(matched.at(0).at(0).toString().contains("is the open scene"));

    const fs::path out = copy / "scene_matched.json";
    window_->match_scene(QString::fromStdString(out.string()));
    QVERIFY(matched.wait(240000));
    QCOMPARE(matched.at(1).at(0).toString(), QString());
    if (const auto boxes = window_->findChildren<QMessageBox*>(); !boxes.empty())
      keep_picture("scene_matched", *boxes.back());
    QVERIFY(opened.wait(240000));
    const float off_after = view_difference_px(truth.camera.spec(), load_scene(out).camera.spec(), w, h);
    std::printf("[ figures  ] the camera turned 1 degree: its view %.2f px off before matching, %.2f px after\n",
                off_before, off_after);
    QVERIFY(off_after < 1.0f);
    QCOMPARE(file_text(copy / "scene.json"), original);
    QCOMPARE(view_difference_px(truth.camera.spec(), document().studio_scene().analysed->scene().camera.spec(), w, h),
             off_after);

    // Matched again, the camera now right is kept as it is, not nudged.
    const fs::path again = copy / "scene_matched_again.json";
    window_->match_scene(QString::fromStdString(again.string()));
    QVERIFY(matched.wait(240000));
    QCOMPARE(matched.at(2).at(0).toString(), QString());
    QVERIFY(view_difference_px(load_scene(out).camera.spec(), load_scene(again).camera.spec(), w, h) < 0.01f);
  }

  void export_writes_the_full_size_image() {
    QSignalSpy done(window_.get(), &MainWindow::exportFinished);
    const QString path = folder_.filePath("relit.png");
    window_->export_image(path);
    QVERIFY(done.wait(240000));
    QCOMPARE(done.at(0).at(0).toString(), QString());
    const Image image = read_image(path.toStdString());
    QCOMPARE(image.width, 320);
    QCOMPARE(image.height, 240);
    window_->export_image(folder_.filePath("relit.tiff"));
    QVERIFY(window_->last_error().contains("relit.tiff"));
  }
};

// The functions that wait for the session's final renders (or, the last
// three, for analyses and a material estimate or a fit), ten times slower
// under the sanitizers than the rest: `studio_test --final-renders` runs
// them, `studio_test --editing` everything else (tests/CMakeLists.txt: the
// first is labelled `slow`, so CI runs it in the Release step only; the
// session's final renders run under the sanitizers in session_test, the
// analyses in the CLI tests, the estimate in specular_test).
const QStringList kFinalRenderFunctions = {
    "the_picture_changes_when_a_light_moves",
    "solo_shows_one_light_alone_and_leaves_the_rig",
    "exporting_while_soloed_renders_that_light_alone",
    "opening_a_rig_keeps_the_images_of_lights_that_did_not_move",
    "a_plain_click_on_the_photo_selects_and_moves_nothing",
    "the_photo_shows_a_spots_cone_where_the_camera_sees_it",
    "dragging_handles_on_the_photo_moves_and_aims_the_light",
    "the_geometry_over_the_photo_is_a_view_toggle",
    "placing_a_light_from_the_photo_is_a_tool_or_ctrl_click",
    "dragging_an_area_lights_circle_on_the_photo_turns_it",
    "the_split_shows_the_photo_left_and_the_relit_image_right",
    "export_writes_the_full_size_image",
    "finding_the_surfaces_that_shine_writes_and_opens_a_new_scene",
    "matching_the_scene_to_the_photo_writes_and_opens_it",
    "a_large_photo_opens_with_a_preview_and_the_full_analysis_keeps_its_edits",
};

// QtTest's arguments, the test functions of the group asked for (one of
// the two flags above, first) put in their place; without a flag, as given.
QStringList test_arguments(const QObject& test, QStringList arguments) {
  const bool final_renders = arguments.size() > 1 && arguments[1] == "--final-renders";
  if (arguments.size() < 2 || (!final_renders && arguments[1] != "--editing")) return arguments;
  arguments.removeAt(1);
  const QMetaObject& meta = *test.metaObject();
  for (int m = meta.methodOffset(); m < meta.methodCount(); ++m) {
    const QMetaMethod method = meta.method(m);
    const QString name = QString::fromLatin1(method.name());
    if (method.methodType() != QMetaMethod::Slot || method.parameterCount() != 0 ||
        QStringList{"initTestCase", "cleanupTestCase", "init", "cleanup"}.contains(name))
      continue;
    if (kFinalRenderFunctions.contains(name) == final_renders) arguments.append(name);
  }
  return arguments;
}

int main(int argc, char** argv) {
  // A session of its own: Linux shares the processor fairly between
  // sessions (the scheduler's autogroups) and by nice value only within
  // one. The studio's background work gives way (nice 10,
  // core/background_work.h); in ctest's session beside another test using
  // every core it got a tenth of one (a 27-second function unfinished after
  // 180 s), in its own session its fair share (36 s). Fails harmlessly where
  // the program already leads a process group (a shell's job).
  ::setsid();
  QApplication app(argc, argv);
  StudioTest test;
  return QTest::qExec(&test, test_arguments(test, app.arguments()));
}
#include "studio_test.moc"
