// Clipping the mesh to the camera's view (thesis 4.3): edges crossing a side
// of the view frustum (or the near plane) are split where they cross it, and
// the triangles left outside are dropped, so connectivity is kept throughout.
#pragma once

#include "mesh/connectivity_mesh.h"
#include "scene/camera.h"

namespace relight {

struct ClipStats {
  size_t edges_split = 0;
  size_t triangles_dropped = 0;
};

// Clips to the image border and to `near` metres in front of the camera.
ClipStats clip_to_view(ConnectivityMesh& mesh, const Camera& camera, float near = 1e-3f);

}  // namespace relight
