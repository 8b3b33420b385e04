#include "scene/environment.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace relight {

ProbeEnvironment::ProbeEnvironment(const Probe& probe) : probe_(probe), frame_(probe.forward, probe.up) {
  const Image& img = probe_.image;
  std::vector<float> weights(img.size());
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const Vec2 uv((x + 0.5f) / img.width, (y + 0.5f) / img.height);
      const bool inside = probe_uv_to_direction(probe_.mapping, frame_, uv).has_value();
      weights[size_t(y) * img.width + x] =
          inside ? luminance(img.at(x, y)) * probe_pixel_solid_angle(probe_.mapping, uv, img.width, img.height) : 0.0f;
    }
  distribution_ = Distribution2D(weights, img.width, img.height);
}

ProbeEnvironment::ProbeEnvironment(const ProbeEnvironment& same_image, const Probe& probe)
    : probe_(probe), frame_(probe.forward, probe.up), distribution_(same_image.distribution_) {
  if (probe.mapping != same_image.probe_.mapping || probe.image.width != same_image.probe_.image.width ||
      probe.image.height != same_image.probe_.image.height)
    throw std::invalid_argument("ProbeEnvironment: a turned probe must keep its image and mapping");
}

Vec3 ProbeEnvironment::radiance(const Vec3& d) const {
  const Vec2 uv = probe_direction_to_uv(probe_.mapping, frame_, d);
  const Image& img = probe_.image;
  const int x = std::clamp(int(uv.x() * img.width), 0, img.width - 1);
  const int y = std::clamp(int(uv.y() * img.height), 0, img.height - 1);
  return img.at(x, y);
}

bool ProbeEnvironment::sample(const Vec2& u, Vec3& d, float& pdf_out) const {
  float pdf_uv;
  const Vec2 uv = distribution_.sample(u, pdf_uv);
  const auto dir = probe_uv_to_direction(probe_.mapping, frame_, uv);
  if (!dir || pdf_uv <= 0.0f) return false;
  d = *dir;
  const Image& img = probe_.image;
  const float pixel_sr = probe_pixel_solid_angle(probe_.mapping, uv, img.width, img.height);
  // density per pixel = pdf_uv / (w h); per steradian divide by the pixel's solid angle
  pdf_out = pixel_sr > 0.0f ? pdf_uv / (float(img.width) * img.height * pixel_sr) : 0.0f;
  return pdf_out > 0.0f;
}

float ProbeEnvironment::pdf(const Vec3& d) const {
  const Vec2 uv = probe_direction_to_uv(probe_.mapping, frame_, d);
  const Image& img = probe_.image;
  const float pixel_sr = probe_pixel_solid_angle(probe_.mapping, uv, img.width, img.height);
  if (pixel_sr <= 0.0f) return 0.0f;
  return distribution_.pdf(uv) / (float(img.width) * img.height * pixel_sr);
}

Environment Environment::constant(const Vec3& radiance) {
  Environment env;
  env.constant_ = radiance;
  return env;
}

Environment Environment::from_probes(const std::vector<Probe>& probes) {
  Environment env;
  for (const auto& p : probes) env.probes_.push_back(std::make_shared<ProbeEnvironment>(p));
  return env;
}

Environment Environment::turned(const Probe& probe) const {
  if (probes_.size() != 1) throw std::invalid_argument("Environment::turned: not a one-probe environment");
  Environment env = *this;
  env.probes_ = {std::make_shared<ProbeEnvironment>(*probes_.front(), probe)};
  return env;
}

const ProbeEnvironment* Environment::probe_for(const Vec3& p) const {
  const ProbeEnvironment* best = nullptr;
  float best_d2 = std::numeric_limits<float>::infinity();
  for (const auto& probe : probes_) {
    const float d2 = (probe->probe().position - p).squaredNorm();
    if (d2 < best_d2) best = probe.get(), best_d2 = d2;  // ties keep the first listed
  }
  return best;
}

Vec3 Environment::radiance(const ProbeEnvironment* probe, const Vec3& d) const {
  return scale_ * (probe ? probe->radiance(d) : constant_);
}

bool Environment::sample(const ProbeEnvironment* probe, const Vec2& u, Vec3& d, float& pdf_out) const {
  if (probe) return probe->sample(u, d, pdf_out);
  d = sample_uniform_sphere(u);
  pdf_out = 1.0f / (4.0f * kPi);
  return true;
}

float Environment::pdf(const ProbeEnvironment* probe, const Vec3& d) const {
  return probe ? probe->pdf(d) : 1.0f / (4.0f * kPi);
}

}  // namespace relight
