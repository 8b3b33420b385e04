// MainWindow (thesis 6.2): relight studio's main form. Left: the geometry
// view, the list of lights (eye checkbox, short description) with New,
// Change and Delete, and the selected light's details (LightsPanel). Right:
// the re-lit photo, live from the relighting session, with a before/after
// split, an exposure and the ambient (environment) level (PhotoPanel).
// Files: scenes (analysed on a worker with progress and cancel, cached next
// to the scene), rigs, exported images; every edit is undoable.
#pragma once

#include <QMainWindow>
#include <QUndoStack>
#include <functional>
#include <memory>

#include "gui/background_task.h"
#include "gui/light_commands.h"
#include "gui/lighting_document.h"

class QLabel;
class QMenu;

namespace relight::gui {

class GeometryView;
class LightListModel;
class LightsPanel;
class PhotoPanel;
class PhotoView;
class TaskStatus;

struct StudioOptions {
  AnalysisOptions analysis;   // for a scene without a cached analysis
  SessionOptions session;     // its backend draws moving lights; its view size is chosen from the photo (StudioLoad)
  int max_view_width = 1280;  // larger photos are shown (and edited) smaller; an export is always full size
  // A photo of more pixels than this is shown with a preview analysis first
  // while the full one runs (0: never).
  int64_t preview_above_pixels = kPreviewPixels;
  bool remember_recent = true;
};
// The defaults of the application: the OpenGL backend where it can open.
StudioOptions default_studio_options();

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  explicit MainWindow(StudioOptions options = default_studio_options(), QWidget* parent = nullptr);
  ~MainWindow() override;

  // Loads the scene on a worker (sceneOpened or openFailed follows) with the
  // rig, or the scene's own lights where rig_path is empty.
  // With analysis_folder, the analysis `relight analyze` made there is used
  // (File > Open Analysis); else the scene's cache, or a new analysis.
  void open_scene(const QString& scene_path, const QString& rig_path = {}, const QString& analysis_folder = {});
  bool open_rig(const QString& path);
  bool save_rig(const QString& path);
  // Renders the rig at full quality on a worker and writes EXR or PNG (by
  // the extension; PNG through the exposure); exportFinished follows.
  void export_image(const QString& path);
  // Finds which surfaces of the open scene shine from its photo (`relight
  // materials`) on a worker, writes the scene with them to `out_path` (never
  // over the open scene) and opens it; where none is found to shine it says
  // so and writes nothing. materialsFound follows (then sceneOpened where it
  // opens the new scene).
  void find_materials(const QString& out_path);
  // Matches the open scene to its photo (`relight fit --register
  // --refine-placement`) on a worker: registers the camera to the photo's
  // edges (a match out of range is reported and the camera kept), fits the
  // lights' power and colour and the background, moves the lights to where
  // their shadows fall, writes the scene so matched to `out_path` (never over
  // the open scene) and opens it. sceneMatched follows (then sceneOpened).
  void match_scene(const QString& out_path);
  bool busy() const { return task_.running(); }
  void cancel_task() { task_.cancel(); }

  // The edits, each one undo step.
  void add_light(const Light& light);
  void change_light(int index, const Light& light);
  void delete_light(int index);
  // Adds a copy of light `index`, named "NAME copy" (or "NAME copy 2", ...:
  // a name no light has), in the same place, and selects it.
  void duplicate_light(int index);
  // Shows light `index` alone (-1: every light as the rig has it); not an
  // edit of the rig, so not on the undo stack.
  void solo_light(int index);
  // Solos light `index`, or, if it is the one soloed, ends the solo.
  void toggle_solo(int index);
  void set_light_enabled(int index, bool enabled);
  // The Environment entry's edits, each one undo step: a new sky from an
  // HDR image (false, with the error shown, where it cannot be read), its
  // turn in degrees (a run of them one step), the eye.
  bool open_sky(const QString& image_path);
  void turn_sky(float turn_deg);
  void set_sky_enabled(bool enabled);
  // The selected light's colour / power (a sun's irradiance); a run of these
  // edits of one light is one undo step.
  void set_selected_colour(const Vec3& colour);
  void set_selected_power(float power);
  void move_selected_light(const Vec3& delta);
  // Puts the selected light in front of the surface under the re-lit
  // image's pixel position (spots and areas aim at it; a sun, which has no
  // position, is refused).
  void place_selected_light(const QPointF& image_position);
  // A click on the photo: with the Place Light tool on, or Ctrl held, it
  // places the selected light; else it selects the light drawn there.
  void photo_clicked(const QPointF& image_position, Qt::KeyboardModifiers modifiers);
  // The light (not a sun) whose position the camera shows within a few
  // pixels of the re-lit image's position, the nearest; -1 if none.
  int light_at(const QPointF& image_position) const;
  QAction& place_tool() const { return *place_tool_action_; }
  QString mode_text() const;  // what the status bar says a click on the photo does

