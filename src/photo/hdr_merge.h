// Exposure brackets merged into one linear HDR photo: the camera's response
// curve recovered from the brackets themselves (Debevec & Malik 1997), the
// brackets aligned to the middle one first (Ward's median threshold bitmaps)
// where the tripod moved.
#pragma once

#include <array>
#include <vector>

#include "core/image.h"
#include "io/image_io.h"

namespace relight {

struct MergedBrackets {
  Image radiance;  // linear, up to one global scale (the camera's unknown gain)
  // The recovered inverse response: ln(exposure) for each code 0-255, per channel.
  std::array<std::vector<float>, 3> log_response;
  // The shift (x, y) in pixels applied to each bracket to align it.
  std::vector<std::array<int, 2>> shifts;
};

// `brackets` (at least two, all of one size) taken with exposure times
// `times` (seconds, > 0). align: find and undo whole-pixel shifts between them.
MergedBrackets merge_brackets(const std::vector<EncodedImage>& brackets, const std::vector<float>& times, bool align);

}  // namespace relight
