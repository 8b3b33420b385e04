// Renders the illumination of every pixel of a G-buffer: the mean, over the
// pixel's samples that see geometry, of the light a white diffuse surface
// there would reflect; and the mean environment radiance over those that see
// the background. Multithreaded, deterministic for a seed.
#pragma once

#include "core/image.h"
#include "core/progress.h"
#include "render/denoise.h"
#include "render/gbuffer.h"
#include "render/integrator.h"

namespace relight {

struct IlluminationImages {
  Image surface;     // mean illumination over the geometry samples (0 where none)
  Image background;  // mean environment radiance over the background samples (0 where none)
};

struct IlluminationOptions {
  int paths_per_pixel = 64;  // spread evenly over the pixel's G-buffer samples
  uint64_t seed = 1;
  bool denoise = true;       // filter the environment + interreflection part
};

// A synthetic photo: each camera sample's illumination times the albedo of
// the surface it sees, the environment where it sees none; no denoising.
// Used to make scenes with a known albedo (the example, round-trip tests).
Image synthesize_photo(const GBuffer& gbuffer, const Camera& camera, const Integrator& integrator,
                       const SurfaceAlbedo& albedo, int paths_per_pixel, uint64_t seed, Progress& progress);

// The mean environment radiance over each pixel's samples that see the
// background (0 where none does): IlluminationImages::background.
Image render_background(const GBuffer& gbuffer, const Camera& camera, const Integrator& integrator);

// The illumination over the geometry in its two parts, each denoised as
// render_illumination does: the light straight from the lights, and the rest
// (the environment and all interreflection). render_illumination's surface
// is their sum.
struct IlluminationParts {
  Image direct, indirect;
  Image total() const;  // direct + indirect
};
IlluminationParts render_illumination_parts(const GBuffer& gbuffer, const Integrator& integrator,
                                            const IlluminationOptions& options, Progress& progress,
                                            const std::string& label = "illumination");

IlluminationImages render_illumination(const GBuffer& gbuffer, const Camera& camera, const Integrator& integrator,
                                       const IlluminationOptions& options, Progress& progress,
                                       const std::string& label = "illumination");

}  // namespace relight
