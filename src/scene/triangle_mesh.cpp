#include "scene/triangle_mesh.h"

#include <unordered_map>

namespace relight {

std::vector<uint32_t> same_position_ids(const std::vector<Vec3>& positions) {
  struct PositionHash {
    size_t operator()(const Vec3& p) const {
      return std::hash<float>()(p.x()) ^ (std::hash<float>()(p.y()) << 1) ^ (std::hash<float>()(p.z()) << 2);
    }
  };
  struct PositionEqual {
    bool operator()(const Vec3& a, const Vec3& b) const { return a == b; }
  };
  std::unordered_map<Vec3, uint32_t, PositionHash, PositionEqual> first;
  std::vector<uint32_t> ids(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) ids[i] = first.try_emplace(positions[i], uint32_t(i)).first->second;
  return ids;
}

}  // namespace relight
