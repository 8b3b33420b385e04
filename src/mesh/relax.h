// Mesh relaxation (thesis 4.4): each free vertex climbs the photo's gradient
// magnitude (the uphill maximum gradient path of VPR) towards the nearest
// shadow edge, a pixel at a time, staying in the plane of its triangles;
// a move that would flip a triangle in the image is refused.
#pragma once

#include <vector>

#include "mesh/connectivity_mesh.h"
#include "mesh/photo_samples.h"
#include "scene/camera.h"

namespace relight {

struct RelaxOptions {
  int iterations = 2;    // passes over the vertices
  int max_steps_px = 3;  // pixels a vertex may climb per pass
  FlipTest flip_test = FlipTest::side_of_edge;
};

struct RelaxStats {
  size_t vertices_moved = 0;
  size_t moves_refused = 0;  // by the flip test, or leaving a triangle under half a pixel high
};

// The gradient magnitude of the photo's log intensity (Sobel), per pixel:
// a shadow scales the light, so its edge is as steep in bright and dark parts.
std::vector<float> log_gradient_magnitude(const PhotoSamples& photo);

// The end of the uphill path from pixel (x, y) over `height` (width x
// height_px values): at most max_steps moves to the highest of the eight
// neighbours while that is higher than the current pixel.
Eigen::Vector2i climb(const std::vector<float>& height, int width, int height_px, int x, int y, int max_steps);

// Moves the interior vertices whose triangles are coplanar and visible.
RelaxStats relax_towards_shadow_edges(ConnectivityMesh& mesh, const Camera& camera, const PhotoSamples& photo,
                                      const RelaxOptions& options);

}  // namespace relight
