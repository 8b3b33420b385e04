#include "scene/gloss.h"

#include <algorithm>

namespace relight {

SurfaceGloss::SurfaceGloss(const std::map<std::string, Gloss>& materials, const TriangleMesh& mesh) {
  if (materials.empty()) return;
  // Each name's gloss as an index, for the objects and the materials of the file.
  const auto indices = [&](const std::vector<std::string>& names) {
    std::vector<uint16_t> out(names.size(), kMatte);
    for (size_t k = 0; k < names.size(); ++k)
      if (const auto it = materials.find(names[k]); it != materials.end() && it->second.specular > 0.0f) {
        const auto known = std::find(glosses_.begin(), glosses_.end(), it->second);
        out[k] = uint16_t(known - glosses_.begin());
        if (known == glosses_.end()) glosses_.push_back(it->second);
      }
    return out;
  };
  const std::vector<uint16_t> of_object = indices(mesh.objects), of_material = indices(mesh.materials);
  if (glosses_.empty()) return;
  index_.assign(mesh.triangles.size(), kMatte);
  for (size_t t = 0; t < index_.size(); ++t) {
    if (mesh.has_objects()) index_[t] = of_object[mesh.triangle_objects[t]];
    if (index_[t] == kMatte && mesh.has_materials() && mesh.triangle_materials[t] != TriangleMesh::kNoMaterial)
      index_[t] = of_material[mesh.triangle_materials[t]];
  }
}

size_t SurfaceGloss::glossy_triangles() const {
  return size_t(std::count_if(index_.begin(), index_.end(), [](uint16_t i) { return i != kMatte; }));
}

}  // namespace relight
