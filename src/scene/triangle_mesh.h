// TriangleMesh: the scene geometry as loaded (world frame, metres), with
// optional per-vertex shading normals (smooth-shaded spheres keep them).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec.h"

namespace relight {

struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  // empty, or one per position
  std::vector<std::array<uint32_t, 3>> triangles;
  // The objects of the file (its nodes' names: Blender's object names), and
  // for each triangle the index of its object in `objects`; has_objects()
  // is false where a mesh was made rather than read (refined, subdivided).
  std::vector<std::string> objects;
  std::vector<uint32_t> triangle_objects;
  // Likewise the materials the file names (Blender's material names) and
  // each triangle's; kNoMaterial where the file gives a triangle none.
  std::vector<std::string> materials;
  std::vector<uint32_t> triangle_materials;
  static constexpr uint32_t kNoMaterial = 0xffffffffu;

  bool has_normals() const { return !normals.empty(); }
  bool has_objects() const { return !triangles.empty() && triangle_objects.size() == triangles.size(); }
  bool has_materials() const { return !triangles.empty() && triangle_materials.size() == triangles.size(); }
  Eigen::AlignedBox3f bounds() const {
    Eigen::AlignedBox3f box;
    for (const auto& p : positions) box.extend(p);
    return box;
  }
};

// For each position, the index of the first position exactly equal to it:
// the vertices a file repeats where normals or texture coordinates differ
// are one point.
std::vector<uint32_t> same_position_ids(const std::vector<Vec3>& positions);

}  // namespace relight
