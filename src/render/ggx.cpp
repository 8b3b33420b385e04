#include "render/ggx.h"

#include <algorithm>
#include <cmath>

namespace relight {
namespace {

// Blender's Principled BSDF: an index of refraction from `specular`
// (0.5: reflectance 4 % at normal incidence, an index of 1.5).
float index_of_refraction(float specular) {
  const float root_f0 = std::sqrt(std::clamp(0.08f * specular, 0.0f, 0.99f));
  return (1.0f + root_f0) / (1.0f - root_f0);
}

}  // namespace

GgxLobe::GgxLobe(const Gloss& gloss)
    : alpha_(std::max(gloss.roughness, kMinRoughness) * std::max(gloss.roughness, kMinRoughness)),
      eta_(index_of_refraction(gloss.specular)) {}

float GgxLobe::distribution(float cos_h) const {
  const float a2 = alpha_ * alpha_;
  const float d = cos_h * cos_h * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * d * d);
}

float GgxLobe::shadowing(float cos_theta) const {
  const float c2 = cos_theta * cos_theta;
  const float tan2 = std::max(0.0f, 1.0f - c2) / c2;
  return 2.0f / (1.0f + std::sqrt(1.0f + alpha_ * alpha_ * tan2));
}

float GgxLobe::fresnel(float cos_d) const {
  const float c = std::abs(cos_d);
  float g = eta_ * eta_ - 1.0f + c * c;
  if (g <= 0.0f) return 1.0f;
  g = std::sqrt(g);
  const float a = (g - c) / (g + c);
  const float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
  return 0.5f * a * a * (1.0f + b * b);
}

float GgxLobe::f0() const { return fresnel(1.0f); }

float GgxLobe::brdf(const Vec3& n, const Vec3& l, const Vec3& v) const {
  if (n.dot(l) <= 0.0f) return 0.0f;  // before the view's terms: the path tracer's light below the surface
  return brdf(n, l, v, view_terms(n, v));
}

GgxLobe::ViewTerms GgxLobe::view_terms(const Vec3& n, const Vec3& v) const {
  const float nv = n.dot(v);
  return {nv, nv > 0.0f ? shadowing(nv) : 0.0f};
}

float GgxLobe::brdf(const Vec3& n, const Vec3& l, const Vec3& v, const ViewTerms& view, float tail) const {
  const float nl = n.dot(l), nv = view.cos_v;
  if (nl <= 0.0f || nv <= 0.0f) return 0.0f;
  const Vec3 h = (l + v).normalized();
  // Less its tail (the peak is 1 / (pi alpha^2)): no edge where it is cut.
  const float d = distribution(n.dot(h)) - (tail > 0.0f ? tail / (kPi * alpha_ * alpha_) : 0.0f);
  if (d <= 0.0f) return 0.0f;
  return fresnel(l.dot(h)) * d * shadowing(nl) * view.shadowing_v / (4.0f * nl * nv);
}

float GgxLobe::pdf(const Vec3& n, const Vec3& l, const Vec3& v) const {
  const float nl = n.dot(l), nv = n.dot(v);
  if (nl <= 0.0f || nv <= 0.0f) return 0.0f;
  const Vec3 h = (l + v).normalized();
  return shadowing(nv) * distribution(n.dot(h)) / (4.0f * nv);
}

bool GgxLobe::sample(const Vec3& n, const Vec3& v, const Vec2& u, Vec3& l, float& weight) const {
  Vec3 t, b;
  orthonormal_basis(n, t, b);
  const Vec3 view(v.dot(t), v.dot(b), v.dot(n));
  if (view.z() <= 0.0f) return false;
  // Heitz 2018: the view stretched to the unit-roughness configuration, a
  // point of the projected hemisphere's disc, and the normal it shows
  // unstretched.
  const Vec3 vh = Vec3(alpha_ * view.x(), alpha_ * view.y(), view.z()).normalized();
  const float len2 = vh.x() * vh.x() + vh.y() * vh.y();
  const Vec3 t1 = len2 > 0.0f ? Vec3(-vh.y(), vh.x(), 0.0f) / std::sqrt(len2) : Vec3(1.0f, 0.0f, 0.0f);
  const Vec3 t2 = vh.cross(t1);
  const float r = std::sqrt(u.x()), phi = 2.0f * kPi * u.y();
  const float p1 = r * std::cos(phi);
  const float s = 0.5f * (1.0f + vh.z());
  const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * r * std::sin(phi);
  const Vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  const Vec3 m = Vec3(alpha_ * nh.x(), alpha_ * nh.y(), std::max(1e-6f, nh.z())).normalized();
  const Vec3 h = m.x() * t + m.y() * b + m.z() * n;
  l = 2.0f * v.dot(h) * h - v;
  const float nl = n.dot(l);
  if (nl <= 0.0f) return false;
  // brdf x cos / pdf, with the pdf G1(v) D / (4 n.v): the Fresnel term and
  // the light's side of the shadowing.
  weight = fresnel(l.dot(h)) * shadowing(nl);
  return true;
}

}  // namespace relight
