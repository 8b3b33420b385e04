// LightingDocument: the lighting design being edited — the rig, kept in step
// with a RelightSession that renders it — on a loaded scene. Every change to
// the rig goes through here (the undo commands call it), and each one
// announces itself so that the list, the geometry view and the photo follow.
// A light can be soloed: the session then draws it alone, lit, and the
// others off, while the rig keeps every light's own `enabled`. The rig's
// new environment is edited as a SkyEdit (the Environment entry).
#pragma once

#include <QObject>
#include <atomic>
#include <memory>

#include "gui/studio_scene.h"
#include "relight/session.h"

namespace relight::gui {

// The rig's new environment as the Environment entry edits it: the sky as
// opened (none: the scene's own environment), turned by turn_deg about its
// up (counter-clockwise seen from above), shown or switched off (then the
// scene's own environment lights, and a rig saved so has no `environment`).
struct SkyEdit {
  std::optional<RigEnvironment> opened;
  float turn_deg = 0.0f;
  bool enabled = true;

  // The rig's `environment` this gives (the opened one itself unturned).
  std::optional<RigEnvironment> environment() const;
  // Opened skies compare by their image (shared, never copied) and colour.
  bool operator==(const SkyEdit& other) const;
};

class LightingDocument : public QObject {
  Q_OBJECT

 public:
  // The session draws on the scene's session_view: options' width and
  // height are not used.
  LightingDocument(std::shared_ptr<const StudioScene> scene, const Rig& rig, const SessionOptions& options,
                   QObject* parent = nullptr);
  ~LightingDocument() override;

  const StudioScene& studio_scene() const { return *scene_; }
  const Scene& scene() const { return scene_->analysed->scene(); }
  const Rig& rig() const { return rig_; }
  int light_count() const { return int(rig_.lights.size()); }
  const Light& light(int index) const { return rig_.lights.at(size_t(index)); }
  RelightSession& session() { return *session_; }
  // Light `index` as the session draws it: as in the rig, or, while a light
  // is soloed, switched on if it is that one and off if not.
  Light shown_light(int index) const;
  // The rig as the session draws it (what the picture shows).
  Rig shown_rig() const;
  int solo() const { return solo_; }  // the soloed light, or -1
  const SkyEdit& sky() const { return sky_; }
  // Solos light `index`; -1 lights the rig as it is again.
  void set_solo(int index);

  void set_light(int index, const Light& light);
  // Inserts at `index` (0..light_count()).
  void insert_light(int index, const Light& light);
  void remove_light(int index);
  void set_environment_scale(float scale);
  // A new sky, a turn, the eye: the session renders the environment again,
  // not the lights. The sky as it is makes no change.
  void set_sky(const SkyEdit& sky);
  // Replaces the whole rig (a rig file was opened); the session keeps the
  // images of the lights that did not move.
  void reset_rig(const Rig& rig);
  // Another analysis of the same scene (the full one after the preview):
  // the session starts again on it with the design as it is — rig, solo,
  // sky — so the views and the undo history stay with this document.
  void replace_scene(std::shared_ptr<const StudioScene> scene, const SessionOptions& options);

 signals:
  void lightChanged(int index);
  void lightInserted(int index);
  void lightRemoved(int index);
  void environmentScaleChanged(float scale);
  void skyChanged();
  void rigReset();
  void soloChanged(int index);
  // The session has a new frame (RelightSession::frame): emitted on the
  // document's thread, once for any number made since the last.
  void frameReady();

 private:
  // Forwards the session's new frames as frameReady (post_frame_ready, from
  // the session's worker).
  void listen_to_frames();
  void post_frame_ready();

  std::shared_ptr<const StudioScene> scene_;
  Rig rig_;
  // A frameReady is on its way. Declared before the session so that it is
  // destroyed after it: the session's worker may post until it is gone.
  std::atomic<bool> frame_posted_{false};
  std::unique_ptr<RelightSession> session_;
  int solo_ = -1;
  SkyEdit sky_;
};

}  // namespace relight::gui
