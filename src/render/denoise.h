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
  // The G-buffer's overload filters this many rows at a time (0: about 4
  // Mpixel's worth); the result does not depend on it.
  int band_rows = 0;
};

// variance: per pixel, the variance of the pixel's mean luminance.
// surfaces: what each pixel of `noisy` sees (a G-buffer's centre samples, or
// the pixels a sparse render traced).
Image denoise_illumination(const Image& noisy, std::vector<float> variance, const PixelSurfaces& surfaces,
                           const DenoiseOptions& options = {});
// The same, the surfaces a G-buffer's centre samples. The image is filtered
// in bands of rows, each with the rows the filter reaches beyond it, so that
// what it holds besides the images grows with the band, not the view: the
// result is the whole image's filtered at once, bit for bit.
Image denoise_illumination(const Image& noisy, const std::vector<float>& variance, const GBuffer& gbuffer,
                           const DenoiseOptions& options = {});

}  // namespace relight
