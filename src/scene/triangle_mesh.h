// TriangleMesh: the scene geometry as loaded (world frame, metres), with
// optional per-vertex shading normals (smooth-shaded spheres keep them).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/vec.h"

namespace relight {

struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  // empty, or one per position
  std::vector<std::array<uint32_t, 3>> triangles;

  bool has_normals() const { return !normals.empty(); }
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
