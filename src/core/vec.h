// Small vector helpers on top of Eigen: the 3-vector used for points,
// directions and linear RGB alike, and the few operations the renderer needs.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace relight {

using Vec3 = Eigen::Vector3f;
using Vec2 = Eigen::Vector2f;

inline constexpr float kPi = std::numbers::pi_v<float>;
inline constexpr float kInvPi = 1.0f / kPi;

inline float radians(float degrees) { return degrees * kPi / 180.0f; }

// The angle between two directions, in degrees.
inline float angle_degrees(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0f, 1.0f)) * 180.0f / kPi;
}

// Rec. 709 luminance of a linear RGB value.
inline float luminance(const Vec3& c) { return 0.2126f * c.x() + 0.7152f * c.y() + 0.0722f * c.z(); }

inline bool is_finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

// Two unit vectors t, b completing the unit vector n to a right-handed
// orthonormal frame (Duff et al. 2017, branchless).
inline void orthonormal_basis(const Vec3& n, Vec3& t, Vec3& b) {
  const float sign = std::copysign(1.0f, n.z());
  const float a = -1.0f / (sign + n.z());
  const float c = n.x() * n.y() * a;
  t = Vec3(1.0f + sign * n.x() * n.x() * a, sign * c, -sign * n.x());
  b = Vec3(c, sign + n.y() * n.y() * a, -n.y());
}

// A direction given in the local frame (t, b, n) expressed in world space.
inline Vec3 to_world(const Vec3& local, const Vec3& n) {
  Vec3 t, b;
  orthonormal_basis(n, t, b);
  return local.x() * t + local.y() * b + local.z() * n;
}

}  // namespace relight
