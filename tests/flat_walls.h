// A camera facing walls (axis-aligned rectangles facing it), for tests that
// need a G-buffer of known surfaces: the camera at the origin looks along +y
// with z up.
#pragma once

#include <vector>

#include "render/gbuffer.h"
#include "render/ray_scene.h"

namespace relight::test {

// A wall at depth y spanning x in [x0, x1] and z in [-10, 10], facing the camera (normal -y).
struct Wall {
  float y, x0, x1;
};

inline TriangleMesh walls_mesh(const std::vector<Wall>& walls) {
  TriangleMesh mesh;
  for (const Wall& w : walls) {
    const auto base = uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(),
                          {Vec3(w.x0, w.y, -10), Vec3(w.x1, w.y, -10), Vec3(w.x1, w.y, 10), Vec3(w.x0, w.y, 10)});
    // Wound so that the normal, (b - a) x (c - a), points at the camera.
    mesh.triangles.push_back({base, base + 2, base + 1});
    mesh.triangles.push_back({base, base + 3, base + 2});
  }
  return mesh;
}

inline Camera walls_camera(int width, int height) {
  CameraSpec spec;
  spec.vfov_deg = 40.0f;
  return Camera(spec, width, height);
}

}  // namespace relight::test
