// The whole image-based refinement of thesis chapter 4 for one photo: clip
// the scene mesh to the view, subdivide it along the photo's shadow edges,
// relax it towards them.
#pragma once

#include "mesh/clip.h"
#include "mesh/relax.h"
#include "mesh/subdivide.h"

namespace relight {

struct RefineOptions {
  SubdivisionOptions subdivision;
  RelaxOptions relax;
};

struct RefineReport {
  MeshCleanup cleanup;
  size_t triangles_input = 0;    // after cleaning
  size_t triangles_clipped = 0;  // in view, before subdivision
  ClipStats clip;
  SubdivisionStats subdivision;
  RelaxStats relax;
  double seconds = 0;  // clip, subdivide and relax
};

ConnectivityMesh refine_mesh_for_photo(const TriangleMesh& mesh, const Camera& camera, const PhotoSamples& photo,
                                       const RefineOptions& options, RefineReport& report);

}  // namespace relight
