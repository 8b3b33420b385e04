// Scene geometry through Assimp (OBJ, PLY, glTF/GLB, FBX, ...): flattened to
// one triangle mesh in the world frame, validated and cleaned.
#pragma once

#include <filesystem>

#include "scene/triangle_mesh.h"

namespace relight {

// Loads every triangle of the file with node transforms applied. Throws
// InputError for a missing/unreadable file, no triangles, non-finite or
// out-of-range (> 1e7 m) vertices, or a face index past the vertices.
// Degenerate (zero-area) triangles are dropped with a warning; a mesh whose
// triangles are all degenerate is an error. Non-manifold meshes are fine:
// surfaces are two-sided, so the ray tracer needs no closed solids.
TriangleMesh load_mesh(const std::filesystem::path& path);

// Writes the mesh as Wavefront OBJ (with normals when it has them), atomically.
void save_obj(const std::filesystem::path& path, const TriangleMesh& mesh);

// Removes zero-area triangles and ones with repeated vertices; returns how many.
size_t remove_degenerate_triangles(TriangleMesh& mesh);

}  // namespace relight
