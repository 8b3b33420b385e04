#include "render/specular.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace relight {
namespace {

// The Rng stream of the specular estimates (render_illumination.cpp's are 0-3).
constexpr uint64_t kSpecularStream = 5;

}  // namespace

SpecularReflection::SpecularReflection(const Integrator& lights, const SurfaceGloss& gloss,
                                       const ReflectedRadiance& surfaces)
    : lights_(lights), gloss_(gloss), surfaces_(surfaces) {}

Vec3 SpecularReflection::radiance(const SurfacePoint& p, const Vec3& eye, Rng& rng) const {
  const Gloss* gloss = gloss_.at(p.prim);
  if (!gloss) return Vec3::Zero();
  const GgxLobe lobe(*gloss);
  const Vec3 v = (eye - p.position).normalized();
  const Vec3 from_lights = lights_.specular_from_lights(p, lobe, v, rng);
  Vec3 l;
  float weight;
  // A reflected ray below the facet would leave through it: it brings nothing.
  if (!lobe.sample(p.normal, v, rng.uniform2(), l, weight) || l.dot(p.geometric_normal) <= 0.0f) return from_lights;
  const RayScene& rays = lights_.rays();
  SurfacePoint hit;
  if (rays.intersect(rays.offset_origin(p, l), l, hit)) return from_lights + weight * surfaces_(hit, rng);
  return from_lights + weight * lights_.environment(p.position, l);
}

bool sees_gloss(const GBuffer& gbuffer, const SurfaceGloss& gloss) {
  if (gloss.all_matte()) return false;
  for (int y = 0; y < gbuffer.height(); ++y)
    for (int x = 0; x < gbuffer.width(); ++x)
      if (const GBufferSample s = gbuffer.central(x, y); s.hit && gloss.at(s.surface.prim)) return true;
  return false;
}

Image render_specular(const GBuffer& g, const Camera& camera, const SpecularReflection& specular, int paths_per_pixel,
                      uint64_t seed, Progress& progress, const std::string& label) {
  const int w = g.width(), h = g.height(), spp = g.samples_per_pixel();
  Image image(w, h);
  if (specular.gloss().all_matte()) return image;
  const int paths = std::max(paths_per_pixel, spp);
  progress.begin(label, h);
  tbb::parallel_for(0, h, [&](int y) {
    std::vector<GBufferSample> samples;
    for (int x = 0; x < w; ++x) {
      g.pixel_samples(x, y, samples);
      const bool glossy = std::any_of(samples.begin(), samples.end(), [&](const GBufferSample& s) {
        return s.hit && specular.gloss().at(s.surface.prim);
      });
      if (!glossy) continue;
      const size_t i = size_t(y) * w + x;
      Rng rng(seed, i, kSpecularStream);
      Vec3 sum = Vec3::Zero();
      int hits = 0;
      for (int k = 0; k < paths; ++k) {
        const GBufferSample& s = samples[size_t(k % spp)];
        if (!s.hit) continue;
        sum += specular.radiance(s.surface, camera.position(), rng);
        ++hits;
      }
      if (hits) image.pixels[i] = sum / float(hits);
    }
    progress.advance();
  });
  progress.end();
  return image;
}

}  // namespace relight
