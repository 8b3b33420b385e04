// The whole image-based refinement of thesis chapter 4 for one photo: clip
// the scene mesh to the view, subdivide it along the photo's shadow edges,
// relax it towards them.
#pragma once

#include "mesh/clip.h"
#include "mesh/relax.h"
#include "mesh/subdivide.h"

namespace relight {

struct RefineOptions {
  // Before subdividing along the photo, split every edge longer than this
  // many pixels in the photo (0: none). A radiosity solution, which
  // interpolates across triangles, needs them small and rounder everywhere,
  // not only where the photo changes.
  float max_edge_px = 0.0f;
  SubdivisionOptions subdivision;
  RelaxOptions relax;
};

struct RefineReport {
  MeshCleanup cleanup;
  size_t triangles_input = 0;    // after cleaning
  size_t triangles_clipped = 0;  // in view, before subdivision
  ClipStats clip;
  size_t long_edges_split = 0;  // by max_edge_px
  SubdivisionStats subdivision;
  RelaxStats relax;
  double seconds = 0;  // clip, subdivide and relax
};

ConnectivityMesh refine_mesh_for_photo(const TriangleMesh& mesh, const Camera& camera, const PhotoSamples& photo,
                                       const RefineOptions& options, RefineReport& report);

}  // namespace relight
