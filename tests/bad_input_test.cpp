// The bad-input catalogue: malformed files of every kind a person or another
// tool can hand relight, each run through the real command line
// (relight::cli::run) in a fresh copy of a small valid scene. Every bad input
// must end with exit status 2, exactly one error line on stderr naming the
// file and the problem, and no output written. A few rows are odd but valid
// input (docs/reliability.md says which and why): they must work, with a
// warning where something was dropped or changed.
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "reference_scenes.h"
#include "sanitizer.h"
#include "scene_folder.h"

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using relight::Image;
using relight::Vec3;
using relight::test::error_lines;
using relight::test::kGeometry;
using relight::test::kAddressSanitizer;
using relight::test::read_text;
using relight::test::run_cli;
using relight::test::SceneFolder;
using relight::test::write_text;

Image photo_with(int x, int y, float value) {
  Image img(8, 6, Vec3(0.3f, 0.25f, 0.2f));
  img.at(x, y).y() = value;
  return img;
}

// A rig's new environment: an 8 x 4 equirect image, Blender's default frame.
json sky(const std::string& image) {
  return {{"image", image}, {"mapping", "equirect"}, {"forward", {1, 0, 0}}, {"up", {0, 0, 1}}};
}
Image sky_with(int x, int y, float value) {
  Image img(8, 4, Vec3(0.5f, 0.6f, 0.8f));
  img.at(x, y).y() = value;
  return img;
}

// Overwrites the data window (and display window) in an EXR header: the image
// then claims (xmax+1) x (ymax+1) pixels whatever the file holds. Zeros are
// appended where the chunk offsets of that many rows would be (16 rows a
// chunk with zip), so that OpenEXR can read its header and open the file.
// A 6 x 8 EXR holding an EXIF orientation, read upright as 8 x 6.
void write_sideways_photo(const fs::path& path, int orientation) {
  OIIO::ImageSpec spec(6, 8, 3, OIIO::TypeDesc::FLOAT);
  spec.attribute("Orientation", orientation);
  const std::vector<float> pixels(6 * 8 * 3, 0.3f);
  const auto out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out && out->open(path.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) &&
              out->close());
}

void forge_exr_size(const fs::path& path, int32_t xmax, int32_t ymax) {
  std::string bytes = read_text(path);
  for (const std::string attribute : {"dataWindow", "displayWindow"}) {
    const std::string key = attribute + std::string("\0box2i\0", 7);
    const size_t at = bytes.find(key);
    ASSERT_NE(at, std::string::npos) << attribute;
    const int32_t box[4] = {0, 0, xmax, ymax};
    std::memcpy(&bytes[at + key.size() + 4], box, sizeof box);  // after the 4-byte attribute size
  }
  write_text(path, bytes + std::string(size_t(std::max(0, ymax + 16) / 16) * 8, '\0'));
}

enum class Command { load, analyze, render };

struct Row {
  const char* name;
  std::function<void(SceneFolder&)> make;  // breaks one thing in the valid scene
  Command command;
  const char* file;     // the file the message must name
  const char* problem;  // what the error (or, for accepted rows, the warning) must say
  int status = 2;
  std::vector<std::string> extra_args = {};
  const char* scene_file = "scene.json";  // the scene.json the command is given
};

// fuzz/regressions/mesh/off_junk_faces_segv without its format byte.
constexpr char kOffThatCrashesAssimp[] =
    "\x4f\x46\x46\x0a\x34\x20\x32\x20\x30\x0a\x30\x20\x30\x20\x30\x0a\x31\x20\x30\x20\x30\x0a\x31\x20"
    "\x31\x31\x20\x30\x0a\x30\x20\x31\x20\x30\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4"
    "\xb4\xb4\xb4\xb4\xb4\xb9\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\x01\x70\x6c\x79\x0a"
    "\x66\x6f\x72\x6d\x61\x74\x20\x61\x73\x63\x69\x69\x20\x31\x2e\x30\x0a\x65\x6c\x65\x6d\x65\x6e\x74"
    "\x20\x76\x65\x72\x74\x65\x3c\x61\x6d\x66\x70\x72\x6f\x70\x65\x72\x74\x79\x20\x66\x6c\x6f\x61\x74"
    "\x20\x78\x0a\x70\x72\x6f\x70\x65\x72\x74\x79\x20\x66\x6c\xff\xff\xff\xff\xff\x5f\x70\x00\x02\xb6"
    "\xe0\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\x00\x02\x00\x00\x00\x00\x4b\x00\x00\xff\xff\xff\xff"
    "\xff\xff\xff\xff\xff\xff\xff\xff\xff\x66\x61\x63\x65\x20\x30\x0a\x70\x72\x6f\x70\x65\x72\x74\x79"
    "\x20\x94\x95\x73\x74\x20\x75\x63\x68\x61\x72\x20\x69\x6e\x74\x20\x76\x65\x72\x74\xb4\xb4\xb4\xb4"
    "\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\x65\x78\x5f\x69\x6e\x64\x69"
    "\x63\x65\x73\x0a\x65\x6e\x64\x5f\x68\x65\x61\x64\x65\x72\x0a\x30\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4"
    "\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4"
    "\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\xb4\x20\x31\x20\x30\x0a\x31\x20\x30\x20\x30"
    "\x0a\x31\x20\x31\x20\x30\x0a\xb4\xb4\xb4\xb4\xb4\x0a\x33\x20\x30\x20\x31\x20\x30\x0a\x34\x20\x30"
    "\x20\x31\x30\x20\x31\x20\x32\x0a\x33\x20\x32\x20\x33\x20\x30\x20\x0a\x32\x20\x33\x0a";

