#include "gui/colour_temperature.h"

#include <algorithm>
#include <cmath>

namespace relight::gui {

namespace {

using Vec2d = Eigen::Vector2d;
using Vec3d = Eigen::Vector3d;

// One asymmetric Gaussian lobe of the fits below.
double lobe(double nm, double mean, double sigma_below, double sigma_above) {
  const double t = (nm - mean) / (nm < mean ? sigma_below : sigma_above);
  return std::exp(-0.5 * t * t);
}

// The CIE 1931 2° colour-matching functions, by the multi-lobe fit of Wyman,
// Sloan and Shirley, "Simple Analytic Approximations to the CIE XYZ Color
// Matching Functions", JCGT 2(2), 2013.
Vec3d colour_matching(double nm) {
  return {1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7) -
              0.065 * lobe(nm, 501.1, 20.4, 26.2),
          0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1),
          1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8)};
}

// XYZ of a blackbody at `kelvin` (Planck's law, to a constant factor),
// summed over 380..780 nm in 1 nm steps.
Vec3d blackbody_xyz(double kelvin) {
  constexpr double c2 = 1.4387769e-2;  // second radiation constant h c / k, m K
  Vec3d xyz = Vec3d::Zero();
  for (int nm = 380; nm <= 780; ++nm) {
    const double metres = nm * 1e-9;
    xyz += colour_matching(nm) / (std::pow(metres, 5) * std::expm1(c2 / (metres * kelvin)));
  }
  return xyz;
}

// CIE 1960 UCS (u, v) and back to XYZ with Y = 1.
Vec2d uv_of(const Vec3d& xyz) {
  const double d = xyz.x() + 15.0 * xyz.y() + 3.0 * xyz.z();
  return {4.0 * xyz.x() / d, 6.0 * xyz.y() / d};
}
Vec3d xyz_of(const Vec2d& uv) {
  const double d = 2.0 * uv.x() - 8.0 * uv.y() + 4.0;
  const double x = 3.0 * uv.x() / d, y = 2.0 * uv.y() / d;
  return {x / y, 1.0, (1.0 - x - y) / y};
}

// The Planckian locus at `kelvin` and its unit normal there, pointing to
// green (+v), as ANSI C78.377 measures Duv.
struct LocusPoint {
  Vec2d uv, normal;
};
LocusPoint locus(double kelvin) {
  const double mired = 1e6 / kelvin;
  const Vec2d tangent = uv_of(blackbody_xyz(1e6 / (mired - 0.5))) - uv_of(blackbody_xyz(1e6 / (mired + 0.5)));
  Vec2d normal(-tangent.y(), tangent.x());
  if (normal.y() < 0.0) normal = -normal;
  return {uv_of(blackbody_xyz(kelvin)), normal.normalized()};
}

// sRGB's primaries and D65 white (IEC 61966-2-1).
const Eigen::Matrix3d& rgb_to_xyz() {
  static const Eigen::Matrix3d m = (Eigen::Matrix3d() << 0.4124564, 0.3575761, 0.1804375,  //
                                    0.2126729, 0.7151522, 0.0721750,                        //
                                    0.0193339, 0.1191920, 0.9503041)
                                       .finished();
  return m;
}

}  // namespace

Vec3 colour_from_temperature(float kelvin, float tint) {
  const LocusPoint p = locus(std::clamp(double(kelvin), double(kMinKelvin), double(kMaxKelvin)));
  const double duv = std::clamp(double(tint), -double(kMaxTint), double(kMaxTint));
  const Vec3d rgb = (rgb_to_xyz().inverse() * xyz_of(p.uv + duv * p.normal)).cwiseMax(0.0);
  return (rgb / rgb.maxCoeff()).cast<float>();
}

std::optional<ColourTemperature> temperature_of_colour(const Vec3& linear) {
  const Vec3d xyz = rgb_to_xyz() * linear.cast<double>().cwiseMax(0.0);
  if (xyz.sum() <= 0.0) return std::nullopt;
  const Vec2d uv = uv_of(xyz);
  // The locus's nearest point, by golden-section search in mireds (even in
  // how different temperatures look).
  const auto distance = [&](double mired) { return (uv - uv_of(blackbody_xyz(1e6 / mired))).norm(); };
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = 1e6 / kMaxKelvin, hi = 1e6 / kMinKelvin;
  while (hi - lo > 1e-3) {
    const double a = hi - golden * (hi - lo), b = lo + golden * (hi - lo);
    if (distance(a) < distance(b))
      hi = b;
    else
      lo = a;
  }
  const double kelvin = 1e6 / (0.5 * (lo + hi));
  const LocusPoint p = locus(kelvin);
  return ColourTemperature{float(kelvin),
                           float(std::clamp((uv - p.uv).dot(p.normal), -double(kMaxTint), double(kMaxTint)))};
}

}  // namespace relight::gui
