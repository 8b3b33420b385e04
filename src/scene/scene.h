// Scene: everything scene.json describes, loaded and validated — the photo,
// the geometry, the camera bound to the photo, the principal lights, the
// background and the probes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "core/image.h"
#include "scene/camera.h"
#include "scene/gloss.h"
#include "scene/light.h"
#include "scene/probe.h"
#include "scene/triangle_mesh.h"

namespace relight {

// A surface of known albedo the photo shows (a grey card): the polygon
// (photo pixels, x right and y down from the top-left corner) and its albedo.
// Or an object of the geometry of that albedo (the pixels that see only it).
// Or a colour chart of known patches: the four outer corners of an X-Rite
// ColorChecker Classic (analysis/color_chart.h), polygon and albedo unused.
struct AlbedoReference {
  std::vector<Vec2> polygon;
  std::string object;  // a name in TriangleMesh::objects, or empty (the polygon)
  Vec3 albedo = Vec3::Constant(0.18f);
  std::vector<Vec2> colorchecker;  // empty, or the chart's 4 corners
};

// One frame of a shot (scene.json's optional `shot`): a photo of the same
// scene from a moving camera.
struct ShotFrame {
  int number = 0;  // the frame's number, as the photo's file name gives it
  std::filesystem::path photo_path;
  CameraSpec camera;
};

// A tracked shot: its frames, in order, numbered on from the first.
struct Shot {
  std::filesystem::path photo_pattern;  // '#'s for the frame number
  std::vector<ShotFrame> frames;        // empty: the scene is a still
};

struct Scene {
  std::filesystem::path path;  // the scene.json it came from
  Image photo;
  // 1 where an 8/16-bit photo's pixel has a channel at the top code value:
  // unreliable, never divided into albedo. Empty for an HDR photo.
  std::vector<uint8_t> photo_clipped;
  std::filesystem::path photo_path, geometry_path;
  TriangleMesh mesh;
  Camera camera;
  std::vector<Light> lights;
  Vec3 background = Vec3::Zero();
  std::vector<Probe> probes;
  std::optional<AlbedoReference> reference;  // scene.json's optional `reference`
  // scene.json's optional `materials`: the surfaces that shine, by object or
  // material name, and put on the mesh's triangles.
  std::map<std::string, Gloss> materials;
  SurfaceGloss gloss;
  // A tracked shot's frames (none: a still). Their photos are read one at a
  // time (load_shot_frame), not with the scene.
  Shot shot;
};

// Sets the scene's `materials` and puts them on its mesh's triangles (`gloss`).
inline void set_materials(Scene& scene, std::map<std::string, Gloss> materials) {
  scene.materials = std::move(materials);
  scene.gloss = SurfaceGloss(scene.materials, scene.mesh);
}

// A rig's new environment (FORMAT.md, "A new environment in a rig"): a
// constant radiance, or an image mapped as a probe's (its position unused:
// the environment is infinitely distant). Shared: rigs are copied on every
// edit in the studio, the image is not.
struct RigEnvironment {
  Vec3 color = Vec3::Zero();
  std::shared_ptr<const Probe> image;  // null: the constant color
};

// A lighting design: rig.json.
struct Rig {
  float environment_scale = 1.0f;
  std::optional<RigEnvironment> environment;  // none: the scene's own environment
  std::vector<Light> lights;
};

}  // namespace relight
