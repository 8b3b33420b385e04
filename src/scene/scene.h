// Scene: everything scene.json describes, loaded and validated — the photo,
// the geometry, the camera bound to the photo, the principal lights, the
// background and the probes.
#pragma once

#include <filesystem>
#include <vector>

#include "core/image.h"
#include "scene/camera.h"
#include "scene/light.h"
#include "scene/probe.h"
#include "scene/triangle_mesh.h"

namespace relight {

struct Scene {
  std::filesystem::path path;  // the scene.json it came from
  Image photo;
  std::filesystem::path photo_path, geometry_path;
  TriangleMesh mesh;
  Camera camera;
  std::vector<Light> lights;
  Vec3 background = Vec3::Zero();
  std::vector<Probe> probes;
};

// A lighting design: rig.json.
struct Rig {
  float environment_scale = 1.0f;
  std::vector<Light> lights;
};

}  // namespace relight
