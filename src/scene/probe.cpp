#include "scene/probe.h"

#include <algorithm>
#include <cmath>

namespace relight {

ProbeFrame::ProbeFrame(const Vec3& f, const Vec3& u) {
  forward = f.normalized();
  right = forward.cross(u).normalized();
  up = right.cross(forward);
}

Vec2 probe_direction_to_uv(ProbeMapping mapping, const ProbeFrame& frame, const Vec3& d) {
  const float x = d.dot(frame.right), y = d.dot(frame.up), z = d.dot(frame.forward);
  if (mapping == ProbeMapping::equirect) {
    const float u = 0.5f + std::atan2(x, z) / (2.0f * kPi);
    const float v = std::acos(std::clamp(y, -1.0f, 1.0f)) / kPi;
    return {u, v};
  }
  // Mirror ball: the normal halfway between the view ray and d, n ~ d - f.
  Vec3 n(x, y, z - 1.0f);
  const float len = n.norm();
  if (len < 1e-7f) return {0.5f, 0.0f};  // straight behind the ball: the disc's rim
  n /= len;
  return {(n.x() + 1.0f) * 0.5f, (1.0f - n.y()) * 0.5f};
}

std::optional<Vec3> probe_uv_to_direction(ProbeMapping mapping, const ProbeFrame& frame, const Vec2& uv) {
  if (mapping == ProbeMapping::equirect) {
    const float phi = (uv.x() - 0.5f) * 2.0f * kPi;
    const float theta = uv.y() * kPi;
    const float s = std::sin(theta);
    return (s * std::sin(phi)) * frame.right + std::cos(theta) * frame.up + (s * std::cos(phi)) * frame.forward;
  }
  const float a = 2.0f * uv.x() - 1.0f, b = 1.0f - 2.0f * uv.y();
  const float r2 = a * a + b * b;
  if (r2 > 1.0f) return std::nullopt;
  const Vec3 n = a * frame.right + b * frame.up - std::sqrt(1.0f - r2) * frame.forward;
  const Vec3& f = frame.forward;
  return (f - 2.0f * f.dot(n) * n).normalized();
}

float probe_pixel_solid_angle(ProbeMapping mapping, const Vec2& uv, int width, int height) {
  if (mapping == ProbeMapping::equirect)
    return (2.0f * kPi / width) * (kPi / height) * std::sin(std::clamp(uv.y(), 0.0f, 1.0f) * kPi);
  // The mirror-ball map has constant Jacobian: 4 sr per unit of disc area.
  return 4.0f * (2.0f / width) * (2.0f / height);
}

}  // namespace relight