json& light(SceneFolder& f) { return f.scene["lights"][0]; }

// inner/scene.json: the scene with `edit` applied, in a subfolder that holds
// copies of the photo and the geometry, so that "../" leaves its folder.
void inner_scene(SceneFolder& f, const std::function<void(json&)>& edit) {
  fs::create_directory(f / "inner");
  for (const char* name : {"photo.exr", "geometry.obj"}) fs::copy_file(f / name, f / "inner" / name);
  json scene = f.scene;
  edit(scene);
  write_text(f / "inner" / "scene.json", scene.dump(2));
}

// inner/geometry.gltf, a 4 m floor whose buffer is inline (a data: URI),
// with `extra` merged in (images, or a buffer elsewhere), as the geometry of
// inner/scene.json.
void inner_gltf_floor(SceneFolder& f, const json& extra) {
  json gltf = json::parse(R"({
    "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "buffers": [{"byteLength": 60, "uri":
      "data:application/octet-stream;base64,AAAAwAAAAAAAAADAAAAAQAAAAAAAAADAAAAAQAAAAAAAAABAAAAAwAAAAAAAAABAAAACAAEAAAADAAIA"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-2, 0, -2], "max": [2, 0, 2]},
      {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}]
  })");
  gltf.merge_patch(extra);
  inner_scene(f, [](json& scene) { scene["geometry"] = "geometry.gltf"; });
  write_text(f / "inner" / "geometry.gltf", gltf.dump());
}

// inner/geometry.obj naming a material library one folder up.
void inner_obj_with_mtllib_outside(SceneFolder& f) {
  inner_scene(f, [](json&) {});
  write_text(f / "inner" / "geometry.obj", std::string("mtllib ../materials.mtl\n") + kGeometry);
  write_text(f / "materials.mtl", "newmtl grey\nKd 0.5 0.5 0.5\n");
}

void black_probe(SceneFolder& f) {
  f.add_probe("equirect", 8, 4);
  relight::write_exr(f / "probe.exr", Image(8, 4, Vec3::Zero()));
}

json spot() {
  return {{"type", "spot"}, {"position", {0, 0, 3}}, {"direction", {0, 0, -1}}, {"power", 100}, {"spot_angle_deg", 40}};
}
json area() {
  return {{"type", "area"}, {"position", {0, 0, 3}}, {"direction", {0, 0, -1}}, {"up", {0, 1, 0}},
          {"size", {1, 1}}, {"power", 100}};
}
json sun() { return {{"type", "directional"}, {"direction", {0, 0.3, -1}}, {"irradiance", 3}}; }

// geometry.obj in millimetres (the camera and the light stay in metres),
// the camera looking level along the inside of the 1000-unit cube.
void geometry_in_millimetres(SceneFolder& f) {
  std::istringstream in(kGeometry);
  std::string text;
  for (std::string line; std::getline(in, line);) {
    float x, y, z;
    if (std::sscanf(line.c_str(), "v %f %f %f", &x, &y, &z) == 3)
      line = fmt::format("v {} {} {}", x * 1000, y * 1000, z * 1000);
    text += line + "\n";
  }
  write_text(f / "geometry.obj", text);
  f.scene["camera"]["look_at"] = {0, 0, 2};
}

