// How much softer the photo is than the render of its illumination. A real
// camera's photo is softer than a path tracer's (the lens, the sensor's
// anti-aliasing filter, demosaicing, a resize), by a pixel or so; divided
// by the sharp illumination, it leaves a bright and a dark line beside
// every shadow edge and silhouette, in the albedo and in every re-lit
// image. The blur is measured as the Gaussian that, applied to the
// illumination, leaves the albedo smoothest across the illumination's own
// edges, and the illumination divided by is blurred alike.
#pragma once

#include <cmath>

#include "core/image.h"
#include "render/gbuffer.h"
#include "render/render_illumination.h"

namespace relight {

struct PhotoBlur {
  float sigma_px = 0.0f;  // the Gaussian's standard deviation, pixels; 0: as sharp as the render
  // The median change of log albedo between neighbouring pixels by the
  // illumination's edges, divided by the sharp illumination and by the
  // blurred one.
  float roughness_sharp = 0.0f, roughness_blurred = 0.0f;
  size_t edge_pixels = 0;  // the pixels it was measured over
};

// The candidate blurs (0.5 to 2 pixels) against none, over the pixels within
// 2 of a step of 0.3 in the illumination's log luminance (35 %); a blur is
// taken where it lowers the median roughness there by kSofterShare.
constexpr float kSofterShare = 0.15f;
PhotoBlur measure_photo_blur(const Image& photo, const IlluminationImages& illumination, const GBuffer& gbuffer);

// `image` blurred by a Gaussian of standard deviation sigma_px (OpenCV's).
Image gaussian_blur(const Image& image, float sigma_px);

// `image` with a Gaussian blur of sigma_px undone as far as it can be
// without amplifying noise: u = argmin |G u - image|^2 + k |Laplacian u|^2
// (Tikhonov's regularisation, k = kDeblurSmoothness), solved exactly in the
// Fourier domain (OpenCV's DFT) over the image mirrored at its borders.
// The Laplacian's penalty leaves a region of one colour as it is and holds
// back the fine detail a blur all but erased.
Image deblur(const Image& image, float sigma_px);
constexpr float kDeblurSmoothness = 0.01f;
// How far deblur reaches (and mirrors the image beyond its borders): beyond
// it the filter's response is 0.2 % of its absolute sum at 1 and 2 pixels.
inline int deblur_reach_px(float sigma_px) { return int(std::ceil(12.0f * sigma_px)) + 4; }

// The illumination as a photo blurred by sigma_px sees it: each pixel's
// surface and background parts blurred with their coverage (photo =
// blur(c a L) + blur((1 - c) B), the albedo locally constant), and divided
// by the pixel's own coverage so that recover_albedo's division holds.
IlluminationImages blur_illumination(const IlluminationImages& illumination, const GBuffer& gbuffer, float sigma_px);

}  // namespace relight
