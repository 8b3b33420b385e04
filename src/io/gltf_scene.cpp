#include "io/gltf_scene.h"

#include <spdlog/spdlog.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <numbers>
#include <optional>

#include "core/error.h"
#include "io/file_bytes.h"
#include "io/input_file.h"
#include "io/json_reader.h"

namespace relight {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// Luminous efficacy glTF exporters (Blender's among them) take for a watt of
// light: 683 lm/W, the SI candela's.
constexpr double kLumensPerWatt = 683.0;

// The JSON of a .gltf, or the JSON chunk of a .glb (12-byte header "glTF",
// version, length; then chunks of length, type, data, the first one JSON).
json read_gltf_json(const fs::path& path) {
  const std::string name = path.string();
  if (lower_extension(path) == ".gltf") return JsonReader::parse_file(path);
  const std::string bytes = read_input_bytes(path, "a glTF binary file (.glb)");
  if (bytes.size() < 20 || std::memcmp(bytes.data(), "glTF", 4) != 0)
    throw InputError(name, "", "not a binary glTF file (no \"glTF\" header)");
  if (little_endian_u32(bytes, 4) != 2) throw InputError(name, "", "glTF version " + std::to_string(little_endian_u32(bytes, 4)) + " is not supported (expected 2)");
  const uint64_t json_size = little_endian_u32(bytes, 12);
  if (std::memcmp(bytes.data() + 16, "JSON", 4) != 0 || 20 + json_size > bytes.size())
    throw InputError(name, "", "truncated or malformed binary glTF: no complete JSON chunk after the header");
  return JsonReader::parse_text(name, bytes.substr(20, json_size));
}

// A node's transform relative to its parent: "matrix" (column-major) or
// translation x rotation (quaternion x, y, z, w) x scale.
Eigen::Affine3d node_transform(const JsonReader& r, const json& node, const std::string& ptr) {
  auto numbers = [&](const char* key, size_t count, std::vector<double> fallback) {
    const json* v = r.optional(node, key);
    if (!v) return fallback;
    const std::string p = json_child(ptr, key);
    if (!v->is_array() || v->size() != count) r.fail(p, "expected " + std::to_string(count) + " numbers");
    std::vector<double> out;
    for (size_t i = 0; i < count; ++i) out.push_back(r.number((*v)[i], json_child(p, i)));
    return out;
  };
  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  if (r.optional(node, "matrix")) {
    const std::vector<double> m = numbers("matrix", 16, {});
    t.matrix() = Eigen::Map<const Eigen::Matrix4d>(m.data());
    return t;
  }
  const std::vector<double> tr = numbers("translation", 3, {0, 0, 0});
  const std::vector<double> q = numbers("rotation", 4, {0, 0, 0, 1});
  const std::vector<double> s = numbers("scale", 3, {1, 1, 1});
  const Eigen::Quaterniond rotation(q[3], q[0], q[1], q[2]);
  if (rotation.norm() < 1e-6) r.fail(json_child(ptr, "rotation"), "expected a unit quaternion [x, y, z, w]");
  t.translate(Eigen::Vector3d(tr[0], tr[1], tr[2])).rotate(rotation.normalized()).scale(Eigen::Vector3d(s[0], s[1], s[2]));
  return t;
}

// glTF cameras and lights look along their node's -Z with +Y up.
struct Placement {
  Vec3 position, forward, up;
};
Placement place(const Eigen::Affine3d& world) {
  return {world.translation().cast<float>(), (world.linear() * Eigen::Vector3d(0, 0, -1)).normalized().cast<float>(),
          (world.linear() * Eigen::Vector3d(0, 1, 0)).normalized().cast<float>()};
}

CameraSpec parse_camera(const JsonReader& r, const json& camera, const std::string& ptr, const Placement& at) {
  const std::string type = r.string(r.required(camera, ptr, "type"), json_child(ptr, "type"));
  if (type != "perspective") r.fail(json_child(ptr, "type"), "only perspective cameras can be a photo's camera, found \"" + type + "\"");
  const std::string persp = json_child(ptr, "perspective");
  const float yfov = r.number(r.required(r.required(camera, ptr, "perspective"), persp, "yfov"), persp + "/yfov", 0.0f, 3.12f);
  if (yfov <= 0.0f) r.fail(persp + "/yfov", "expected a vertical field of view in (0, pi) radians");
  CameraSpec c;
  c.position = at.position;
  c.look_at = at.position + at.forward;
  c.up = at.up;
  c.vfov_deg = yfov * 180.0f / kPi;
  if (const json& p = camera.at("perspective"); p.contains("aspectRatio"))
    c.aspect = r.number(p["aspectRatio"], persp + "/aspectRatio", 1e-3f, 1e3f);
  return c;
}

// A KHR_lights_punctual light in relight's units, or nothing for a light of zero intensity (switched off).
std::optional<Light> parse_light(const JsonReader& r, const json& def, const std::string& ptr, const Placement& at,
                                 const std::string& fallback_name) {
  Light light;
  const std::string type = r.string(r.required(def, ptr, "type"), json_child(ptr, "type"));
  if (type == "point") light.type = LightType::point;
  else if (type == "spot") light.type = LightType::spot;
  else if (type == "directional") light.type = LightType::directional;
  else r.fail(json_child(ptr, "type"), "expected \"point\", \"spot\" or \"directional\", found \"" + type + "\"");
  light.name = fallback_name;
  if (const json* c = r.optional(def, "color")) light.color = r.vec3(*c, json_child(ptr, "color"));
  double intensity = 1.0;  // candela (point, spot) or lux (directional)
  if (const json* i = r.optional(def, "intensity")) intensity = r.number(*i, json_child(ptr, "intensity"), 0.0f);
  if (intensity <= 0.0) {
    spdlog::warn("{}: {}: light \"{}\" has intensity 0 and is left out", r.file(), ptr, light.name);
    return std::nullopt;
  }
  light.position = at.position;
  light.direction = at.forward;
  if (light.type == LightType::directional) {
    light.irradiance = float(intensity / kLumensPerWatt);
  } else {
    light.power = float(4.0 * std::numbers::pi * intensity / kLumensPerWatt);
  }
  if (light.type == LightType::spot) {
    const std::string sp = json_child(ptr, "spot");
    const json empty = json::object();
    const json* spot = r.optional(def, "spot");
    const json& s = spot ? *spot : empty;
    float outer = kPi / 4.0f, inner = 0.0f;
    if (const json* o = r.optional(s, "outerConeAngle")) outer = r.number(*o, sp + "/outerConeAngle", 0.0f, kPi / 2.0f);
    if (const json* i = r.optional(s, "innerConeAngle")) inner = r.number(*i, sp + "/innerConeAngle", 0.0f, outer);
    if (outer <= 0.0f) r.fail(sp + "/outerConeAngle", "expected a cone half-angle in (0, pi/2]");
    light.spot_angle_deg = 2.0f * outer * 180.0f / kPi;
    light.blend = (outer - inner) / outer;  // as Blender's glTF importer maps it
  }
  return light;
}

}  // namespace

