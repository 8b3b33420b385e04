// The simulated illumination's edges moved onto the photo's. A camera
// matched a few pixels off puts a shadow's boundary (or a silhouette or
// crease the light differs across) a few pixels from where the photo shows
// it, and photo / illumination then leaves a bright and a dark line along it.
// Each edge of the illumination is matched to the photo's nearest edge
// (running the same way, its bright side on the same side, of a like
// contrast); the matches together give the image's motion (a shift, scale
// and turn: how a camera a little off moves everything); where the motion
// says an edge lies more than a pixel off and the edge's own match agrees,
// the illumination around it is taken from as far back as the photo's edge
// lies ahead. The division then sees the edge where the photo has it, and
// the texture under it survives. docs/algorithms.md, "Edges the photo shows
// elsewhere".
#pragma once

#include <vector>

#include "analysis/photo_edges.h"
#include "core/image.h"

namespace relight {

class IlluminationAlignment {
 public:
  explicit IlluminationAlignment(const Image& photo);  // the photo's edges, found once

  struct Mismatch {
    std::vector<uint8_t> moved;  // 1 per pixel whose illumination align() takes from elsewhere
    float motion_px = 0.0f;      // how far the photo's edges lie from the illumination's: the motion's
                                 // largest length over the image, pixels
  };
  // Where the illumination's edges lie off the photo's, and how far; nothing moved.
  Mismatch mismatch(const Image& surface_illumination) const;
  struct Aligned {
    Image illumination;  // the surface illumination, its edges where the photo has them
    Mismatch mismatch;
  };
  Aligned align(const Image& surface_illumination) const;

  // An edge pixel of the illumination and its counterpart in the photo.
  struct EdgeMatch {
    int x, y;
    Vec2 normal;   // the illumination's gradient, unit
    float offset;  // to the photo's edge along `normal`, pixels (to a fraction)
  };

 private:
  std::vector<EdgeMatch> edge_matches(const Image& surface_illumination) const;
  // The matches the image's motion confirms, each an edge to move, and the
  // motion's largest length (Mismatch::motion_px).
  struct Moving {
    std::vector<EdgeMatch> edges;
    float motion_px = 0.0f;
  };
  Moving moving_edges(const Image& surface_illumination) const;

  EdgeField photo_edges_;  // full resolution
};

}  // namespace relight
