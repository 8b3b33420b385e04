#include "gui/lighting_document.h"

namespace relight::gui {

std::optional<RigEnvironment> SkyEdit::environment() const {
  if (!opened || !enabled) return std::nullopt;
  return turn_deg == 0.0f ? *opened : turned_environment(*opened, turn_deg);
}

bool SkyEdit::operator==(const SkyEdit& other) const {
  const bool same_opened = opened && other.opened
                               ? opened->image == other.opened->image && opened->color == other.opened->color
                               : !opened && !other.opened;
  return same_opened && turn_deg == other.turn_deg && enabled == other.enabled;
}

LightingDocument::LightingDocument(std::shared_ptr<const StudioScene> scene, const Rig& rig,
                                   const SessionOptions& options, QObject* parent)
    : QObject(parent),
      scene_(std::move(scene)),
      rig_(rig),
      session_(std::make_unique<RelightSession>(*scene_->analysed, rig_, options, scene_->session_view)),
      sky_{rig.environment} {
  listen_to_frames();
}

LightingDocument::~LightingDocument() = default;

Light LightingDocument::shown_light(int index) const {
  Light shown = light(index);
  if (solo_ >= 0) shown.enabled = index == solo_;
  return shown;
}

Rig LightingDocument::shown_rig() const {
  Rig shown = rig_;
  for (int i = 0; i < light_count(); ++i) shown.lights[size_t(i)] = shown_light(i);
  return shown;
}

void LightingDocument::set_solo(int index) {
  if (index == solo_) return;
  const int before = solo_;
  const auto lit = [this](int i, int solo) { return solo < 0 ? light(i).enabled : i == solo; };
  solo_ = index;
  // Only the lights that go on or off are drawn again.
  for (int i = 0; i < light_count(); ++i)
    if (lit(i, before) != lit(i, solo_)) session_->set_light(size_t(i), shown_light(i));
  emit soloChanged(solo_);
}

void LightingDocument::set_light(int index, const Light& light) {
  rig_.lights.at(size_t(index)) = light;
  session_->set_light(size_t(index), shown_light(index));
  emit lightChanged(index);
}

void LightingDocument::insert_light(int index, const Light& light) {
  const size_t at = size_t(index);
  rig_.lights.insert(rig_.lights.begin() + std::ptrdiff_t(at), light);
  if (solo_ >= index) ++solo_;
  session_->insert_light(at, shown_light(index));
  emit lightInserted(index);
}

void LightingDocument::remove_light(int index) {
  if (index == solo_) set_solo(-1);
  if (index < solo_) --solo_;
  rig_.lights.erase(rig_.lights.begin() + index);
  session_->remove_light(size_t(index));
  emit lightRemoved(index);
}

void LightingDocument::set_environment_scale(float scale) {
  rig_.environment_scale = scale;
  session_->set_environment_scale(scale);
  emit environmentScaleChanged(scale);
}

void LightingDocument::set_sky(const SkyEdit& sky) {
  if (sky == sky_) return;
  sky_ = sky;
  rig_.environment = sky_.environment();
  session_->set_environment(rig_.environment);
  emit skyChanged();
}

void LightingDocument::reset_rig(const Rig& rig) {
  if (solo_ >= 0) {
    solo_ = -1;
    emit soloChanged(-1);
  }
  rig_ = rig;
  sky_ = SkyEdit{rig.environment};
  session_->set_rig(rig_);
  emit rigReset();
}

void LightingDocument::replace_scene(std::shared_ptr<const StudioScene> scene, const SessionOptions& options) {
  // The new session before the old scene goes: the old session reads it.
  session_ = std::make_unique<RelightSession>(*scene->analysed, shown_rig(), options, scene->session_view);
  scene_ = std::move(scene);
  listen_to_frames();
}

void LightingDocument::listen_to_frames() {
  session_->set_frame_listener([this] { post_frame_ready(); });
  post_frame_ready();  // a frame the session made before it had the listener
}

void LightingDocument::post_frame_ready() {
  if (frame_posted_.exchange(true)) return;
  // Queued to this object's thread; dropped if the document is gone by then.
  QMetaObject::invokeMethod(
      this,
      [this] {
        frame_posted_ = false;
        emit frameReady();
      },
      Qt::QueuedConnection);
}

}  // namespace relight::gui
