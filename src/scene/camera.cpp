#include "scene/camera.h"

#include <cmath>

namespace relight {

Camera::Camera(const CameraSpec& spec, int width, int height) : spec_(spec), width_(width), height_(height) {
  forward_ = (spec.look_at - spec.position).normalized();
  right_ = forward_.cross(spec.up).normalized();
  up_ = right_.cross(forward_);
  tan_half_ = std::tan(radians(spec.vfov_deg) * 0.5f);
  aspect_ = float(width) / float(height);
  shift_ = Vec2(2.0f * spec.principal_point.x() - 1.0f, 1.0f - 2.0f * spec.principal_point.y());
}

Vec3 Camera::ray_direction(float x, float y) const {
  const float ndc_x = 2.0f * x / width_ - 1.0f - shift_.x();
  const float ndc_y = 1.0f - 2.0f * y / height_ - shift_.y();
  return (forward_ + ndc_x * tan_half_ * aspect_ * right_ + ndc_y * tan_half_ * up_).normalized();
}

std::optional<Vec2> Camera::project(const Vec3& p) const {
  const Vec3 d = p - spec_.position;
  const float z = d.dot(forward_);
  if (z <= 1e-6f) return std::nullopt;
  const float ndc_x = d.dot(right_) / (z * tan_half_ * aspect_) + shift_.x();
  const float ndc_y = d.dot(up_) / (z * tan_half_) + shift_.y();
  return Vec2((ndc_x + 1.0f) * 0.5f * width_, (1.0f - ndc_y) * 0.5f * height_);
}

}  // namespace relight
