// Environment: the light arriving from everything the geometry does not model
// — a constant background or light probes — evaluated and importance-sampled
// by direction. With several probes a point uses the nearest one.
#pragma once

#include <memory>
#include <vector>

#include "core/sampling.h"
#include "scene/probe.h"

namespace relight {

// One probe prepared for rendering: its frame and a 2D distribution over its
// pixels proportional to luminance x solid angle.
class ProbeEnvironment {
 public:
  explicit ProbeEnvironment(const Probe& probe);
  // `probe`, which shows the same image as `same_image` in another frame (a
  // turned sky): the sampling table, a function of image positions alone,
  // is taken over instead of built again.
  ProbeEnvironment(const ProbeEnvironment& same_image, const Probe& probe);
  Vec3 radiance(const Vec3& d) const;
  // Samples a direction; returns false where the sample fell outside the image.
  bool sample(const Vec2& u, Vec3& d, float& pdf) const;
  float pdf(const Vec3& d) const;
  const Probe& probe() const { return probe_; }

 private:
  Probe probe_;
  ProbeFrame frame_;
  Distribution2D distribution_;
};

class Environment {
 public:
  // A constant radiance from every direction.
  static Environment constant(const Vec3& radiance);
  static Environment from_probes(const std::vector<Probe>& probes);
  // This one-probe environment with its image in the frame of `probe`, which
  // shows the same image (see ProbeEnvironment's).
  Environment turned(const Probe& probe) const;

  // All radiance is multiplied by `scale` (the rig's environment_scale).
  void set_scale(float scale) { scale_ = scale; }
  float scale() const { return scale_; }
  bool is_black() const { return scale_ == 0.0f || (probes_.empty() && constant_.isZero()); }
  bool uses_probes() const { return !probes_.empty(); }

  // The probe serving point p (nullptr for a constant environment).
  const ProbeEnvironment* probe_for(const Vec3& p) const;
  Vec3 radiance(const ProbeEnvironment* probe, const Vec3& d) const;
  bool sample(const ProbeEnvironment* probe, const Vec2& u, Vec3& d, float& pdf) const;
  float pdf(const ProbeEnvironment* probe, const Vec3& d) const;

 private:
  Vec3 constant_ = Vec3::Zero();
  std::vector<std::shared_ptr<const ProbeEnvironment>> probes_;
  float scale_ = 1.0f;
};

}  // namespace relight
