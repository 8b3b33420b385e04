#include "gui/lighting_document.h"

namespace relight::gui {

LightingDocument::LightingDocument(std::shared_ptr<const StudioScene> scene, const Rig& rig,
                                   const SessionOptions& options, QObject* parent)
    : QObject(parent),
      scene_(std::move(scene)),
      rig_(rig),
      session_(std::make_unique<RelightSession>(*scene_->analysed, rig_, options)) {}

LightingDocument::~LightingDocument() = default;

void LightingDocument::set_light(int index, const Light& light) {
  rig_.lights.at(size_t(index)) = light;
  session_->set_light(size_t(index), light);
  emit lightChanged(index);
}

void LightingDocument::insert_light(int index, const Light& light) {
  const size_t at = size_t(index);
  rig_.lights.insert(rig_.lights.begin() + std::ptrdiff_t(at), light);
  session_->insert_light(at, light);
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
  rig_ = rig;
  session_->set_rig(rig_);
  emit rigReset();
}

}  // namespace relight::gui
