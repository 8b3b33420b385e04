#include "io/scene_io.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <optional>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/frame_files.h"
#include "io/gltf_scene.h"
#include "io/image_io.h"
#include "io/json_reader.h"
#include "io/json_text.h"
#include "io/mesh_io.h"
#include "io/scene_folder_reads.h"

namespace relight {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr float kMaxPower = 1.0e9f;

// A path from the JSON, relative to the JSON file's folder.
fs::path resolve(const fs::path& json_file, const std::string& relative) {
  const fs::path p(relative);
  return p.is_absolute() ? p : json_file.parent_path() / p;
}

LightType parse_light_type(const JsonReader& r, const json& v, const std::string& ptr) {
  const std::string t = r.string(v, ptr);
  if (t == "point") return LightType::point;
  if (t == "spot") return LightType::spot;
  if (t == "area") return LightType::area;
  if (t == "directional") return LightType::directional;
  r.fail(ptr, "expected \"point\", \"spot\", \"area\" or \"directional\", found \"" + t + "\"");
}

Interpolation parse_interpolation(const JsonReader& r, const json& v, const std::string& ptr) {
  const std::string t = r.string(v, ptr);
  if (t == "constant") return Interpolation::constant;
  if (t == "linear") return Interpolation::linear;
  if (t == "smooth") return Interpolation::smooth;
  r.fail(ptr, "expected \"constant\", \"linear\" or \"smooth\", found \"" + t + "\"");
}

// An animated light's keys (docs/formats.md, "Animated rigs"): the values a
// light of `type` has, each optional, at whole frames in increasing order.
std::vector<LightKey> parse_light_keys(const JsonReader& r, const json& v, const std::string& ptr, LightType type) {
  if (!v.is_array() || v.empty()) r.fail(ptr, "expected an array of keys ({\"frame\": 1, ...})");
  const bool sun = type == LightType::directional;
  const char* power_key = sun ? "irradiance" : "power";
  std::vector<LightKey> keys;
  for (size_t i = 0; i < v.size(); ++i) {
    const json& k = v[i];
    const std::string at = json_child(ptr, i);
    r.expect_object(k, at);
    auto member = [&](const char* name) { return json_child(at, name); };
    LightKey key;
    const float frame = r.number(r.required(k, at, "frame"), member("frame"), -1.0e6f, 1.0e6f);
    if (frame != std::floor(frame)) r.fail(member("frame"), "expected a whole frame number");
    key.frame = int(frame);
    if (!keys.empty() && key.frame <= keys.back().frame)
      r.fail(member("frame"), "frames must increase from key to key (" + std::to_string(key.frame) + " after " +
                                  std::to_string(keys.back().frame) + ")");
    if (auto* m = r.optional(k, "interpolation"))
      key.interpolation = parse_interpolation(r, *m, member("interpolation"));
    if (auto* m = r.optional(k, "position")) {
      if (sun) r.fail(member("position"), "a directional light has no position (key its direction)");
      key.position = r.vec3(*m, member("position"));
    }
    if (auto* m = r.optional(k, "direction")) {
      if (type == LightType::point) r.fail(member("direction"), "a point light has no direction");
      key.direction = r.direction(*m, member("direction"));
    }
    if (auto* m = r.optional(k, "color")) key.color = r.color(*m, member("color"));
    if (auto* m = r.optional(k, power_key)) key.power = r.number(*m, member(power_key), 0.0f, kMaxPower);
    if (auto* m = r.optional(k, "enabled")) key.enabled = r.boolean(*m, member("enabled"));
    r.warn_unknown_keys(k, at, {"frame", "interpolation", "position", "direction", "color", power_key, "enabled"});
    if (!key.position && !key.direction && !key.color && !key.power && !key.enabled)
      spdlog::warn("{}: {}: the key sets nothing (position, direction, color, {} or enabled)", r.file(), at, power_key);
    keys.push_back(key);
  }
  return keys;
}

Light parse_light(const JsonReader& r, const json& v, const std::string& ptr, size_t index) {
  r.expect_object(v, ptr);
  Light light;
  light.type = parse_light_type(r, r.required(v, ptr, "type"), json_child(ptr, "type"));
  auto key = [&](const char* k) { return json_child(ptr, k); };
  light.name = std::string(to_string(light.type)) + " " + std::to_string(index);
  if (auto* n = r.optional(v, "name")) light.name = r.string(*n, key("name"));
  if (auto* c = r.optional(v, "color")) light.color = r.color(*c, key("color"));
  if (auto* e = r.optional(v, "enabled")) light.enabled = r.boolean(*e, key("enabled"));
  if (light.enabled && light.color.isZero())
    spdlog::warn("{}: {}: the colour is black ([0, 0, 0]): the light lights nothing", r.file(), key("color"));

  switch (light.type) {
    case LightType::point:
    case LightType::spot:
      light.position = r.vec3(r.required(v, ptr, "position"), key("position"));
      light.power = r.number_above(r.required(v, ptr, "power"), key("power"), 0.0f);
      if (light.power > kMaxPower) r.fail(key("power"), "power is implausibly large (over 1e9 W)");
      if (auto* rad = r.optional(v, "radius")) light.radius = r.number(*rad, key("radius"), 0.0f, 1.0e3f);
      if (light.type == LightType::spot) {
        light.direction = r.direction(r.required(v, ptr, "direction"), key("direction"));
        light.spot_angle_deg = r.number(r.required(v, ptr, "spot_angle_deg"), key("spot_angle_deg"), 0.0f, 180.0f);
        if (light.spot_angle_deg <= 0.0f) r.fail(key("spot_angle_deg"), "expected a cone angle in (0, 180]");
        if (auto* b = r.optional(v, "blend")) light.blend = r.number(*b, key("blend"), 0.0f, 1.0f);
        r.warn_unknown_keys(v, ptr,
                            {"type", "name", "color", "enabled", "position", "power", "radius", "direction",
                             "spot_angle_deg", "blend", "keys"});
      } else {
        r.warn_unknown_keys(v, ptr, {"type", "name", "color", "enabled", "position", "power", "radius", "keys"});
      }
      break;
    case LightType::area: {
      light.position = r.vec3(r.required(v, ptr, "position"), key("position"));
      light.direction = r.direction(r.required(v, ptr, "direction"), key("direction"));
      light.up = r.direction(r.required(v, ptr, "up"), key("up"));
      if (light.up.cross(light.direction).norm() < 1e-4f) r.fail(key("up"), "must not be parallel to direction");
      const json& size = r.required(v, ptr, "size");
      if (!size.is_array() || size.size() != 2) r.fail(key("size"), "expected [w, h] in metres");
      light.size = Vec2(r.number_above(size[0], key("size") + "/0", 0.0f), r.number_above(size[1], key("size") + "/1", 0.0f));
      light.power = r.number_above(r.required(v, ptr, "power"), key("power"), 0.0f);
      if (light.power > kMaxPower) r.fail(key("power"), "power is implausibly large (over 1e9 W)");
      r.warn_unknown_keys(v, ptr,
                          {"type", "name", "color", "enabled", "position", "direction", "up", "size", "power", "keys"});
      break;
    }
    case LightType::directional:
      light.direction = r.direction(r.required(v, ptr, "direction"), key("direction"));
      light.irradiance = r.number_above(r.required(v, ptr, "irradiance"), key("irradiance"), 0.0f);
      if (light.irradiance > kMaxPower) r.fail(key("irradiance"), "irradiance is implausibly large");
      if (auto* a = r.optional(v, "angle_deg")) light.angle_deg = r.number(*a, key("angle_deg"), 0.0f, 180.0f);
      r.warn_unknown_keys(v, ptr, {"type", "name", "color", "enabled", "direction", "irradiance", "angle_deg", "keys"});
      break;
  }
  if (auto* keys = r.optional(v, "keys")) light.keys = parse_light_keys(r, *keys, key("keys"), light.type);
  return light;
}

std::vector<Light> parse_lights(const JsonReader& r, const json& root) {
  std::vector<Light> lights;
  const json* arr = r.optional(root, "lights");
  if (!arr) return lights;
  if (!arr->is_array()) r.fail("/lights", "expected an array of lights");
  for (size_t i = 0; i < arr->size(); ++i) lights.push_back(parse_light(r, (*arr)[i], json_child("/lights", i), i));
  return lights;
}

void expect_format(const JsonReader& r, const json& root, const char* expected) {
  r.expect_object(root, "");
  const std::string f = r.string(r.required(root, "", "format"), "/format");
  if (f != expected) r.fail("/format", std::string("expected \"") + expected + "\", found \"" + f + "\"");
}

// The cameras and lights of a glTF geometry, read once when the camera or
// the lights come from it.
class GeometryContents {
 public:
  GeometryContents(const JsonReader& r, fs::path geometry) : r_(r), geometry_(std::move(geometry)) {}
  const GltfCamerasAndLights& get(const std::string& pointer) {
    if (!is_gltf(geometry_))
      r_.fail(pointer, "the geometry " + geometry_.string() + " is not glTF (.gltf/.glb); only glTF holds cameras and lights");
    if (!contents_) contents_ = read_gltf_cameras_and_lights(geometry_);
    return *contents_;
  }
  const fs::path& path() const { return geometry_; }

