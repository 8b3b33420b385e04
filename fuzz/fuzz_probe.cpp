// Fuzzes the probe mappings and the probe environment (scene/probe.h,
// scene/environment.h) with the probes the loader lets through: either
// mapping, the right aspect, any frame whose forward and up are not
// parallel, pixels anywhere from 0 to the largest value the loader accepts. Every
// lookup, sample and density must stay finite and in range.
#include <cmath>

#include "fuzz_support.h"
#include "scene/environment.h"

using namespace relight;
using relight::fuzz::ByteReader;
using relight::fuzz::check;

namespace {

// A unit vector, or nothing where the bytes give (almost) zero.
std::optional<Vec3> direction(ByteReader& in) {
  const Vec3 v(in.in_range(-1, 1), in.in_range(-1, 1), in.in_range(-1, 1));
  if (v.norm() < 1e-3f) return std::nullopt;
  return v.normalized();
}

// A pixel value as the loader lets through: 0, or 2^e for e in [-126, 66]
// (read_image refuses values over kMaxPixelValue = 1e20).
float radiance(ByteReader& in) {
  const uint8_t b = in.byte();
  return b == 0 ? 0.0f : std::ldexp(1.0f, -126 + int(b) % 193);
}

bool in_unit_square(const Vec2& uv) { return uv.x() >= 0 && uv.x() <= 1 && uv.y() >= 0 && uv.y() <= 1; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  ByteReader in(data, size);
  Probe probe;
  probe.mapping = (in.byte() & 1) ? ProbeMapping::mirrorball : ProbeMapping::equirect;
  const int height = 1 + in.byte() % 16;
  const int width = probe.mapping == ProbeMapping::equirect ? 2 * height : height;
  const auto forward = direction(in), up = direction(in);
  if (!forward || !up || forward->cross(*up).norm() < 1e-4f) return 0;  // the loader refuses these
  probe.forward = *forward;
  probe.up = *up;
  probe.position = Vec3(in.in_range(-10, 10), in.in_range(-10, 10), in.in_range(-10, 10));
  probe.image = Image(width, height);
  for (Vec3& p : probe.image.pixels) p = Vec3(radiance(in), radiance(in), radiance(in));

  const ProbeFrame frame(probe.forward, probe.up);
  const ProbeEnvironment env(probe);
  while (in.left() > 0) {
    const auto d = direction(in);
    if (!d) continue;
    const Vec2 uv = probe_direction_to_uv(probe.mapping, frame, *d);
    check(in_unit_square(uv), "a direction maps into the image");
    if (probe.mapping == ProbeMapping::equirect && std::abs(d->dot(frame.up)) < 0.99f) {
      const auto back = probe_uv_to_direction(probe.mapping, frame, uv);
      check(back && (*back - *d).norm() < 1e-3f, "equirect: direction -> uv -> direction is the identity");
    }
    check(std::isfinite(probe_pixel_solid_angle(probe.mapping, uv, width, height)), "pixel solid angles are finite");
    const Vec3 l = env.radiance(*d);
    check(is_finite(l) && (l.array() >= 0.0f).all(), "radiance is finite and >= 0");
    const float pdf = env.pdf(*d);
    check(std::isfinite(pdf) && pdf >= 0.0f, "the density of a direction is finite and >= 0");

    const Vec2 u(in.unit(), in.unit());
    Vec3 sampled;
    float sample_pdf = 0.0f;
    if (env.sample(u, sampled, sample_pdf)) {
      check(is_finite(sampled) && std::abs(sampled.norm() - 1.0f) < 1e-3f, "a sampled direction is a unit vector");
      check(std::isfinite(sample_pdf) && sample_pdf > 0.0f, "a sample's density is finite and > 0");
    }
  }
  return 0;
}
