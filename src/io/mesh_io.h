// Scene geometry through Assimp (OBJ, PLY, glTF/GLB, FBX, ...): flattened to
// one triangle mesh in the world frame, validated and cleaned.
#pragma once

#include <filesystem>
#include <vector>

#include "core/progress.h"
#include "scene/triangle_mesh.h"

namespace relight {

// Loads every triangle of the file with node transforms applied (a mesh two
// nodes place is there twice), each keeping its node's name as its object
// (TriangleMesh::objects). Throws
// InputError for a missing/unreadable file, no triangles, non-finite or
// out-of-range (> 1e7 m) vertices, a face index past the vertices, or
// degenerate (zero-area) triangles — unless repair_meshes() is on, which
// drops those with a warning (a mesh of nothing else stays an error).
// Non-manifold edges (three or more triangles on one) get a warning: the
// ray tracer needs no closed solids (surfaces are two-sided), and real
// scenes have them (the reference bookcase's shelves meet its sides so).
// The file is read in a child process bounded in time and memory
// (mesh_reader_memory_limit); throws Cancelled, the child killed, as soon as
// `progress` is cancelled (a Ctrl-C) while it reads.
TriangleMesh load_mesh(const std::filesystem::path& path, const Progress& progress = Progress::silent());

// The address space the mesh reader may take for a file of `file_bytes`:
// 1 GiB plus 64 bytes per byte of the file. A sound file needs far less
// (docs/reliability.md gives the figures); a header claiming millions of
// elements in a few bytes runs into it at once.
uint64_t mesh_reader_memory_limit(uint64_t file_bytes);

// Whether load_mesh drops degenerate triangles instead of refusing the mesh
// (the CLI's --repair-mesh or RELIGHT_REPAIR_MESH). Off by default.
bool repair_meshes();
void set_repair_meshes(bool repair);

// Writes the mesh as Wavefront OBJ (with normals when it has them), atomically.
void save_obj(const std::filesystem::path& path, const TriangleMesh& mesh);

// The indices of the zero-area triangles and ones with repeated vertices.
std::vector<size_t> degenerate_triangles(const TriangleMesh& mesh);

// The edges (between vertices at the same positions) that three or more
// triangles share.
size_t count_non_manifold_edges(const TriangleMesh& mesh);

}  // namespace relight