const std::vector<Row>& catalogue() {
  static const std::vector<Row> rows = {
      // scene.json as a file
      {"SceneMissing", [](SceneFolder&) {}, Command::load, "no_such_scene.json", "file not found", 2,
       {}, "no_such_scene.json"},
      {"SceneIsAFolder", [](SceneFolder& f) { fs::create_directory(f / "folder.json"); }, Command::load,
       "folder.json", "is a folder", 2, {}, "folder.json"},
      {"SceneEmpty", [](SceneFolder& f) { f.scene_text = ""; }, Command::load, "scene.json", "malformed JSON"},
      {"SceneTruncated", [](SceneFolder& f) { f.scene_text = f.scene.dump(2).substr(0, 60); }, Command::load,
       "scene.json", "malformed JSON"},
      {"SceneIsAnArray", [](SceneFolder& f) { f.scene = json::array({1, 2, 3}); }, Command::load, "scene.json",
       "expected an object"},
      // wrong types and values
      {"FormatIsANumber", [](SceneFolder& f) { f.scene["format"] = 1; }, Command::load, "scene.json",
       "/format: expected a string"},
      {"FormatOfARig", [](SceneFolder& f) { f.scene["format"] = "relight-rig/1"; }, Command::load, "scene.json",
       "/format: expected \"relight-scene/1\""},
      {"PhotoKeyMissing", [](SceneFolder& f) { f.scene.erase("photo"); }, Command::load, "scene.json",
       "/photo: missing required key"},
      {"PhotoIsANumber", [](SceneFolder& f) { f.scene["photo"] = 42; }, Command::load, "scene.json",
       "/photo: expected a string"},
      {"CameraIsAnArray", [](SceneFolder& f) { f.scene["camera"] = json::array({1, 2, 3}); }, Command::load,
       "scene.json", "/camera: expected an object"},
      {"CameraPositionHoldsAString", [](SceneFolder& f) { f.scene["camera"]["position"][1] = "-5"; }, Command::load,
       "scene.json", "/camera/position/1: expected a number, found string"},
      {"CameraPositionOfTwoNumbers", [](SceneFolder& f) { f.scene["camera"]["position"] = {0, -5}; }, Command::load,
       "scene.json", "/camera/position: expected an array of 3 numbers"},
      {"CameraPositionHuge", [](SceneFolder& f) { f.scene["camera"]["position"][0] = 1e30; }, Command::load,
       "scene.json", "/camera/position/0: expected a number in"},
      {"VfovOverflowsADouble", [](SceneFolder& f) { f.replace_in_scene_text("\"vfov_deg\": 40", "\"vfov_deg\": 1e400"); },
       Command::load, "scene.json", "the number 1e400 is out of range"},
      {"VfovZero", [](SceneFolder& f) { f.scene["camera"]["vfov_deg"] = 0; }, Command::load, "scene.json",
       "/camera/vfov_deg: expected a field of view"},
      {"CameraLooksAtItself", [](SceneFolder& f) { f.scene["camera"]["look_at"] = f.scene["camera"]["position"]; },
       Command::load, "scene.json", "/camera/look_at: must differ from the camera position"},
      {"CameraUpAlongTheView", [](SceneFolder& f) { f.scene["camera"]["up"] = {0, 5, -1.5}; }, Command::load,
       "scene.json", "/camera/up: must not be parallel"},
      {"CameraUpZero", [](SceneFolder& f) { f.scene["camera"]["up"] = {0, 0, 0}; }, Command::load, "scene.json",
       "/camera/up: expected a non-zero direction"},
      // The 8 x 6 (4:3) photo cropped to 16:9 after the camera was matched, or the other way round.
      {"PhotoOfAnotherAspectThanTheCamera", [](SceneFolder& f) { f.scene["camera"]["aspect"] = 16.0 / 9.0; },
       Command::load, "photo.exr",
       "the photo's aspect ratio is 1.3333 (8x6) but the camera was matched on an image of aspect ratio 1.7778"},
      // A portrait stored sideways (6 x 8, EXIF orientation 6) is read
      // upright (8 x 6); the camera was matched on it as stored (6:8).
      {"PhotoTurnedByItsOrientationAfterTheCameraWasMatchedOnItAsStored",
       [](SceneFolder& f) {
         f.scene["camera"]["aspect"] = 6.0 / 8.0;
         write_sideways_photo(f / "photo.exr", 6);
       },
       Command::load, "photo.exr",
       "(8x6) but the camera was matched on an image of aspect ratio 0.7500 (scene.json /camera): it was read upright, "
       "turned a quarter as its EXIF orientation (6) says"},
      {"ReferencePolygonOfTwoPoints",
       [](SceneFolder& f) { f.scene["reference"] = {{"polygon", {{0, 0}, {8, 0}}}, {"albedo", 0.18}}; },
       Command::load, "scene.json", "/reference/polygon: expected three or more"},
      {"ReferenceAlbedoAboveOne",
       [](SceneFolder& f) { f.scene["reference"] = {{"polygon", {{0, 0}, {8, 0}, {8, 6}}}, {"albedo", 1.5}}; },
       Command::load, "scene.json", "/reference/albedo"},
      {"ReferenceColorCheckerOfThreeCorners",
       [](SceneFolder& f) { f.scene["reference"] = {{"colorchecker", {{0, 0}, {8, 0}, {8, 6}}}}; }, Command::load,
       "scene.json", "/reference/colorchecker: expected 4 [x, y] photo pixel positions"},
      {"CameraAspectNegative", [](SceneFolder& f) { f.scene["camera"]["aspect"] = -1.5; }, Command::load,
       "scene.json", "/camera/aspect"},
      {"BackgroundIsAWord", [](SceneFolder& f) { f.scene["background"] = "blue"; }, Command::load, "scene.json",
       "/background: expected a colour"},
      // lights
      {"LightsNotAnArray", [](SceneFolder& f) { f.scene["lights"] = json::object(); }, Command::load, "scene.json",
       "/lights: expected an array"},
      {"LightOfUnknownType", [](SceneFolder& f) { light(f)["type"] = "laser"; }, Command::load, "scene.json",
       "/lights/0/type: expected \"point\""},
      {"LightPowerZero", [](SceneFolder& f) { light(f)["power"] = 0; }, Command::load, "scene.json",
       "/lights/0/power: expected a number greater than 0"},
      {"LightPowerNegative", [](SceneFolder& f) { light(f)["power"] = -100; }, Command::load, "scene.json",
       "/lights/0/power: expected a number greater than 0"},
      {"LightPowerHuge", [](SceneFolder& f) { light(f)["power"] = 1e15; }, Command::load, "scene.json",
       "/lights/0/power: power is implausibly large"},
      {"LightPowerAsAString", [](SceneFolder& f) { light(f)["power"] = "200 W"; }, Command::load, "scene.json",
       "/lights/0/power: expected a number, found string"},
      {"SpotDirectionZero", [](SceneFolder& f) { f.scene["lights"][0] = spot(); light(f)["direction"] = {0, 0, 0}; },
       Command::load, "scene.json", "/lights/0/direction: expected a non-zero direction"},
      {"SpotAngleZero", [](SceneFolder& f) { f.scene["lights"][0] = spot(); light(f)["spot_angle_deg"] = 0; },
       Command::load, "scene.json", "/lights/0/spot_angle_deg"},
      {"SunDirectionZero", [](SceneFolder& f) { f.scene["lights"][0] = sun(); light(f)["direction"] = {0, 0, 0}; },
       Command::load, "scene.json", "/lights/0/direction: expected a non-zero direction"},
      {"SunIrradianceNegative", [](SceneFolder& f) { f.scene["lights"][0] = sun(); light(f)["irradiance"] = -3; },
       Command::load, "scene.json", "/lights/0/irradiance: expected a number greater than 0"},
      {"AreaSizeNegative", [](SceneFolder& f) { f.scene["lights"][0] = area(); light(f)["size"] = {1, -1}; },
       Command::load, "scene.json", "/lights/0/size/1: expected a number greater than 0"},
      {"AreaUpAlongDirection", [](SceneFolder& f) { f.scene["lights"][0] = area(); light(f)["up"] = {0, 0, 2}; },
       Command::load, "scene.json", "/lights/0/up: must not be parallel to direction"},
      {"ColourBadHex", [](SceneFolder& f) { light(f)["color"] = "#ffd8a"; }, Command::load, "scene.json",
       "/lights/0/color: expected a colour \"#rrggbb\""},
      {"ColourNegative", [](SceneFolder& f) { light(f)["color"] = {1, -0.5, 1}; }, Command::load, "scene.json",
       "/lights/0/color/1: expected a number in"},
      // probes
      {"ProbesNotAnArray", [](SceneFolder& f) { f.scene["probes"] = "probe.exr"; }, Command::load, "scene.json",
       "/probes: expected an array"},
      {"ProbeMappingUnknown", [](SceneFolder& f) { f.add_probe("cubemap", 8, 4); }, Command::load, "scene.json",
       "/probes/0/mapping: expected \"equirect\" or \"mirrorball\""},
      {"ProbeForwardAlongUp", [](SceneFolder& f) { f.add_probe("equirect", 8, 4); f.scene["probes"][0]["up"] = {0, 2, 0}; },
       Command::load, "scene.json", "/probes/0/up: must not be parallel to forward"},
      {"ReferenceObjectUnknown", [](SceneFolder& f) { f.scene["reference"] = {{"object", "poster"}, {"albedo", 0.18}}; },
       Command::load, "scene.json", "has no object named \"poster\""},
      {"ReferenceObjectAndPolygon",
       [](SceneFolder& f) {
         f.scene["reference"] = {{"object", "card"}, {"polygon", {{0, 0}, {4, 0}, {4, 4}}}, {"albedo", 0.18}};
       },
       Command::load, "scene.json", "/reference: give either \"polygon\" or \"object\", not both"},
      {"ProbeScaleNegative", [](SceneFolder& f) { f.add_probe("equirect", 8, 4); f.scene["probes"][0]["scale"] = {1, -2, 1}; },
       Command::load, "scene.json", "/probes/0/scale: expected a positive number or [r, g, b]"},
      {"ProbeEquirectSquare", [](SceneFolder& f) { f.add_probe("equirect", 8, 8); }, Command::load, "probe.exr",
       "an equirect probe must be twice as wide as high, found 8x8"},
      {"ProbeMirrorballNotSquare", [](SceneFolder& f) { f.add_probe("mirrorball", 8, 4); }, Command::load,
       "probe.exr", "a mirror-ball probe must be square, found 8x4"},
      {"ProbeImageMissing", [](SceneFolder& f) { f.add_probe("equirect", 8, 4); fs::remove(f / "probe.exr"); },
       Command::load, "probe.exr", "file not found"},
      // the photo
      {"PhotoMissing", [](SceneFolder& f) { fs::remove(f / "photo.exr"); }, Command::load, "photo.exr",
       "file not found"},
      {"PhotoIsAFolder", [](SceneFolder& f) { f.scene["photo"] = "photos"; fs::create_directory(f / "photos"); },
       Command::load, "photos", "is a folder, expected an image file"},
      {"PhotoExrCutInTheHeader", [](SceneFolder& f) { fs::resize_file(f / "photo.exr", 200); }, Command::load,
       "photo.exr", "Unexpected end of file"},
      {"PhotoExrCutInThePixels",
       [](SceneFolder& f) { fs::resize_file(f / "photo.exr", fs::file_size(f / "photo.exr") - 8); }, Command::load,
       "photo.exr", "corrupt or truncated image"},
      {"PhotoEmptyFile", [](SceneFolder& f) { write_text(f / "photo.exr", ""); }, Command::load, "photo.exr",
       "not a readable image"},
      {"PhotoOfTextBytes", [](SceneFolder& f) { write_text(f / "photo.exr", "this is not an image\n"); },
       Command::load, "photo.exr", "not a readable image"},
      {"PhotoClaims0x0", [](SceneFolder& f) { forge_exr_size(f / "photo.exr", -1, -1); }, Command::load,
       "photo.exr", "not a readable image"},
      {"PhotoClaims100000x100000", [](SceneFolder& f) { forge_exr_size(f / "photo.exr", 99999, 99999); },
       Command::load, "photo.exr", "image of 100000x100000 (10000.0 Mpixel) is over the limit of"},
      {"PhotoOverMaxPixels", [](SceneFolder&) {}, Command::load, "photo.exr",
       "image of 8x6 (0.0 Mpixel) is over the limit", 2, {"--max-pixels", "40"}},
      {"PhotoWithNaN", [](SceneFolder& f) { f.replace_photo(photo_with(3, 2, std::numeric_limits<float>::quiet_NaN())); },
       Command::load, "photo.exr", "pixel (3, 2): holds a NaN or infinite value"},
      {"PhotoWithInfinity", [](SceneFolder& f) { f.replace_photo(photo_with(0, 5, std::numeric_limits<float>::infinity())); },
       Command::load, "photo.exr", "pixel (0, 5): holds a NaN or infinite value"},
      {"PhotoWithNegativePixel", [](SceneFolder& f) { f.replace_photo(photo_with(7, 1, -0.5f)); }, Command::load,
       "photo.exr", "pixel (7, 1): holds the negative value -0.5"},
      // the geometry
      {"GeometryMissing", [](SceneFolder& f) { fs::remove(f / "geometry.obj"); }, Command::load, "geometry.obj",
       "file not found"},
      {"GeometryIsAFolder", [](SceneFolder& f) { f.scene["geometry"] = "meshes"; fs::create_directory(f / "meshes"); },
       Command::load, "meshes", "is a folder, expected a mesh file"},
      {"MeshWithoutTriangles", [](SceneFolder& f) { write_text(f / "geometry.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"); },
       Command::load, "geometry.obj", "the mesh has no triangles"},
      {"MeshWithNaNVertex", [](SceneFolder& f) { write_text(f / "geometry.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"); },
       Command::load, "geometry.obj", "has a NaN or infinite coordinate"},
      {"MeshWithHugeVertex", [](SceneFolder& f) { write_text(f / "geometry.obj", "v 0 0 0\nv 1e20 0 0\nv 0 1 0\nf 1 2 3\n"); },
       Command::load, "geometry.obj", "has a coordinate beyond 1e+07 m"},
      {"MeshAllDegenerate",
       [](SceneFolder& f) { write_text(f / "geometry.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 4\n"); },
       Command::load, "geometry.obj", "every triangle of the mesh is degenerate"},
      {"MeshThatCrashesTheReader",  // an OFF file on which Assimp's reader crashes (found by fuzzing)
       [](SceneFolder& f) {
         f.scene["geometry"] = "geometry.off";
         write_text(f / "geometry.off", std::string(kOffThatCrashesAssimp, sizeof kOffThatCrashesAssimp - 1));
       },
       Command::load, "geometry.off", "the mesh reader crashed (signal 11) on this file"},
      {"MeshWithSomeDegenerateTriangles",
       [](SceneFolder& f) { write_text(f / "geometry.obj", std::string(kGeometry) + "f 1 1 2\nf 2 2 3\n"); },
       Command::load, "geometry.obj", "is degenerate (zero area), as is 1 other: remove such triangles"},
      {"MeshOfBinaryJunk", [](SceneFolder& f) { f.scene["geometry"] = "geometry.ply"; write_text(f / "geometry.ply", "\x01\x02\xff\x7f junk"); },
       Command::load, "geometry.ply", "not a readable mesh"},
      {"PlyHeaderWithoutEnd",
       [](SceneFolder& f) { f.scene["geometry"] = "geometry.ply"; write_text(f / "geometry.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"); },
       Command::load, "geometry.ply", "a PLY header without an end_header line"},
      {"PlyEndHeaderRunningIntoTheData",
       [](SceneFolder& f) {
         f.scene["geometry"] = "geometry.ply";
         write_text(f / "geometry.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                                        "property float y\nproperty float z\nend_header\x03\x01\x02\x03");
       },
       Command::load, "geometry.ply", "a PLY header without an end_header line"},
      // the camera against the geometry
      {"CameraLooksAway", [](SceneFolder& f) { f.scene["camera"]["look_at"] = {0, -10, 2}; }, Command::analyze,
       "scene.json", "/camera: the camera sees no geometry"},
      {"CameraInsideTheCube",
       [](SceneFolder& f) { f.scene["camera"]["position"] = {0, 0, 0.5}; f.scene["camera"]["look_at"] = {0, 1, 0.5}; },
       Command::analyze, "scene.json", "/camera: no light reaches any surface the camera sees"},
      // rig.json (render reads it first)
      {"RigMissing", [](SceneFolder& f) { f.rig = nullptr; }, Command::render, "rig.json", "file not found"},
      {"RigOfASceneFormat", [](SceneFolder& f) { f.rig["format"] = "relight-scene/1"; }, Command::render, "rig.json",
       "/format: expected \"relight-rig/1\""},
      {"RigEnvironmentScaleNegative", [](SceneFolder& f) { f.rig["environment_scale"] = -1; }, Command::render,
       "rig.json", "/environment_scale: expected a number in"},
      {"RigEnvironmentImageMissing", [](SceneFolder& f) { f.rig["environment"] = sky("sky.exr"); }, Command::render,
       "sky.exr", "file not found"},
      {"RigEnvironmentImageNaN",
       [](SceneFolder& f) { write_exr(f / "sky.exr", sky_with(3, 1, std::numeric_limits<float>::quiet_NaN())); f.rig["environment"] = sky("sky.exr"); },
       Command::render, "sky.exr", "pixel (3, 1): holds a NaN or infinite value"},
      {"RigEnvironmentImageNegative",
       [](SceneFolder& f) { write_exr(f / "sky.exr", sky_with(3, 1, -5.0f)); f.rig["environment"] = sky("sky.exr"); },
       Command::render, "sky.exr", "pixel (3, 1): holds the negative value -5"},
      {"RigEnvironmentMappingUnknown",
       [](SceneFolder& f) { write_exr(f / "sky.exr", sky_with(0, 0, 1.0f)); f.rig["environment"] = sky("sky.exr"); f.rig["environment"]["mapping"] = "cube"; },
       Command::render, "rig.json", "/environment/mapping: expected \"equirect\" or \"mirrorball\", found \"cube\""},
      {"RigEnvironmentForwardAlongUp",
       [](SceneFolder& f) { write_exr(f / "sky.exr", sky_with(0, 0, 1.0f)); f.rig["environment"] = sky("sky.exr"); f.rig["environment"]["forward"] = {0, 0, -3}; },
       Command::render, "rig.json", "/environment/up: must not be parallel to forward"},
      {"RigEnvironmentColorAndImage",
       [](SceneFolder& f) { write_exr(f / "sky.exr", sky_with(0, 0, 1.0f)); f.rig["environment"] = sky("sky.exr"); f.rig["environment"]["color"] = {1, 1, 1}; },
       Command::render, "rig.json", "/environment: give either \"color\" or \"image\", not both"},
      {"RigLightsAString", [](SceneFolder& f) { f.rig["lights"] = "all"; }, Command::render, "rig.json",
       "/lights: expected an array"},
      {"RigSpotDirectionZero", [](SceneFolder& f) { f.rig["lights"][0]["direction"] = {0, 0, 0}; }, Command::render,
       "rig.json", "/lights/0/direction: expected a non-zero direction"},
      {"RigLightPowerNegative", [](SceneFolder& f) { f.rig["lights"][0]["power"] = -300; }, Command::render,
       "rig.json", "/lights/0/power: expected a number greater than 0"},
      {"RigKeysOutOfOrder",
       [](SceneFolder& f) { f.rig["lights"][0]["keys"] = json::parse(R"([{"frame": 5, "power": 1}, {"frame": 2, "power": 2}])"); },
       Command::render, "rig.json", "/lights/0/keys/1/frame: frames must increase from key to key (2 after 5)"},
      {"FramesWithoutAFrameNumberInTheOutput", [](SceneFolder&) {}, Command::render, "relit.exr",
       "a frame sequence needs '#' in the output's name", 2, {"--frames", "1-2"}},
      {"FramesBackwards", [](SceneFolder&) {}, Command::render, "--frames",
       "expected a frame (12) or a range (1-120), got '3-1'", 2, {"--frames", "3-1"}},
      // where the output goes
      {"AnalysisFolderIsAFile", [](SceneFolder& f) { write_text(f / "analysis", "a file"); }, Command::analyze,
       "analysis", "cannot create the output folder"},

      // reads outside the scene's folder, refused with --confine-to-scene-folder
      {"PhotoOutsideTheSceneFolder", [](SceneFolder& f) { inner_scene(f, [](json& s) { s["photo"] = "../photo.exr"; }); },
       Command::load, "inner/scene.json", "/photo: names a file outside the scene's folder", 2,
       {"--confine-to-scene-folder"}, "inner/scene.json"},
      {"GeometryByAnAbsolutePathOutside",
       [](SceneFolder& f) { inner_scene(f, [&](json& s) { s["geometry"] = (f / "geometry.obj").string(); }); },
       Command::load, "inner/scene.json", "/geometry: names a file outside the scene's folder", 2,
       {"--confine-to-scene-folder"}, "inner/scene.json"},
      {"ProbeSymlinkedOutside",
       [](SceneFolder& f) {
         f.add_probe("equirect", 8, 4);
         inner_scene(f, [](json&) {});
         fs::create_symlink(f / "probe.exr", f / "inner" / "probe.exr");
       },
       Command::load, "inner/scene.json", "/probes/0/image: names a file outside the scene's folder", 2,
       {"--confine-to-scene-folder"}, "inner/scene.json"},
      {"GltfBufferOutside",
       [](SceneFolder& f) {
         inner_gltf_floor(f, {{"buffers", {{{"byteLength", 60}, {"uri", "../../../../../../../../../etc/passwd"}}}}});
       },
       Command::load, "geometry.gltf", "/buffers/0/uri: names a file outside the scene's folder", 2,
       {"--confine-to-scene-folder"}, "inner/scene.json"},
      {"ObjMaterialLibraryOutside", inner_obj_with_mtllib_outside, Command::load, "geometry.obj",
       "line 1 (mtllib): names a file outside the scene's folder", 2, {"--confine-to-scene-folder"},
       "inner/scene.json"},
      // what lights nothing
      {"NothingLightsTheScene",
       [](SceneFolder& f) { light(f)["color"] = {0, 0, 0}; f.scene["background"] = {0, 0, 0}; }, Command::analyze,
       "scene.json", "/lights: nothing lights the scene: every light is black"},
      {"ProbeBlackWithStrategyProbe", black_probe, Command::analyze, "scene.json",
       "/probes: every probe image is black", 2, {"--strategy", "probe"}},

      // Odd but valid: these must work.
      {"PhotoOutsideTheSceneFolderWarns",
       [](SceneFolder& f) { inner_scene(f, [](json& s) { s["photo"] = "../photo.exr"; }); }, Command::load,
       "inner/scene.json", "/photo: reads a file outside the scene's folder", 0, {}, "inner/scene.json"},
      {"GltfImageOutsideWarns",
       [](SceneFolder& f) { inner_gltf_floor(f, {{"images", {{{"uri", "../../textures/wood.png"}}}}}); },
       Command::load, "geometry.gltf", "/images/0/uri: reads a file outside the scene's folder", 0, {},
       "inner/scene.json"},
      {"ObjMaterialLibraryOutsideWarns", inner_obj_with_mtllib_outside, Command::load, "geometry.obj",
       "line 1 (mtllib): reads a file outside the scene's folder", 0, {}, "inner/scene.json"},
      {"GltfDataUriIsInsideTheFolder", [](SceneFolder& f) { inner_gltf_floor(f, json::object()); }, Command::load,
       "geometry.gltf", "", 0, {"--confine-to-scene-folder"}, "inner/scene.json"},
      {"LightBlack", [](SceneFolder& f) { light(f)["color"] = {0, 0, 0}; }, Command::load, "scene.json",
       "/lights/0/color: the colour is black ([0, 0, 0]): the light lights nothing", 0},
      {"ProbeBlack", black_probe, Command::load, "probe.exr", "the probe image is black everywhere", 0},
      {"SomeTrianglesDegenerateRepaired",
       [](SceneFolder& f) { write_text(f / "geometry.obj", std::string(kGeometry) + "f 1 1 2\n"); }, Command::load,
       "geometry.obj", "dropped 1 degenerate (zero-area) triangles", 0, {"--repair-mesh"}},
      {"NonManifoldFin", [](SceneFolder& f) { write_text(f / "geometry.obj", std::string(kGeometry) + "v 0 0 2\nf 11 12 13\n"); },
       Command::load, "geometry.obj", "1 edge shared by three or more triangles (non-manifold)", 0},
      {"NegativeNoiseInThePhoto", [](SceneFolder& f) { f.replace_photo(photo_with(7, 1, -1e-4f)); }, Command::load,
       "photo.exr", "negative pixel values (noise down to -0.0001) clamped to 0", 0},
      {"UnknownKey", [](SceneFolder& f) { f.scene["exposure"] = 2; }, Command::load, "scene.json",
       "/exposure: unknown key ignored", 0},
      // mistakes seen in the view (src/analysis/view_checks.cpp), warned before fit and analyze
      {"LightBelowTheFloorLightsNothingInView", [](SceneFolder& f) { light(f)["position"] = {2, -2, -1}; },
       Command::analyze, "scene.json", "/lights/0 (point 0): lights nothing the camera sees", 0},
      {"LampSphereThroughTheFloor",  // the sphere's cap below z = 0: a quarter of its surface
       [](SceneFolder& f) {
         light(f)["position"] = {2, -2, 0.25};
         light(f)["radius"] = 0.5;
       },
       Command::analyze, "scene.json", "/lights/0 (point 0): 25 % of its sphere lies beyond a surface of the geometry",
       0},
      {"GeometryCoversLittleOfThePhoto",
       [](SceneFolder& f) {
         f.replace_photo(Image(80, 60, Vec3(0.3f, 0.25f, 0.2f)));
         f.scene["camera"]["position"] = {0, -30, 2};
       },
       Command::analyze, "geometry.obj", "the geometry covers 0.5 % of the photo", 0},
      {"GeometryInMillimetres", geometry_in_millimetres, Command::analyze, "geometry.obj",
       "123 times as far; is the geometry in centimetres", 0},
      {"ShotPhotoWithoutFrameNumber",
       [](SceneFolder& f) { f.scene["shot"] = {{"photo", "photo.exr"}, {"cameras", {f.scene["camera"]}}}; },
       Command::load, "scene.json", "/shot/photo: expected a file name with '#'s for the frame number"},
      {"ShotWithoutCameras",
       [](SceneFolder& f) { f.scene["shot"] = {{"photo", "photo.####.exr"}, {"cameras", json::array()}}; },
       Command::load, "scene.json", "/shot/cameras: expected an array of cameras, one per frame"},
      {"ShotFramePhotoMissing",
       [](SceneFolder& f) {
         fs::copy_file(f / "photo.exr", f / "photo.0001.exr");
         f.scene["shot"] = {{"photo", "photo.####.exr"}, {"cameras", {f.scene["camera"], f.scene["camera"]}}};
       },
       Command::load, "photo.0002.exr", "frame 2's photo"},
  };
  return rows;
}

// The lines of stderr that are not blank and not warnings.
void PrintTo(const Row& row, std::ostream* out) { *out << row.name; }

class BadInput : public testing::TestWithParam<Row> {};

TEST_P(BadInput, ExitsWithOneLineNamingTheFileAndTheProblem) {
  const Row& row = GetParam();
  SceneFolder f(row.name);
  row.make(f);
  f.write_json();

  const std::string scene = (f / row.scene_file).string();
  std::vector<std::string> args;
  fs::path output;
  switch (row.command) {
    case Command::load:
      output = f / "out_rig.json";
      args.insert(args.end(), {"rig", scene, "-o", output.string()});
      break;
    case Command::analyze:
      output = f / "analysis" / "analysis.json";
      args.insert(args.end(), {"analyze", scene, "-o", (f / "analysis").string(), "--spp", "1"});
      break;
    case Command::render:
      output = f / "relit.exr";
      args.insert(args.end(), {"render", scene, "--rig", (f / "rig.json").string(), "-o", output.string(), "--spp", "1"});
      break;
  }
  args.insert(args.end(), row.extra_args.begin(), row.extra_args.end());

  const auto [status, err] = run_cli(args);
  EXPECT_EQ(status, row.status) << err;
  const std::vector<std::string> errors = error_lines(err);
  if (row.status == 2) {
    ASSERT_EQ(errors.size(), 1u) << "expected one error line, stderr was:\n" << err;
    EXPECT_EQ(errors[0].rfind("relight: error: ", 0), 0u) << errors[0];
    EXPECT_NE(errors[0].find(row.file), std::string::npos) << "the error does not name " << row.file << ": " << errors[0];
    EXPECT_NE(errors[0].find(row.problem), std::string::npos) << "the error does not say \"" << row.problem
                                                               << "\": " << errors[0];
    EXPECT_FALSE(fs::exists(output)) << "bad input must not write " << output;
  } else {
    EXPECT_TRUE(errors.empty()) << err;
    EXPECT_TRUE(fs::exists(output)) << output;
    if (*row.problem) {
      EXPECT_NE(err.find(row.file), std::string::npos) << "the warning does not name " << row.file << ": " << err;
      EXPECT_NE(err.find(row.problem), std::string::npos) << "no warning \"" << row.problem << "\": " << err;
    } else {
      EXPECT_EQ(err.find("warning"), std::string::npos) << "no warning expected: " << err;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Catalogue, BadInput, testing::ValuesIn(catalogue()),
                         [](const testing::TestParamInfo<Row>& info) { return std::string(info.param.name); });

TEST(BadInputCatalogue, HoldsAtLeastFortyRejectedInputs) {
  const auto& rows = catalogue();
  EXPECT_GE(std::count_if(rows.begin(), rows.end(), [](const Row& r) { return r.status == 2; }), 40);
}

// The checks of the catalogue for a bad input run by hand: exit 2, one error
// line that names `file` and says `problem`.
void expect_one_error_line(const relight::test::CliResult& r, const std::string& file, const std::string& problem) {
  EXPECT_EQ(r.status, 2) << r.err;
  const std::vector<std::string> errors = error_lines(r.err);
  ASSERT_EQ(errors.size(), 1u) << r.err;
  EXPECT_NE(errors[0].find(file), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find(problem), std::string::npos) << errors[0];
}

// 44 bytes claiming 3e8 vertices: Assimp's OFF reader reserves them all
// (3.6 GB) before it reads one. The reader's child runs into its limit.
TEST(MeshReader, AHeaderClaimingMillionsOfVerticesRunsIntoTheMemoryLimit) {
  if (kAddressSanitizer) GTEST_SKIP() << "AddressSanitizer's allocator reports and aborts on a failed allocation";
  SceneFolder f("memory_bomb");
  f.scene["geometry"] = "geometry.off";
  write_text(f / "geometry.off", "OFF\n300000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  f.write_json();
  const auto r = run_cli({"rig", (f / "scene.json").string(), "-o", (f / "out_rig.json").string()});
  expect_one_error_line(r, "geometry.off", "the mesh reader ran out of its memory limit");
  EXPECT_FALSE(fs::exists(f / "out_rig.json"));
}

// A name or a key in scene.json may hold terminal escape sequences (to clear
// the screen, retitle the window, hide what follows): they reach stderr as
// text, in errors and in warnings.
TEST(BadInputText, ControlCharactersFromAFileReachTheTerminalEscaped) {
  SceneFolder f("control_characters");
  f.scene["photo"] = "\x1b]0;owned\x07\x1b[2Jphoto.exr";
  f.scene["\x1b[8mhidden"] = 1;  // an unknown key: a warning
  f.write_json();
  const auto r = run_cli({"rig", (f / "scene.json").string(), "-o", (f / "out_rig.json").string()});
  expect_one_error_line(r, "\\x1b]0;owned\\x07\\x1b[2Jphoto.exr", "file not found");
  EXPECT_NE(r.err.find("/\\x1b[8mhidden: unknown key ignored"), std::string::npos) << r.err;
  for (const char c : r.err) EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20 && c != '\n') << "control byte " << int(c);
}

// The scenes made for relight name their own files: confinement refuses
// nothing and nothing warns about a read outside.
TEST(OutsideReads, TheExampleAndTheReferenceScenesReadOnlyInsideTheirFolders) {
  std::vector<fs::path> scenes = {fs::path(RELIGHT_SOURCE_DIR) / "examples" / "room" / "scene.json"};
  for (const char* name : {"outdoor", "bookcase", "studio"})
    if (fs::exists(relight::test::reference_scenes_folder() / name / "scene.json"))
      scenes.push_back(relight::test::reference_scenes_folder() / name / "scene.json");
  SceneFolder out("confined_scenes");
  for (const fs::path& scene : scenes) {
    const auto r = run_cli({"rig", scene.string(), "-o", (out / "rig.json").string(), "--confine-to-scene-folder"});
    EXPECT_EQ(r.status, 0) << scene << ": " << r.err;
    EXPECT_EQ(r.err.find("outside"), std::string::npos) << scene << ": " << r.err;
  }
}

}  // namespace
