// Denoising the smooth part of the illumination (environment and
// interreflection): an edge-avoiding a-trous wavelet filter (Dammertz et al.
// 2010) guided by the G-buffer — it never mixes pixels of different surfaces
// (normal and plane tests) — with a luminance weight scaled by each pixel's
// estimated noise (Schied et al. 2017), so real gradients and soft shadows
// stay while Monte Carlo noise goes.
#pragma once

#include <vector>

#include "core/image.h"
#include "core/progress.h"
#include "render/gbuffer.h"

namespace relight {

struct DenoiseOptions {
  int passes = 5;               // filter footprint 2^(passes+1)+1 pixels
  float luminance_sigma = 4.0f; // in standard deviations of the noise
  float normal_power = 64.0f;
  float plane_sigma = 0.01f;    // plane distance, relative to the depth
  const Progress* progress = nullptr;  // if given, polled between passes: throws Cancelled once cancelled
};

// variance: per pixel, the variance of the pixel's mean luminance.
// surfaces: what each pixel of `noisy` sees (a G-buffer's centre samples, or
// the pixels a sparse render traced).
Image denoise_illumination(const Image& noisy, std::vector<float> variance, const PixelSurfaces& surfaces,
                           const DenoiseOptions& options = {});
inline Image denoise_illumination(const Image& noisy, std::vector<float> variance, const GBuffer& gbuffer,
                                  const DenoiseOptions& options = {}) {
  return denoise_illumination(noisy, std::move(variance), PixelSurfaces::central_samples(gbuffer), options);
}

}  // namespace relight
