// glTF scenes: a .glb/.gltf geometry made here, with a camera and
// KHR_lights_punctual lights under a node hierarchy, standing in for
// scene.json's camera and lights, in relight's units.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <functional>
#include <numbers>

#include "io/scene_io.h"
#include "scene/light.h"
#include "scene_folder.h"

namespace relight::test {
namespace {

constexpr double kPiD = std::numbers::pi;

// The floor (a 4 m square at y = 0) as a glTF buffer: 4 float positions, 6 uint16 indices.
std::string floor_buffer() {
  const float positions[12] = {-2, 0, -2, 2, 0, -2, 2, 0, 2, -2, 0, 2};
  const uint16_t indices[6] = {0, 2, 1, 0, 3, 2};
  std::string bytes(sizeof positions + sizeof indices, '\0');
  std::memcpy(bytes.data(), positions, sizeof positions);
  std::memcpy(bytes.data() + sizeof positions, indices, sizeof indices);
  return bytes;
}

json quaternion(const Eigen::Vector3d& axis, double degrees) {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(degrees * kPiD / 180.0, axis.normalized()));
  return {q.x(), q.y(), q.z(), q.w()};
}

// Node 0 "Rig" (moved +1 in x) holds the camera; the floor's node is moved
// -1 in z; a point, a spot, a sun and a switched-off lamp.
json gltf_document() {
  return json::parse(R"({
    "asset": {"version": "2.0"}, "scene": 0,
    "scenes": [{"nodes": [0, 2, 3, 4, 5, 6]}],
    "nodes": [
      {"name": "Rig", "translation": [1, 0, 0], "children": [1]},
      {"name": "Camera", "camera": 0, "translation": [0, 1.5, 5]},
      {"name": "Floor", "mesh": 0, "translation": [0, 0, -1]},
      {"name": "Bulb", "translation": [0.5, 2, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
      {"name": "Spot", "translation": [-1, 3, 1], "extensions": {"KHR_lights_punctual": {"light": 1}}},
      {"name": "Sun", "extensions": {"KHR_lights_punctual": {"light": 2}}},
      {"name": "Off", "extensions": {"KHR_lights_punctual": {"light": 3}}}
    ],
    "cameras": [{"name": "CameraData", "type": "perspective",
                 "perspective": {"yfov": 0.6, "aspectRatio": 1.3333, "znear": 0.1}}],
    "extensions": {"KHR_lights_punctual": {"lights": [
      {"name": "bulb data", "type": "point", "color": [1, 0.8, 0.6], "intensity": 100},
      {"type": "spot", "intensity": 250, "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.5}},
      {"type": "directional", "intensity": 2732},
      {"type": "point", "intensity": 0}
    ]}},
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "buffers": [{"byteLength": 60}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-2, 0, -2], "max": [2, 0, 2]},
      {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}
    ]
  })");
}

// A binary glTF: 12-byte header, a JSON chunk and a BIN chunk, each padded to 4 bytes.
std::string glb(const json& document, std::string bin) {
  std::string text = document.dump();
  text.resize((text.size() + 3) / 4 * 4, ' ');
  bin.resize((bin.size() + 3) / 4 * 4, '\0');
  auto u32 = [](uint32_t v) {
    std::string s(4, '\0');
    for (int i = 0; i < 4; ++i) s[i] = char((v >> (8 * i)) & 0xff);
    return s;
  };
  return "glTF" + u32(2) + u32(uint32_t(12 + 8 + text.size() + 8 + bin.size())) + u32(uint32_t(text.size())) + "JSON" +
         text + u32(uint32_t(bin.size())) + "BIN" + std::string(1, '\0') + bin;
}

// A scene folder whose geometry is `file` and whose camera and lights come from it.
void use_gltf(SceneFolder& folder, const std::string& file) {
  folder.scene["geometry"] = file;
  folder.scene["camera"] = {{"from_geometry", "Camera"}};
  folder.scene["lights"] = {{"from_geometry", true}};
  folder.write_json();
}

const Light& light_called(const Scene& scene, const std::string& name) {
  for (const Light& l : scene.lights)
    if (l.name == name) return l;
  throw std::runtime_error("no light " + name);
}

TEST(Gltf, CameraFromGeometryIsPlacedByTheNodeHierarchy) {
  SceneFolder folder("gltf_camera");
  write_text(folder / "scene.glb", glb(gltf_document(), floor_buffer()));
  use_gltf(folder, "scene.glb");
  const Scene scene = load_scene(folder / "scene.json");
  const CameraSpec& c = scene.camera.spec();
  EXPECT_LT((c.position - Vec3(1, 1.5f, 5)).norm(), 1e-6f);
  EXPECT_LT((scene.camera.forward() - Vec3(0, 0, -1)).norm(), 1e-6f);  // glTF cameras look along -Z, +Y up
  EXPECT_LT((c.up - Vec3(0, 1, 0)).norm(), 1e-6f);
  EXPECT_NEAR(c.vfov_deg, 0.6 * 180.0 / kPiD, 1e-4);
  // Assimp placed the floor by its node in the same frame: its corner (2, 0, -3) is there, and the
  // floor point straight ahead of the camera's optical axis images at the photo's centre.
  bool corner = false;
  for (const Vec3& p : scene.mesh.positions) corner |= (p - Vec3(2, 0, -3)).norm() < 1e-5f;
  EXPECT_TRUE(corner);
  const auto centre = scene.camera.project(Vec3(1, 1.5f, -1));
  ASSERT_TRUE(centre.has_value());
  EXPECT_LT((*centre - Vec2(4, 3)).norm(), 1e-4f);
}

TEST(Gltf, RotatedCameraNode) {
  json doc = gltf_document();
  doc["nodes"][1]["rotation"] = quaternion(Eigen::Vector3d(1, 0, 0), -30.0);  // pitched down 30 degrees
  doc["nodes"][0]["rotation"] = quaternion(Eigen::Vector3d(0, 1, 0), 90.0);   // the rig turned to look along -x
  SceneFolder folder("gltf_rotated");
  write_text(folder / "scene.glb", glb(doc, floor_buffer()));
  use_gltf(folder, "scene.glb");
  const Scene scene = load_scene(folder / "scene.json");
  const Eigen::Matrix3d rig = Eigen::AngleAxisd(kPiD / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix3d cam = Eigen::AngleAxisd(-kPiD / 6, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Vector3d position = Eigen::Vector3d(1, 0, 0) + rig * Eigen::Vector3d(0, 1.5, 5);
  const Eigen::Vector3d forward = rig * cam * Eigen::Vector3d(0, 0, -1);
  EXPECT_LT((scene.camera.position().cast<double>() - position).norm(), 1e-5);
  EXPECT_LT((scene.camera.forward().cast<double>() - forward).norm(), 1e-5);
  EXPECT_LT(forward.x(), -0.8);  // looks along -x, and down
  EXPECT_LT(forward.y(), -0.4);
}

TEST(Gltf, LightsInBlendersUnits) {
  SceneFolder folder("gltf_lights");
  write_text(folder / "scene.glb", glb(gltf_document(), floor_buffer()));
  use_gltf(folder, "scene.glb");
  const Scene scene = load_scene(folder / "scene.json");
  ASSERT_EQ(scene.lights.size(), 3u);  // the lamp of intensity 0 is left out

  // Point: 100 cd. A surface facing it 2 m away receives 100 / 2^2 = 25 lux = 25/683 W/m^2.
  const Light& bulb = light_called(scene, "Bulb");
  EXPECT_EQ(bulb.type, LightType::point);
  EXPECT_LT((bulb.position - Vec3(0.5f, 2, 0)).norm(), 1e-6f);
  EXPECT_NEAR(bulb.power, 4.0 * kPiD * 100.0 / 683.0, 1e-4);
  EXPECT_LT((bulb.color - Vec3(1, 0.8f, 0.6f)).norm(), 1e-6f);
  const LightSample s = sample_light(bulb, Vec3(0.5f, 0, 0), Vec3(0, 1, 0), Vec2(0.5f, 0.5f));
  EXPECT_NEAR(s.irradiance.x(), 25.0 / 683.0, 1e-6);

  // Spot: cone 2 x 0.5 rad, blend (outer - inner) / outer, pointing down its node's -Z.
  const Light& spot = light_called(scene, "Spot");
  EXPECT_EQ(spot.type, LightType::spot);
  EXPECT_NEAR(spot.spot_angle_deg, 2.0 * 0.5 * 180.0 / kPiD, 1e-4);
  EXPECT_NEAR(spot.blend, 0.4, 1e-6);
  EXPECT_NEAR(spot.power, 4.0 * kPiD * 250.0 / 683.0, 1e-3);
  EXPECT_LT((spot.direction - Vec3(0, 0, -1)).norm(), 1e-6f);

  // Sun: 2732 lux = 4 W/m^2.
  const Light& sun = light_called(scene, "Sun");
  EXPECT_EQ(sun.type, LightType::directional);
  EXPECT_NEAR(sun.irradiance, 4.0, 1e-5);
}

TEST(Gltf, TextGltfWithAnExternalBuffer) {
  json doc = gltf_document();
  doc["buffers"][0]["uri"] = "floor.bin";
  SceneFolder folder("gltf_text");
  write_text(folder / "floor.bin", floor_buffer());
  write_text(folder / "scene.gltf", doc.dump(2));
  use_gltf(folder, "scene.gltf");
  const CliResult r = run_cli({"rig", (folder / "scene.json").string(), "-o", (folder / "rig.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json rig = json::parse(read_text(folder / "rig.json"));
  ASSERT_EQ(rig["lights"].size(), 3u);
  EXPECT_EQ(rig["lights"][0]["name"], "Bulb");
  EXPECT_NEAR(rig["lights"][2]["irradiance"].get<double>(), 4.0, 1e-5);
}

TEST(Gltf, BadReferencesAreOneLineErrors) {
  struct Case {
    std::string what;
    std::function<void(SceneFolder&)> make;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"unknown camera", [](SceneFolder& f) { f.scene["camera"]["from_geometry"] = "Nope"; },
       "no camera called \"Nope\"; its cameras: \"Camera\""},
      {"OBJ geometry", [](SceneFolder& f) { f.scene["geometry"] = "geometry.obj"; }, "/camera/from_geometry"},
      {"orthographic", [](SceneFolder& f) {
         json doc = gltf_document();
         doc["cameras"][0] = {{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"zfar", 9}, {"znear", 0}}}};
         write_text(f / "scene.glb", glb(doc, floor_buffer()));
       }, "/cameras/0/type: only perspective cameras"},
      {"light index", [](SceneFolder& f) {
         json doc = gltf_document();
         doc["nodes"][3]["extensions"]["KHR_lights_punctual"]["light"] = 9;
         write_text(f / "scene.glb", glb(doc, floor_buffer()));
       }, "/nodes/3/extensions/KHR_lights_punctual/light: refers to light 9"},
      {"truncated", [](SceneFolder& f) { write_text(f / "scene.glb", glb(gltf_document(), floor_buffer()).substr(0, 40)); },
       "no complete JSON chunk"},
  };
  for (const Case& c : cases) {
    SceneFolder folder("gltf_bad");
    write_text(folder / "scene.glb", glb(gltf_document(), floor_buffer()));
    use_gltf(folder, "scene.glb");
    c.make(folder);
    folder.write_json();
    const CliResult r = run_cli({"rig", (folder / "scene.json").string(), "-o", (folder / "rig.json").string()});
    EXPECT_EQ(r.status, 2) << c.what;
    // One line, naming the file and the problem (warnings may come before it).
    const size_t at = r.err.find("relight: error: ");
    ASSERT_NE(at, std::string::npos) << c.what << ": " << r.err;
    const std::string line = r.err.substr(at, r.err.find('\n', at) - at);
    EXPECT_NE(line.find(c.message), std::string::npos) << c.what << ": " << r.err;
    EXPECT_NE(line.find(folder.dir.string()), std::string::npos) << c.what << ": " << r.err;
  }
}

}  // namespace
}  // namespace relight::test
