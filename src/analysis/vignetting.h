// The photo's vignetting: a lens passes less light towards the corners of
// its image (a photo taken wide open is often a stop darker there), and the
// albedo would carry that darkening as if the surfaces were darker. A probe
// in the scene sees the same matte surfaces with no such falloff across the
// photo, so photo / probe over the points both show is the probe's exposure
// times the photo's falloff at each point's place in the photo: fitted as
// log falloff = a r^2 + b r^4 (r: the distance from the photo's centre over
// its half diagonal) plus the probe's log exposure, robustly.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "analysis/probe_exposure.h"
#include "core/image.h"

namespace relight {

struct Vignetting {
  float r2 = 0.0f, r4 = 0.0f;  // log falloff = r2 r^2 + r4 r^4
  // The falloff at pixel (x, y) of a w x h photo: at most 1, at least
  // kMaxVignetting's, whatever the polynomial does beyond the points fitted.
  float at(int x, int y, int w, int h) const;
  // At the corners.
  float corner() const;
};

// A falloff at the corners smaller than kExposureTolerance is left in the
// photo (a third of a stop is 26 %); one that stands fewer than
// kMinVignettingSignificance standard errors (a jackknife over the photo's
// blocks) clear of none is too, and so is one fitted over points that do
// not reach kMinVignettingReach of the way to the corners in at least
// kMinVignettingBlocks of the photo's blocks. More than kMaxVignetting is
// not a lens's (two stops): it is reported, not divided out.
inline constexpr float kMinVignettingSignificance = 4.5f;
inline constexpr float kMinVignettingReach = 0.6f;
inline constexpr size_t kMinVignettingBlocks = 10;
inline constexpr float kMaxVignetting = 0.25f;

// The fit over the points a probe shares with `photo`
// (points_shared_with_photo) and what it found; nothing where fewer than
// kMinExposurePoints are usable.
struct VignettingFit {
  Vignetting falloff;
  float significance = 0.0f;  // of log corner(), in jackknife standard errors
  size_t points = 0, outer_blocks = 0;
};
std::optional<VignettingFit> fit_vignetting(const std::vector<SharedPoint>& shared, const Image& photo);

// Whether a fit's falloff is one to divide out: it darkens the corners
// clearly and no more than a lens does.
bool is_lens_vignetting(const VignettingFit& fit);

// The falloff of `fit` where it is a lens's vignetting; otherwise nothing.
// Either way a line in the log says what was found (a warning where it is
// divided out, or too strong to be a lens's). `scene_path` names the scene.
std::optional<Vignetting> photo_vignetting(const VignettingFit& fit, const std::string& scene_path);

// Each pixel of `photo` divided by its falloff.
void remove_vignetting(Image& photo, const Vignetting& v);

}  // namespace relight
