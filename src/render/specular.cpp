#include "render/specular.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "render/pixel_estimate.h"

namespace relight {
namespace {

// Whether any sample of the pixel sees a glossy triangle (`samples`: room
// for the pixel's own; filled only where its samples are kept, never
// recomputed).
bool pixel_sees_gloss(const GBuffer& g, int x, int y, const SurfaceGloss& gloss, std::vector<GBufferSample>& samples) {
  if (const std::optional<uint32_t> triangle = g.single_triangle(x, y)) return gloss.at(*triangle);
  if (g.coverage(x, y) <= 0.0f) return false;
  g.pixel_samples(x, y, samples);
  return std::any_of(samples.begin(), samples.end(),
                     [&](const GBufferSample& s) { return s.hit && gloss.at(s.surface.prim); });
}

// Each pixel that sees gloss: its estimates (estimate(surface, path,
// paths, rng)) summed by a Sum, and handed to write(pixel index, sum).
template <class Sum, class Estimate, class Write>
void sum_glossy_pixels(const GBuffer& g, const SurfaceGloss& gloss, int paths_per_pixel, uint64_t seed,
                       Progress& progress, const std::string& label, const Estimate& estimate, const Write& write) {
  const int w = g.width(), h = g.height();
  progress.begin(label, h);
  tbb::parallel_for(0, h, [&](int y) {
    std::vector<GBufferSample> samples;
    for (int x = 0; x < w; ++x) {
      if (!pixel_sees_gloss(g, x, y, gloss, samples)) continue;
      const size_t i = size_t(y) * w + x;
      Rng rng(seed, i, kSpecularStream);
      write(i, sum_pixel<Sum>(g, x, y, paths_per_pixel, rng, estimate));
    }
    progress.advance();
  });
  progress.end();
}

// The two parts' estimates summed apart.
struct PartsSum {
  EstimateSum lights, reflected;
  void add(const SpecularParts& s) {
    lights.add(s.lights);
    reflected.add(s.reflected);
  }
};

}  // namespace

SpecularReflection::SpecularReflection(const Integrator& lights, const SurfaceGloss& gloss,
                                       const ReflectedRadiance& surfaces)
    : lights_(lights), gloss_(gloss), surfaces_(surfaces) {}

SpecularParts SpecularReflection::parts(const SurfacePoint& p, const Vec3& eye, Rng& rng) const {
  const Gloss* gloss = gloss_.at(p.prim);
  if (!gloss) return {};
  const GgxLobe lobe(*gloss);
  const Vec3 v = (eye - p.position).normalized();
  SpecularParts s;
  s.lights = lights_.specular_from_lights(p, lobe, v, rng);
  Vec3 l;
  float weight;
  // A reflected ray below the facet would leave through it: it brings nothing.
  if (!lobe.sample(p.normal, v, rng.uniform2(), l, weight) || l.dot(p.geometric_normal) <= 0.0f) return s;
  const RayScene& rays = lights_.rays();
  SurfacePoint hit;
  s.reflected = weight * (rays.intersect(rays.offset_origin(p, l), l, hit) ? surfaces_(hit, rng)
                                                                           : lights_.environment(p.position, l));
  return s;
}

bool sees_gloss(const GBuffer& gbuffer, const SurfaceGloss& gloss) {
  if (gloss.all_matte()) return false;
  std::vector<GBufferSample> samples;
  for (int y = 0; y < gbuffer.height(); ++y)
    for (int x = 0; x < gbuffer.width(); ++x)
      if (pixel_sees_gloss(gbuffer, x, y, gloss, samples)) return true;
  return false;
}

Image render_specular(const GBuffer& g, const Camera& camera, const SpecularReflection& specular, int paths_per_pixel,
                      uint64_t seed, Progress& progress, const std::string& label) {
  Image image(g.width(), g.height());
  if (specular.gloss().all_matte()) return image;
  sum_glossy_pixels<EstimateSum>(
      g, specular.gloss(), paths_per_pixel, seed, progress, label,
      [&](const SurfacePoint& p, int, int, Rng& r) { return specular.radiance(p, camera.position(), r); },
      [&](size_t i, const EstimateSum& sum) { image.pixels[i] = sum.estimate().mean; });
  return image;
}

SpecularImages render_specular_parts(const GBuffer& g, const Camera& camera, const SpecularReflection& specular,
                                     int paths_per_pixel, uint64_t seed, Progress& progress, const std::string& label) {
  SpecularImages images{Image(g.width(), g.height()), Image(g.width(), g.height())};
  if (specular.gloss().all_matte()) return images;
  sum_glossy_pixels<PartsSum>(
      g, specular.gloss(), paths_per_pixel, seed, progress, label,
      [&](const SurfacePoint& p, int, int, Rng& r) { return specular.parts(p, camera.position(), r); },
      [&](size_t i, const PartsSum& sum) {
        images.lights.pixels[i] = sum.lights.estimate().mean;
        images.reflected.pixels[i] = sum.reflected.estimate().mean;
      });
  return images;
}

MovingHighlights::MovingHighlights(const PixelSurfaces& surfaces, const SurfaceGloss& gloss, const Vec3& eye) {
  if (gloss.all_matte()) return;
  for (size_t i = 0; i < surfaces.surface.size(); ++i) {
    if (!surfaces.hit[i]) continue;
    const SurfacePoint& p = surfaces.surface[i];
    const Gloss* g = gloss.at(p.prim);
    if (!g) continue;
    const GgxLobe lobe(*g);
    const Vec3 to_eye = (eye - p.position).normalized();
    pixels_.push_back(uint32_t(i));
    const Vec3 mirror = 2.0f * p.normal.dot(to_eye) * p.normal - to_eye;
    glossy_.push_back({p.position, p.normal, to_eye, mirror, lobe, lobe.view_terms(p.normal, to_eye)});
  }
}

namespace {

// The radius of the sphere a soft light highlights as: a soft point's, an
// area light's disc of the same area; 0 for a hard point or a sun.
float highlight_radius(const Light& light) {
  switch (light.type) {
    case LightType::point:
    case LightType::spot:
      return light.radius;
    case LightType::area:
      return std::sqrt(light.size.x() * light.size.y() / kPi);
    case LightType::directional:
      return 0.0f;
  }
  return 0.0f;
}

}  // namespace

void MovingHighlights::render(const Light& light, const Image& direct, Image& out) const {
  const LightSampler sampler(light);
  const float radius = highlight_radius(light);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, glossy_.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k != r.end(); ++k) {
      const uint32_t i = pixels_[k];
      const Vec3& d = direct.pixels[i];
      if (d.isZero()) {
        out.pixels[i] = Vec3::Zero();
        continue;
      }
      const GlossyPixel& g = glossy_[k];
      Vec3 l = sampler.direction_to_centre(g.position);
      float scale = kPi;
      // A light wider than the lobe (Karis 2013): the lobe towards the point
      // of its sphere nearest the mirror ray, its peak lowered as the lobe's
      // would be, widened by half the sphere's angular radius. A narrower one
      // highlights as its centre does.
      if (radius > 0.0f) {
        const Vec3 to_centre = light.position - g.position;
        const float distance = to_centre.norm(), alpha = g.lobe.alpha();
        if (radius > alpha * distance && distance > 0.0f) {
          const Vec3 off_mirror = to_centre.dot(g.mirror) * g.mirror - to_centre;
          const float off = off_mirror.norm();
          l = (off > radius ? Vec3(to_centre + (radius / off) * off_mirror) : Vec3(to_centre + off_mirror))
                  .normalized();
          const float widened = std::min(1.0f, alpha + radius / (2.0f * distance));
          scale *= (alpha / widened) * (alpha / widened);
        }
      }
      constexpr float kTail = 1e-3f;
      out.pixels[i] = (scale * g.lobe.brdf(g.normal, l, g.to_eye, g.view, kTail)) * d;
    }
  });
}

}  // namespace relight
