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
  distorted_ = spec.distortion != Vec2::Zero();
}

Vec2 Camera::distort(const Vec2& u) const {
  const float r2 = u.squaredNorm();
  return u * (1.0f + r2 * (spec_.distortion.x() + r2 * spec_.distortion.y()));
}

// Newton's method on the radius: r (1 + k1 r^2 + k2 r^4) = |d|, from r = |d|;
// a few steps reach float precision for any distortion that does not fold.
Vec2 Camera::undistort(const Vec2& d) const {
  const float k1 = spec_.distortion.x(), k2 = spec_.distortion.y(), rd = d.norm();
  if (rd == 0.0f) return d;
  float r = rd;
  for (int step = 0; step < 8; ++step) {
    const float r2 = r * r;
    const float f = r * (1.0f + r2 * (k1 + r2 * k2)) - rd, slope = 1.0f + r2 * (3.0f * k1 + 5.0f * r2 * k2);
    if (slope <= 0.0f) break;
    r -= f / slope;
  }
  return d * (r / rd);
}

bool Camera::distortion_folds() const {
  if (!distorted_) return false;
  // The farthest corner from the principal point, on the image plane.
  const float half_w = tan_half_ * aspect_, half_h = tan_half_;
  const float corner = Vec2(half_w * (1.0f + std::abs(shift_.x())), half_h * (1.0f + std::abs(shift_.y()))).norm();
  // The distorted radius must grow with the undistorted one out to the corner.
  constexpr int kSteps = 256;
  float last = 0.0f;
  for (int i = 1; i <= 8 * kSteps; ++i) {
    const float r = corner * float(i) / kSteps, seen = distort(Vec2(r, 0.0f)).x();
    if (seen <= last) return true;
    if (seen >= corner) return false;
    last = seen;
  }
  return false;
}

Vec3 Camera::ray_direction(float x, float y) const {
  Vec2 u((2.0f * x / width_ - 1.0f - shift_.x()) * tan_half_ * aspect_,
         (1.0f - 2.0f * y / height_ - shift_.y()) * tan_half_);
  if (distorted_) u = undistort(u);
  return (forward_ + u.x() * right_ + u.y() * up_).normalized();
}

std::optional<Vec2> Camera::project(const Vec3& p) const {
  const Vec3 d = p - spec_.position;
  const float z = d.dot(forward_);
  if (z <= 1e-6f) return std::nullopt;
  Vec2 across(d.dot(right_), d.dot(up_));  // on the image plane at depth z
  if (distorted_) across = z * distort(across / z);
  const float ndc_x = across.x() / (z * tan_half_ * aspect_) + shift_.x();
  const float ndc_y = across.y() / (z * tan_half_) + shift_.y();
  return Vec2((ndc_x + 1.0f) * 0.5f * width_, (1.0f - ndc_y) * 0.5f * height_);
}

}  // namespace relight
