#include "gui/lighting_document.h"

namespace relight::gui {

namespace {

std::unique_ptr<RelightSession> start_session(const StudioScene& s, const Rig& rig, const SessionOptions& options) {
  return std::make_unique<RelightSession>(s.scene, *s.rays, *s.gbuffer, s.analysis, rig, options);
}

}  // namespace

LightingDocument::LightingDocument(std::shared_ptr<const StudioScene> scene, const Rig& rig,
                                   const SessionOptions& options, QObject* parent)
    : QObject(parent), scene_(std::move(scene)), options_(options), rig_(rig),
      session_(start_session(*scene_, rig_, options_)) {}

LightingDocument::~LightingDocument() = default;

void LightingDocument::set_light(int index, const Light& light) {
  rig_.lights.at(size_t(index)) = light;
  session_->set_light(size_t(index), light);
  emit lightChanged(index);
}

void LightingDocument::insert_light(int index, const Light& light) {
  const size_t at = size_t(index);
  rig_.lights.insert(rig_.lights.begin() + std::ptrdiff_t(at), light);
  // The session only appends: the lights after `at` leave and come back
  // behind the new one, so the session's order stays the rig's.
  for (size_t i = rig_.lights.size() - 1; i > at; --i) session_->remove_light(at);
  for (size_t i = at; i < rig_.lights.size(); ++i) session_->add_light(rig_.lights[i]);
  emit lightInserted(index);
}

void LightingDocument::remove_light(int index) {
  rig_.lights.erase(rig_.lights.begin() + index);
  session_->remove_light(size_t(index));
  emit lightRemoved(index);
}

void LightingDocument::set_environment_scale(float scale) {
  rig_.environment_scale = scale;
  session_->set_environment_scale(scale);
  emit environmentScaleChanged(scale);
}

void LightingDocument::reset_rig(const Rig& rig) {
  session_.reset();
  rig_ = rig;
  session_ = start_session(*scene_, rig_, options_);
  emit rigReset();
}

}  // namespace relight::gui