bool is_gltf(const fs::path& path) {
  const std::string ext = lower_extension(path);
  return ext == ".gltf" || ext == ".glb";
}

GltfCamerasAndLights read_gltf_cameras_and_lights(const fs::path& path) {
  const JsonReader r(path.string());
  const json root = read_gltf_json(path);
  r.expect_object(root, "");
  const json empty = json::array();
  auto array = [&](const json& obj, const char* key, const std::string& ptr) -> const json& {
    const json* a = r.optional(obj, key);
    if (a && !a->is_array()) r.fail(json_child(ptr, key), "expected an array");
    return a ? *a : empty;
  };
  const json& nodes = array(root, "nodes", "");
  const json& cameras = array(root, "cameras", "");
  const json* punctual = nullptr;
  if (const json* ext = r.optional(root, "extensions")) punctual = r.optional(*ext, "KHR_lights_punctual");
  const json& light_defs = punctual ? array(*punctual, "lights", "/extensions/KHR_lights_punctual") : empty;
  auto index = [&](const json& v, const std::string& ptr, const json& into, const char* what) {
    const size_t i = size_t(r.number(v, ptr, 0.0f, 1.0e9f));
    if (i >= into.size()) r.fail(ptr, std::string("refers to ") + what + " " + std::to_string(i) + ", which does not exist");
    return i;
  };

  // The roots: the default scene's nodes, or (no scenes) every node no other node lists as a child.
  std::vector<size_t> roots;
  const json& scenes = array(root, "scenes", "");
  if (!scenes.empty()) {
    size_t scene = 0;
    if (const json* s = r.optional(root, "scene")) scene = index(*s, "/scene", scenes, "scene");
    const std::string sp = json_child("/scenes", scene);
    const json& scene_nodes = array(scenes[scene], "nodes", sp);
    for (size_t i = 0; i < scene_nodes.size(); ++i) roots.push_back(index(scene_nodes[i], json_child(sp + "/nodes", i), nodes, "node"));
  } else {
    std::vector<bool> is_child(nodes.size(), false);
    for (const json& n : nodes)
      if (n.is_object() && n.contains("children") && n["children"].is_array())
        for (const json& c : n["children"])
          if (c.is_number_unsigned() && c.get<size_t>() < nodes.size()) is_child[c.get<size_t>()] = true;
    for (size_t i = 0; i < nodes.size(); ++i)
      if (!is_child[i]) roots.push_back(i);
  }

  GltfCamerasAndLights out;
  std::vector<std::pair<size_t, Eigen::Affine3d>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, Eigen::Affine3d::Identity());
  size_t visited = 0;
  while (!stack.empty()) {
    const auto [i, parent] = stack.back();
    stack.pop_back();
    if (++visited > nodes.size()) r.fail("/nodes", "the node hierarchy has a cycle");
    const std::string ptr = json_child("/nodes", i);
    const json& node = nodes[i];
    r.expect_object(node, ptr);
    const Eigen::Affine3d world = parent * node_transform(r, node, ptr);
    std::string node_name;
    if (const json* n = r.optional(node, "name")) node_name = r.string(*n, json_child(ptr, "name"));
    if (const json* c = r.optional(node, "camera")) {
      const size_t ci = index(*c, json_child(ptr, "camera"), cameras, "camera");
      GltfCamera cam;
      cam.node_name = node_name;
      if (const json* n = r.optional(cameras[ci], "name")) cam.camera_name = r.string(*n, json_child("/cameras", ci) + "/name");
      cam.spec = parse_camera(r, cameras[ci], json_child("/cameras", ci), place(world));
      out.cameras.push_back(cam);
    }
    if (const json* ext = r.optional(node, "extensions"))
      if (const json* l = r.optional(*ext, "KHR_lights_punctual")) {
        const std::string lp = ptr + "/extensions/KHR_lights_punctual/light";
        const size_t li = index(r.required(*l, ptr + "/extensions/KHR_lights_punctual", "light"), lp, light_defs, "light");
        // Named after its node (Blender: the object), else its own name.
        std::string name = node_name;
        if (const json* n = r.optional(light_defs[li], "name"); name.empty() && n)
          name = r.string(*n, json_child("/extensions/KHR_lights_punctual/lights", li) + "/name");
        if (name.empty()) name = "light " + std::to_string(li);
        if (auto light = parse_light(r, light_defs[li], json_child("/extensions/KHR_lights_punctual/lights", li), place(world), name))
          out.lights.push_back(*light);
      }
    const json& children = array(node, "children", ptr);
    for (size_t k = children.size(); k-- > 0;)
      stack.emplace_back(index(children[k], json_child(ptr + "/children", k), nodes, "node"), world);
  }
  return out;
}

