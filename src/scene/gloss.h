// Gloss: the specular layer of a surface that shines (scene.json's
// `materials`), and which triangles of the scene have one. Everything else
// is matte (Lambertian), as the thesis takes every surface to be.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "scene/triangle_mesh.h"

namespace relight {

// The two numbers Blender's Principled BSDF gives a dielectric's shine:
// roughness (GGX, alpha = roughness squared) and specular (the reflectance
// at normal incidence is 0.08 x specular: 0.5 is 4 %, an index of 1.5).
struct Gloss {
  float roughness = 0.5f;
  float specular = 0.5f;
  bool operator==(const Gloss&) const = default;
};

// Each triangle's gloss, or none (matte).
class SurfaceGloss {
 public:
  SurfaceGloss() = default;  // every surface matte
  // The glosses named in `materials` put on the triangles of `mesh` whose
  // object or material has that name (an object's name first: it is the
  // more particular).
  SurfaceGloss(const std::map<std::string, Gloss>& materials, const TriangleMesh& mesh);

  // nullptr where the triangle is matte.
  const Gloss* at(uint32_t triangle) const {
    if (triangle >= index_.size() || index_[triangle] == kMatte) return nullptr;
    return &glosses_[index_[triangle]];
  }
  bool all_matte() const { return glosses_.empty(); }
  size_t glossy_triangles() const;

 private:
  static constexpr uint16_t kMatte = 0xffff;
  std::vector<Gloss> glosses_;
  std::vector<uint16_t> index_;  // per triangle: into glosses_, or kMatte
};

}  // namespace relight