 private:
  const JsonReader& r_;
  fs::path geometry_;
  std::optional<GltfCamerasAndLights> contents_;
};

// What a camera block holds besides where it is: checked and read into c.
void read_camera_checks_and_extras(const JsonReader& r, const json& v, const std::string& ptr, CameraSpec& c) {
  const Vec3 forward = c.look_at - c.position;
  if (forward.norm() < 1e-6f) r.fail(ptr + "/look_at", "must differ from the camera position");
  if (forward.normalized().cross(c.up).norm() < 1e-4f) r.fail(ptr + "/up", "must not be parallel to the view direction");
  if (auto* pp = r.optional(v, "principal_point")) {
    const std::string pp_ptr = ptr + "/principal_point";
    if (!pp->is_array() || pp->size() != 2) r.fail(pp_ptr, "expected [u, v], fractions of the photo's width and height");
    // Beyond the image is allowed (strongly shifted lenses), within reason.
    c.principal_point = Vec2(r.number((*pp)[0], pp_ptr + "/0", -10.0f, 10.0f), r.number((*pp)[1], pp_ptr + "/1", -10.0f, 10.0f));
  }
  if (auto* aspect = r.optional(v, "aspect")) c.aspect = r.number(*aspect, ptr + "/aspect", 1e-3f, 1e3f);
  if (auto* k = r.optional(v, "distortion")) {
    const std::string k_ptr = ptr + "/distortion";
    if (!k->is_array() || k->empty() || k->size() > 2)
      r.fail(k_ptr,
             "expected [k1] or [k1, k2], the lens's radial distortion (OpenCV's and Blender's polynomial model)");
    c.distortion.x() = r.number((*k)[0], k_ptr + "/0", -1.0f, 1.0f);
    if (k->size() == 2) c.distortion.y() = r.number((*k)[1], k_ptr + "/1", -1.0f, 1.0f);
  }
  r.warn_unknown_keys(
      v, ptr, {"position", "look_at", "up", "vfov_deg", "principal_point", "from_geometry", "aspect", "distortion"});
}

CameraSpec parse_camera(const JsonReader& r, const json& v, GeometryContents& geometry) {
  const std::string ptr = "/camera";
  r.expect_object(v, ptr);
  if (!r.optional(v, "from_geometry")) return camera_from_json(r, v, ptr);
  const std::string key = ptr + "/from_geometry";
  CameraSpec c = find_gltf_camera(geometry.path(), geometry.get(key), r.string(*r.optional(v, "from_geometry"), key));
  read_camera_checks_and_extras(r, v, ptr, c);
  return c;
}

// Checks that the image of `p` fits its mapping, and warns if it is black.
void check_mapped_image(const Probe& p, const char* what) {
  if (is_black(p.image)) spdlog::warn("{}: the {} image is black everywhere: it measured no light", p.path, what);
  const int w = p.image.width, h = p.image.height;
  if (p.mapping == ProbeMapping::equirect && w != 2 * h)
    throw InputError(p.path, "", fmt::format("an equirect {} must be twice as wide as high, found {}x{}", what, w, h));
  if (p.mapping == ProbeMapping::mirrorball && w != h)
    throw InputError(p.path, "", fmt::format("a mirror-ball {} must be square, found {}x{}", what, w, h));
}

// An image mapped as a probe's: `image` (relative to the JSON file), `mapping`,
// `forward` and `up` of the object at `ptr`, the image read and checked;
// `what` ("probe", "environment") names it in messages.
Probe parse_mapped_image(const JsonReader& r, const json& v, const std::string& ptr, const fs::path& json_path,
                         const char* what) {
  Probe p;
  p.path = resolve(json_path, r.string(r.required(v, ptr, "image"), ptr + "/image")).string();
  check_read_inside(json_path.parent_path(), json_path, ptr + "/image", p.path);
  const std::string mapping = r.string(r.required(v, ptr, "mapping"), ptr + "/mapping");
  if (mapping == "equirect") p.mapping = ProbeMapping::equirect;
  else if (mapping == "mirrorball") p.mapping = ProbeMapping::mirrorball;
  else r.fail(ptr + "/mapping", "expected \"equirect\" or \"mirrorball\", found \"" + mapping + "\"");
  p.forward = r.direction(r.required(v, ptr, "forward"), ptr + "/forward");
  p.up = r.direction(r.required(v, ptr, "up"), ptr + "/up");
  if (p.forward.cross(p.up).norm() < 1e-4f) r.fail(ptr + "/up", "must not be parallel to forward");
  p.image = read_image(p.path);
  check_mapped_image(p, what);
  return p;
}

Probe parse_probe(const JsonReader& r, const json& v, const std::string& ptr, const fs::path& scene_path) {
  r.expect_object(v, ptr);
  r.warn_unknown_keys(v, ptr, {"image", "mapping", "position", "forward", "up", "scale"});
  const Vec3 position = r.vec3(r.required(v, ptr, "position"), ptr + "/position");
  Vec3 scale = Vec3::Ones();
  if (const json* s = r.optional(v, "scale")) {
    const std::string scale_ptr = ptr + "/scale";
    scale = s->is_number() ? Vec3::Constant(r.number(*s, scale_ptr, 0.0f, 1e9f)) : r.vec3(*s, scale_ptr);
    if (!(scale.minCoeff() > 0.0f) || !is_finite(scale)) r.fail(scale_ptr, "expected a positive number or [r, g, b]");
  }
  Probe p = parse_mapped_image(r, v, ptr, scene_path, "probe");
  p.position = position;
  p.scale = scale;
  for (Vec3& pixel : p.image.pixels) pixel = pixel.cwiseProduct(scale);
  return p;
}

// The rig's `environment`: {"color": [r, g, b]} or a mapped image.
RigEnvironment parse_rig_environment(const JsonReader& r, const json& v, const fs::path& rig_path) {
  const std::string ptr = "/environment";
  r.expect_object(v, ptr);
  const json* color = r.optional(v, "color");
  const bool image = v.contains("image");
  if (color && image) r.fail(ptr, "give either \"color\" or \"image\", not both");
  RigEnvironment environment;
  if (color) {
    r.warn_unknown_keys(v, ptr, {"color"});
    environment.color = r.color(*color, ptr + "/color");
  } else if (image) {
    r.warn_unknown_keys(v, ptr, {"image", "mapping", "forward", "up"});
    environment.image = std::make_shared<const Probe>(parse_mapped_image(r, v, ptr, rig_path, "environment"));
  } else {
    r.fail(ptr, "expected \"color\": [r, g, b], or an \"image\" with \"mapping\", \"forward\" and \"up\"");
  }
  return environment;
}

}  // namespace

