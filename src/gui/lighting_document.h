// LightingDocument: the lighting design being edited — the rig, kept in step
// with a RelightSession that renders it — on a loaded scene. Every change to
// the rig goes through here (the undo commands call it), and each one
// announces itself so that the list, the geometry view and the photo follow.
#pragma once

#include <QObject>
#include <memory>

#include "gui/studio_scene.h"
#include "relight/session.h"

namespace relight::gui {

class LightingDocument : public QObject {
  Q_OBJECT

 public:
  LightingDocument(std::shared_ptr<const StudioScene> scene, const Rig& rig, const SessionOptions& options,
                   QObject* parent = nullptr);
  ~LightingDocument() override;

  const StudioScene& studio_scene() const { return *scene_; }
  const Scene& scene() const { return scene_->analysed->scene(); }
  const Rig& rig() const { return rig_; }
  int light_count() const { return int(rig_.lights.size()); }
  const Light& light(int index) const { return rig_.lights.at(size_t(index)); }
  RelightSession& session() { return *session_; }

  void set_light(int index, const Light& light);
  // Inserts at `index` (0..light_count()).
  void insert_light(int index, const Light& light);
  void remove_light(int index);
  void set_environment_scale(float scale);
  // Replaces the whole rig (a rig file was opened); the session keeps the
  // images of the lights that did not move.
  void reset_rig(const Rig& rig);

 signals:
  void lightChanged(int index);
  void lightInserted(int index);
  void lightRemoved(int index);
  void environmentScaleChanged(float scale);
  void rigReset();

 private:
  std::shared_ptr<const StudioScene> scene_;
  Rig rig_;
  std::unique_ptr<RelightSession> session_;
};

}  // namespace relight::gui