namespace {

// "%2e%2e%2f" is "../": a URI's path is read decoded.
std::string percent_decoded(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit((unsigned char)uri[i + 1]) &&
        std::isxdigit((unsigned char)uri[i + 2])) {
      out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> gltf_file_uris(const fs::path& path) {
  const json root = read_gltf_json(path);
  std::vector<std::pair<std::string, std::string>> uris;
  if (!root.is_object()) return uris;
  for (const char* kind : {"buffers", "images"}) {
    const auto list = root.find(kind);
    if (list == root.end() || !list->is_array()) continue;
    for (size_t i = 0; i < list->size(); ++i) {
      const json& item = (*list)[i];
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string uri = item["uri"];
      if (uri.rfind("data:", 0) == 0) continue;
      uris.emplace_back(json_child(json_child(std::string("/") + kind, i), "uri"), percent_decoded(uri));
    }
  }
  return uris;
}

CameraSpec find_gltf_camera(const fs::path& path, const GltfCamerasAndLights& contents, const std::string& name) {
  std::string names;
  for (const GltfCamera& c : contents.cameras) {
    if (c.node_name == name || c.camera_name == name) return c.spec;
    names += (names.empty() ? "" : ", ") + ("\"" + (c.node_name.empty() ? c.camera_name : c.node_name) + "\"");
  }
  throw InputError(path.string(), "", "has no camera called \"" + name + "\"" +
                                          (names.empty() ? " (it has no cameras)" : "; its cameras: " + names));
}

}  // namespace relight
