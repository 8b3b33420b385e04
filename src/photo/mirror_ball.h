// A light probe from a photo of a chrome ball: the ball's circle found in the
// photo and the square crop whose disc touches the edges, the layout of
// FORMAT.md's "mirrorball" mapping.
#pragma once

#include "core/image.h"

namespace relight {

// In image coordinates: (0, 0) the top-left corner of the top-left pixel,
// pixel (col, row) covering [col, col+1) x [row, row+1).
struct Circle {
  double cx = 0, cy = 0, r = 0;
};

// The most prominent circle of the photo (Hough transform on the log
// luminance's edges), refined to sub-pixel accuracy by a least-squares fit
// to the strongest edge along rays from its centre. Throws InputError
// naming `name` when the photo shows no circle.
Circle find_mirror_ball(const Image& photo, const std::string& name);

// The square image of side round(2r) showing the disc `ball` (bilinear
// resampling); pixels outside the disc are black.
Image crop_mirror_ball(const Image& photo, const Circle& ball);

}  // namespace relight