RigEnvironment load_environment_image(const fs::path& path) {
  auto p = std::make_shared<Probe>();
  p->path = path.string();
  p->forward = Vec3(1, 0, 0);
  p->up = Vec3(0, 0, 1);
  p->image = read_image(p->path);
  if (p->image.width == p->image.height) p->mapping = ProbeMapping::mirrorball;
  check_mapped_image(*p, "environment");
  return RigEnvironment{Vec3::Zero(), std::move(p)};
}

namespace {

json v3(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

// Path p as written in a JSON file in `folder`.
std::string relative_to(const fs::path& folder, const fs::path& p) {
  const fs::path base = fs::absolute(folder).lexically_normal();
  return fs::absolute(p).lexically_normal().lexically_relative(base).generic_string();
}

// The keys parse_mapped_image reads, the image's path relative to `folder`.
json mapped_image_to_json(const Probe& p, const fs::path& folder) {
  return {{"image", relative_to(folder, p.path)},
          {"mapping", p.mapping == ProbeMapping::equirect ? "equirect" : "mirrorball"},
          {"forward", v3(p.forward)},
          {"up", v3(p.up)}};
}

json light_keys_to_json(const Light& l) {
  json keys = json::array();
  for (const LightKey& key : l.keys) {
    json k;
    k["frame"] = key.frame;
    if (key.interpolation != Interpolation::smooth) k["interpolation"] = to_string(key.interpolation);
    // Only what the light's type has (its type may have changed in the studio).
    if (key.position && l.type != LightType::directional) k["position"] = v3(*key.position);
    if (key.direction && l.type != LightType::point) k["direction"] = v3(*key.direction);
    if (key.color) k["color"] = v3(*key.color);
    if (key.power) k[l.type == LightType::directional ? "irradiance" : "power"] = *key.power;
    if (key.enabled) k["enabled"] = *key.enabled;
    keys.push_back(std::move(k));
  }
  return keys;
}

json light_to_json(const Light& l) {
  json j;
  j["name"] = l.name;
  j["type"] = to_string(l.type);
  j["color"] = v3(l.color);
  if (!l.enabled) j["enabled"] = false;
  switch (l.type) {
    case LightType::point:
    case LightType::spot:
      j["position"] = v3(l.position);
      j["power"] = l.power;
      if (l.radius > 0.0f) j["radius"] = l.radius;
      if (l.type == LightType::spot) {
        j["direction"] = v3(l.direction);
        j["spot_angle_deg"] = l.spot_angle_deg;
        j["blend"] = l.blend;
      }
      break;
    case LightType::area:
      j["position"] = v3(l.position);
      j["direction"] = v3(l.direction);
      j["up"] = v3(l.up);
      j["size"] = json::array({l.size.x(), l.size.y()});
      j["power"] = l.power;
      break;
    case LightType::directional:
      j["direction"] = v3(l.direction);
      j["irradiance"] = l.irradiance;
      if (l.angle_deg > 0.0f) j["angle_deg"] = l.angle_deg;
      break;
  }
  if (!l.keys.empty()) j["keys"] = light_keys_to_json(l);
  return j;
}

// `count` (or, with 0, three or more) [x, y] photo pixel positions.
std::vector<Vec2> parse_pixel_positions(const JsonReader& r, const json& v, const std::string& ptr, size_t count) {
  if (!v.is_array() || (count ? v.size() != count : v.size() < 3))
    r.fail(ptr, count ? "expected " + std::to_string(count) + " [x, y] photo pixel positions"
                      : std::string("expected three or more [x, y] photo pixel positions"));
  std::vector<Vec2> points;
  for (size_t i = 0; i < v.size(); ++i) {
    const std::string child = json_child(ptr, i);
    if (!v[i].is_array() || v[i].size() != 2) r.fail(child, "expected [x, y] in photo pixels");
    points.emplace_back(r.number(v[i][0], child + "/0"), r.number(v[i][1], child + "/1"));
  }
  return points;
}

AlbedoReference parse_reference(const JsonReader& r, const json& v) {
  r.expect_object(v, "/reference");
  AlbedoReference ref;
  if (const json* chart = r.optional(v, "colorchecker")) {
    ref.colorchecker = parse_pixel_positions(r, *chart, "/reference/colorchecker", 4);
    r.warn_unknown_keys(v, "/reference", {"colorchecker"});
    return ref;
  }
  const json* object = r.optional(v, "object");
  if (object && v.contains("polygon")) r.fail("/reference", "give either \"polygon\" or \"object\", not both");
  if (object) {
    ref.object = r.string(*object, "/reference/object");
    if (ref.object.empty()) r.fail("/reference/object", "expected the name of an object of the geometry");
  } else {
    ref.polygon = parse_pixel_positions(r, r.required(v, "/reference", "polygon"), "/reference/polygon", 0);
  }
  const json& albedo = r.required(v, "/reference", "albedo");
  const std::string ptr = "/reference/albedo";
  ref.albedo = albedo.is_number() ? Vec3::Constant(r.number(albedo, ptr, 0.0f, 1.0f)) : r.color(albedo, ptr);
  if (ref.albedo.minCoeff() <= 0.0f || ref.albedo.maxCoeff() > 1.0f) r.fail(ptr, "expected an albedo in (0, 1]");
  r.warn_unknown_keys(v, "/reference", {"polygon", "object", "albedo"});
  return ref;
}

// scene.json's `materials`: {"NAME": {"roughness": r, "specular": s}, ...},
// NAME an object or material of the geometry (check_material_names).
std::map<std::string, Gloss> parse_materials(const JsonReader& r, const json& v) {
  r.expect_object(v, "/materials");
  constexpr size_t kMaxMaterials = 10000;  // SurfaceGloss keeps a 16-bit index
  if (v.size() > kMaxMaterials) r.fail("/materials", fmt::format("has over {} entries", kMaxMaterials));
  std::map<std::string, Gloss> materials;
  for (const auto& [name, m] : v.items()) {
    const std::string ptr = json_child("/materials", name);
    r.expect_object(m, ptr);
    r.warn_unknown_keys(m, ptr, {"roughness", "specular"});
    Gloss gloss;
    gloss.roughness = r.number(r.required(m, ptr, "roughness"), ptr + "/roughness", 0.0f, 1.0f);
    if (const json* specular = r.optional(m, "specular"))
      gloss.specular = r.number(*specular, ptr + "/specular", 0.0f, 1.0f);
    materials.emplace(name, gloss);
  }
  return materials;
}

// The names of the geometry's objects (or materials), the first dozen, for
// an error that a name is not among them.
std::string some_names(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size() && i < 12; ++i) out += (i ? ", \"" : "\"") + names[i] + "\"";
  if (names.size() > 12) out += fmt::format(" and {} more", names.size() - 12);
  return out.empty() ? "none named" : out;
}

// Every name in `materials` must be an object or a material of the geometry.
void check_material_names(const JsonReader& r, const std::map<std::string, Gloss>& materials, const fs::path& geometry,
                          const TriangleMesh& mesh) {
  const auto among = [](const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  for (const auto& [name, gloss] : materials) {
    if (among(mesh.objects, name) || among(mesh.materials, name)) continue;
    r.fail(json_child("/materials", name),
           fmt::format("{} has no object or material named \"{}\" (its objects: {}; its materials: {})",
                       geometry.string(), name, some_names(mesh.objects), some_names(mesh.materials)));
  }
}

// A reference object must be one the geometry names.
void check_reference_object(const JsonReader& r, const AlbedoReference& ref, const fs::path& geometry,
                            const TriangleMesh& mesh) {
  if (ref.object.empty()) return;
  if (std::find(mesh.objects.begin(), mesh.objects.end(), ref.object) != mesh.objects.end()) return;
  r.fail("/reference/object", fmt::format("{} has no object named \"{}\" (its objects: {})", geometry.string(),
                                          ref.object, some_names(mesh.objects)));
}

// A photo cropped (say to 16:9) after the camera was matched on the whole
// frame (4:3) would be read with the wrong field of view across its width.
// Within 1 %: a pixel's rounding when the photo was resized.
void check_photo_aspect(const fs::path& photo_path, const Image& photo, const CameraSpec& camera) {
  if (camera.aspect <= 0.0f) return;
  const float photo_aspect = float(photo.width) / float(photo.height);
  const auto near = [&](float aspect) { return std::abs(aspect / camera.aspect - 1.0f) <= 0.01f; };
  if (near(photo_aspect)) return;
  // Matched on the photo as stored, where Blender shows it, not turned
  // upright as its EXIF orientation says (image_io.h).
  const int orientation = exif_orientation(photo_path);
  const std::string turned =
      orientation >= 5 && orientation <= 8 && near(1.0f / photo_aspect)
          ? fmt::format(
                ": it was read upright, turned a quarter as its EXIF orientation ({}) says, and the camera "
                "was matched on it as stored (as Blender shows it); set its orientation to 1 (e.g. exiftool "
                "-Orientation=1 -n) to use it as stored, or match the camera on it upright",
                orientation)
          : ": use the photo as the camera was matched on (uncropped), or match the camera again";
  throw InputError(photo_path.string(), "",
                   fmt::format("the photo's aspect ratio is {:.4f} ({}x{}) but the camera was matched on an image of "
                               "aspect ratio {:.4f} (scene.json /camera){}",
                               photo_aspect, photo.width, photo.height, camera.aspect, turned));
}

// A distortion that bends back within the photo (a sign or unit mistaken:
// k1 of -0.5 on a wide lens) would show one ray at two pixels.
void check_distortion(const fs::path& scene_path, const Camera& camera) {
  if (!camera.distortion_folds()) return;
  const Vec2 k = camera.spec().distortion;
  throw InputError(scene_path.string(), "/camera/distortion",
                   fmt::format("k1 {:g}, k2 {:g} bend the image back on itself before the photo's corners: expected "
                               "OpenCV's or Blender's polynomial coefficients, on coordinates in focal lengths",
                               k.x(), k.y()));
}

}  // namespace

CameraSpec camera_from_json(const JsonReader& r, const nlohmann::json& v, const std::string& ptr) {
  r.expect_object(v, ptr);
  CameraSpec c;
  c.position = r.vec3(r.required(v, ptr, "position"), ptr + "/position");
  c.look_at = r.vec3(r.required(v, ptr, "look_at"), ptr + "/look_at");
  c.up = r.direction(r.required(v, ptr, "up"), ptr + "/up");
  c.vfov_deg = r.number(r.required(v, ptr, "vfov_deg"), ptr + "/vfov_deg", 0.0f, 179.0f);
  if (c.vfov_deg <= 0.0f) r.fail(ptr + "/vfov_deg", "expected a field of view in (0, 179] degrees");
  read_camera_checks_and_extras(r, v, ptr, c);
  return c;
}

nlohmann::json camera_to_json(const CameraSpec& c) {
  json j = {{"position", v3(c.position)}, {"look_at", v3(c.look_at)}, {"up", v3(c.up)}, {"vfov_deg", c.vfov_deg}};
  if (c.principal_point != Vec2(0.5f, 0.5f))
    j["principal_point"] = json::array({c.principal_point.x(), c.principal_point.y()});
  if (c.aspect > 0.0f) j["aspect"] = c.aspect;
  if (c.distortion != Vec2::Zero()) j["distortion"] = json::array({c.distortion.x(), c.distortion.y()});
  return j;
}

// scene.json's `shot`: the photos' file pattern ('#'s for the frame number),
// the first frame's number and a camera per frame. Each photo must exist.
Shot parse_shot(const JsonReader& r, const json& v, const fs::path& scene_path) {
  const std::string ptr = "/shot";
  r.expect_object(v, ptr);
  r.warn_unknown_keys(v, ptr, {"photo", "first_frame", "cameras"});
  const fs::path pattern = resolve(scene_path, r.string(r.required(v, ptr, "photo"), ptr + "/photo"));
  if (!has_frame_digits(pattern))
    r.fail(ptr + "/photo", "expected a file name with '#'s for the frame number (photo.####.exr)");
  check_read_inside(scene_path.parent_path(), scene_path, ptr + "/photo", pattern);
  int first = 1;
  if (auto* f = r.optional(v, "first_frame")) first = int(r.number(*f, ptr + "/first_frame", 0.0f, 1e7f));
  const json& cameras = r.required(v, ptr, "cameras");
  if (!cameras.is_array() || cameras.empty()) r.fail(ptr + "/cameras", "expected an array of cameras, one per frame");
  Shot shot;
  shot.photo_pattern = pattern;
  for (size_t i = 0; i < cameras.size(); ++i) {
    ShotFrame frame;
    frame.number = first + int(i);
    frame.camera = camera_from_json(r, cameras[i], json_child(ptr + "/cameras", i));
    frame.photo_path = frame_file(pattern, frame.number);
    if (!fs::exists(frame.photo_path))
      throw InputError(
          frame.photo_path.string(), "",
          fmt::format("frame {}'s photo (scene {}, /shot/photo) does not exist", frame.number, scene_path.string()));
    shot.frames.push_back(std::move(frame));
  }
  return shot;
}

Scene load_shot_frame(const Scene& scene, size_t index) {
  const ShotFrame& frame = scene.shot.frames.at(index);
  Scene still = scene;
  still.shot = {};
  still.photo_path = frame.photo_path;
  still.photo_clipped.clear();
  still.photo = read_image(frame.photo_path, &still.photo_clipped);
  check_photo_aspect(frame.photo_path, still.photo, frame.camera);
  still.camera = Camera(frame.camera, still.photo.width, still.photo.height);
  check_distortion(scene.path, still.camera);
  return still;
}

Scene load_scene(const fs::path& path, const Progress& progress) {
  const JsonReader r(path.string());
  const json root = JsonReader::parse_file(path);
  expect_format(r, root, "relight-scene/1");
  r.warn_unknown_keys(
      root, "",
      {"format", "photo", "geometry", "camera", "lights", "background", "probes", "reference", "shot", "materials"});

  Scene scene;
  scene.path = path;
  scene.photo_path = resolve(path, r.string(r.required(root, "", "photo"), "/photo"));
  scene.geometry_path = resolve(path, r.string(r.required(root, "", "geometry"), "/geometry"));
  check_read_inside(path.parent_path(), path, "/photo", scene.photo_path);
  check_read_inside(path.parent_path(), path, "/geometry", scene.geometry_path);
  // Validate all the JSON (and a glTF's cameras and lights) before the slow file loads.
  GeometryContents geometry(r, scene.geometry_path);
  const CameraSpec camera = parse_camera(r, r.required(root, "", "camera"), geometry);
  const json* lights = r.optional(root, "lights");
  if (lights && lights->is_object() && lights->contains("from_geometry")) {
    if (!r.boolean((*lights)["from_geometry"], "/lights/from_geometry"))
      r.fail("/lights/from_geometry", "expected true (or list the lights in an array)");
    r.warn_unknown_keys(*lights, "/lights", {"from_geometry"});
    scene.lights = geometry.get("/lights/from_geometry").lights;
  } else {
    scene.lights = parse_lights(r, root);
  }
  if (auto* bg = r.optional(root, "background")) scene.background = r.color(*bg, "/background");
  if (auto* reference = r.optional(root, "reference")) scene.reference = parse_reference(r, *reference);
  if (auto* shot = r.optional(root, "shot")) scene.shot = parse_shot(r, *shot, path);
  std::map<std::string, Gloss> materials;
  if (auto* given = r.optional(root, "materials")) materials = parse_materials(r, *given);
  std::vector<std::pair<const json*, std::string>> probe_specs;
  if (auto* probes = r.optional(root, "probes")) {
    if (!probes->is_array()) r.fail("/probes", "expected an array of probes");
    for (size_t i = 0; i < probes->size(); ++i) probe_specs.emplace_back(&(*probes)[i], json_child("/probes", i));
  }

  check_mesh_references_inside(path.parent_path(), scene.geometry_path);
  scene.photo = read_image(scene.photo_path, &scene.photo_clipped);
  check_photo_aspect(scene.photo_path, scene.photo, camera);
  scene.camera = Camera(camera, scene.photo.width, scene.photo.height);
  check_distortion(path, scene.camera);
  scene.mesh = load_mesh(scene.geometry_path, progress);
  if (scene.reference) check_reference_object(r, *scene.reference, scene.geometry_path, scene.mesh);
  check_material_names(r, materials, scene.geometry_path, scene.mesh);
  set_materials(scene, std::move(materials));
  for (const auto& [spec, ptr] : probe_specs) scene.probes.push_back(parse_probe(r, *spec, ptr, path));
  return scene;
}

Rig load_rig(const fs::path& path) {
  const JsonReader r(path.string());
  const json root = JsonReader::parse_file(path);
  expect_format(r, root, "relight-rig/1");
  r.warn_unknown_keys(root, "", {"format", "environment", "environment_scale", "lights"});
  Rig rig;
  if (auto* s = r.optional(root, "environment_scale")) rig.environment_scale = r.number(*s, "/environment_scale", 0.0f, 1.0e6f);
  rig.lights = parse_lights(r, root);
  if (auto* environment = r.optional(root, "environment")) rig.environment = parse_rig_environment(r, *environment, path);
  return rig;
}

std::string scene_to_json(const Scene& scene, const fs::path& folder) {
  const auto relative = [&](const fs::path& p) { return relative_to(folder, p); };
  json j;
  j["format"] = "relight-scene/1";
  j["photo"] = relative(scene.photo_path);
  j["geometry"] = relative(scene.geometry_path);
  const CameraSpec& c = scene.camera.spec();
  j["camera"] = camera_to_json(c);
  j["lights"] = json::array();
  for (const auto& l : scene.lights) j["lights"].push_back(light_to_json(l));
  j["background"] = v3(scene.background);
  if (scene.reference) {
    const auto positions = [](const std::vector<Vec2>& points) {
      json out = json::array();
      for (const Vec2& p : points) out.push_back({p.x(), p.y()});
      return out;
    };
    const AlbedoReference& ref = *scene.reference;
    if (!ref.colorchecker.empty())
      j["reference"] = {{"colorchecker", positions(ref.colorchecker)}};
    else if (!ref.object.empty())
      j["reference"] = {{"object", ref.object}, {"albedo", v3(ref.albedo)}};
    else
      j["reference"] = {{"polygon", positions(ref.polygon)}, {"albedo", v3(ref.albedo)}};
  }
  for (const auto& [name, gloss] : scene.materials)
    j["materials"][name] = {{"roughness", gloss.roughness}, {"specular", gloss.specular}};
  if (!scene.shot.frames.empty()) {
    json cameras = json::array();
    for (const ShotFrame& frame : scene.shot.frames) cameras.push_back(camera_to_json(frame.camera));
    j["shot"] = {{"photo", relative(scene.shot.photo_pattern)},
                 {"first_frame", scene.shot.frames.front().number},
                 {"cameras", cameras}};
  }
  if (!scene.probes.empty()) {
    j["probes"] = json::array();
    for (const auto& p : scene.probes) {
      json probe = mapped_image_to_json(p, folder);
      probe["position"] = v3(p.position);
      if (p.scale != Vec3::Ones()) probe["scale"] = v3(p.scale);
      j["probes"].push_back(std::move(probe));
    }
  }
  return json_text(j);
}

std::string rig_to_json(const Rig& rig, const fs::path& folder) {
  json j;
  j["format"] = "relight-rig/1";
  if (rig.environment)
    j["environment"] = rig.environment->image ? mapped_image_to_json(*rig.environment->image, folder)
                                              : json{{"color", v3(rig.environment->color)}};
  j["environment_scale"] = rig.environment_scale;
  j["lights"] = json::array();
  for (const auto& l : rig.lights) j["lights"].push_back(light_to_json(l));
  return json_text(j);
}

void save_rig(const fs::path& path, const Rig& rig) {
  write_text_atomically(path, rig_to_json(rig, path.parent_path()));
}

}  // namespace relight
