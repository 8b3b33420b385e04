// Direct light of one light over the pixels of a G-buffer, with shadow rays
// traced in coherent packets: the CPU backend of the interactive engine. One
// sample per pixel (the G-buffer's central samples) while a light moves; all
// of a pixel's G-buffer samples and several light samples each to refine.
#pragma once

#include <atomic>
#include <vector>

#include "core/image.h"
#include "render/gbuffer.h"
#include "scene/light.h"

namespace relight {

struct DirectLightSettings {
  int light_samples = 1;  // per surface sample
  // Area lights: the exact unshadowed irradiance (LightSampler::unshadowed_irradiance)
  // times the share of the samples' irradiance that no shadow ray blocks (a
  // ratio estimator: noise only in the penumbrae, none where the light is
  // wholly seen or wholly hidden). A ratio of sums is biased in penumbrae,
  // less the less its sums spread: the samples are stratified (with 4, under
  // 1 % in tests/light_test.cpp's penumbra; 4 at random were 20 % low there).
  // Consistent as the samples grow; off by default so that the engine
  // converges to the integrator's unbiased image.
  bool exact_unshadowed = false;
  uint64_t seed = 1;
  uint64_t pass = 0;      // a different pass draws different light samples
};

// The light `light` sends straight to each pixel's surface, as the radiance a
// white diffuse surface there reflects (irradiance / pi, the integrator's
// direct part): the mean over the pixel's surface samples, 0 where none.
// Returns false, leaving `out` incomplete, when *cancel becomes true.
bool render_direct_light(const PixelSurfaces& surfaces, const RayScene& rays, const Light& light,
                         const DirectLightSettings& settings, Image& out, const std::atomic<bool>* cancel = nullptr);
bool render_direct_light(const GBuffer& gbuffer, const RayScene& rays, const Light& light,
                         const DirectLightSettings& settings, Image& out, const std::atomic<bool>* cancel = nullptr);

// A renderer of one light's direct light over a view's pixels, one surface
// sample per pixel, fast enough to follow a light while it moves: the
// interactive engine's backends (shadow rays here, OpenGL shadow maps in
// src/realtime).
class DirectLightBackend {
 public:
  virtual ~DirectLightBackend() = default;
  virtual const char* name() const = 0;
  // As render_direct_light: irradiance / pi of `light` at each pixel.
  virtual void render(const Light& light, Image& out) = 0;
};

// The CPU backend, for a light that moves (the interactive frame): each
// pixel's light with nothing in the way, from the light's centre (an area
// light's from one point of it), times whether one shadow ray towards a
// point of the light gets through. Half the pixels, a checkerboard, work
// theirs out; each other pixel takes the visibility its four neighbours
// agree on, and their mean light where that agrees within 20 %, when all
// four lie on its own surface. Where they disagree (a shadow's edge, a soft
// shadow, a spot's rim) or a silhouette or crease lies between them, it
// works out its own. A shadow a pixel wide is kept (its pixels' neighbours
// along it and across it disagree); one that falls on a single pixel of the
// second half alone is lost.
class CpuDirectLight final : public DirectLightBackend {
 public:
  // Holds references to both.
  CpuDirectLight(const PixelSurfaces& surfaces, const RayScene& rays);
  const char* name() const override { return "cpu"; }
  void render(const Light& light, Image& out) override;
  // The same; returns the number of shadow rays traced.
  size_t render_counting_rays(const Light& light, Image& out);

 private:
  const PixelSurfaces& surfaces_;
  const RayScene& rays_;
  std::vector<uint8_t> continuing_;  // per pixel, bit k: neighbour k continues its surface (kNeighbourOffsets)
};

// The light with white colour and unit power (or irradiance): its direct
// light scales linearly with emission, so one render serves every colour and
// power.
Light unit_light(const Light& light);

}  // namespace relight