  int selected_light() const { return selected_; }
  void select_light(int index);
  // Shows the session's newest frame; true if it was a new one.
  bool refresh_frame();

  LightingDocument* document() const { return document_.get(); }
  QUndoStack& undo_stack() { return undo_; }
  GeometryView& geometry_view() const;
  PhotoView& photo_view() const;
  LightListModel& light_model() const;
  QString rig_path() const { return rig_path_; }
  QString last_error() const { return last_error_; }

 signals:
  void sceneOpened();
  // The full analysis replaced the preview the scene opened with (or
  // failed: the preview stays).
  void fullAnalysisDone(const QString& error);
  void openFailed(const QString& error);
  void exportFinished(const QString& error);
  // error: empty on success; found: how many objects or materials shine.
  void materialsFound(const QString& error, int found);
  void sceneMatched(const QString& error);  // empty on success

 protected:
  void closeEvent(QCloseEvent* event) override;

 private:
  void connect_panels();
  void make_menus();
  // A new document on `scene` with the lights of rig_path (or the scene's).
  void install_scene(std::shared_ptr<const StudioScene> scene, const QString& scene_path, const QString& rig_path);
  // The open analysis on screen: the photo, its geometry's edges, and what
  // the status bar says of it.
  void show_analysis();
  // Says in the status bar what relight studio does with the rig's animated
  // lights, where it has any.
  void note_animation(const Rig& rig);
  // How this window opens a scene (its analysis options and view width).
  StudioLoad studio_load() const;
  // Why a scene made from the open one cannot be written to `out_path` now
  // (the full analysis still running, or the open scene named as the
  // output), `doing` what is asked for; empty where it can.
  QString refuse_to_write_scene(const QString& out_path, const QString& doing) const;
  // Says what was found (a message box whose details are `lines`, and the
  // status bar) after a scene was made from the open one.
  void report(const QString& heading, const QStringList& lines);
  // Analyses the open scene in full on a worker and puts it in the
  // preview's place under the same document: the design, the selection and
  // the undo history carry over.
  void replace_preview();
  void run_task(const QString& label, BackgroundTask::Work work, std::function<void(const QString&)> done);
  void show_error(const QString& text);
  bool maybe_keep_changes();  // false: the user cancelled
  void new_light_dialog();
  void change_light_dialog();
  void update_actions();
  void update_title();
  void remember(const QString& key, const QString& path);
  void fill_recent_menu(QMenu* menu, const QString& key);
  Light default_new_light() const;
  // Pushes `change` of the selected light as one edit (merged as `merge` says).
  void edit_selected_light(const QString& text, EditLightCommand::Merge merge,
                           const std::function<void(Light&)>& change);
  void edit_sky(const QString& text, EnvironmentCommand::Merge merge, const std::function<void(SkyEdit&)>& change);

  StudioOptions options_;
  std::shared_ptr<const StudioScene> scene_;
  std::unique_ptr<LightingDocument> document_;
  QUndoStack undo_;
  BackgroundTask task_;
  int selected_ = -1;
  QString scene_path_, rig_path_, last_error_;

  LightsPanel* lights_;
  PhotoPanel* photo_panel_;
  TaskStatus* task_status_;
  QAction *save_rig_action_, *save_rig_as_action_, *open_rig_action_, *export_action_, *find_materials_action_,
      *match_scene_action_;
  QAction *new_light_action_, *change_light_action_, *duplicate_light_action_, *solo_light_action_,
      *delete_light_action_, *place_tool_action_;
  QLabel* mode_label_;
};

}  // namespace relight::gui
