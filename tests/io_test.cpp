// Input and output: every loader's error cases (an InputError whose message
// names the file, the place — a JSON pointer such as /lights/0/power — and the
// problem, FORMAT.md's rule), the successful loading of a small scene and a
// rig, and the image and atomic writers.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "core/error.h"
#include "core/image.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/mesh_io.h"
#include "io/scene_io.h"
#include "temp_dir.h"

namespace relight {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

using relight::test::TempDir;

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  ASSERT_TRUE(out.good()) << path;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs f, which must throw InputError; returns its message.
std::string input_error_message(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected relight::InputError, got another exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected relight::InputError, nothing was thrown";
  return {};
}

// Asserts that `message` contains every one of `parts`.
#define EXPECT_MENTIONS(message, ...)                                                   \
  do {                                                                                  \
    const std::string msg_ = (message);                                                 \
    for (const std::string& part_ : std::initializer_list<std::string>{__VA_ARGS__})    \
      EXPECT_NE(msg_.find(part_), std::string::npos)                                    \
          << "the message \"" << msg_ << "\" does not mention \"" << part_ << "\"";     \
  } while (0)

const char* kQuadObj =
    "# a unit quad in z = 0\n"
    "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
    "f 1 2 3\nf 1 3 4\n";

Image test_photo(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.at(x, y) = Vec3(0.1f * x, 0.2f * y, 0.5f + 0.01f * (x + y));
  return img;
}

// A valid scene folder: geometry.obj, photo.exr (4 x 3), probe.exr (8 x 4)
// and the scene.json text `scene` (editable before writing).
class SceneFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    write_text(dir / "geometry.obj", kQuadObj);
    write_exr(dir / "photo.exr", test_photo(4, 3));
    write_exr(dir / "probe.exr", Image(8, 4, Vec3(0.5f, 0.5f, 0.5f)));
    scene = json::parse(R"({
      "format": "relight-scene/1",
      "photo": "photo.exr",
      "geometry": "geometry.obj",
      "camera": {"position": [0, -5, 1], "look_at": [0, 0, 0], "up": [0, 0, 1], "vfov_deg": 35},
      "lights": [
        {"type": "point", "position": [1, 2, 3], "power": 100},
        {"type": "spot", "name": "key", "color": "#ff8000", "enabled": false, "position": [0, 0, 4],
         "direction": [0, 0, -2], "power": 800, "spot_angle_deg": 40, "blend": 0.2, "radius": 0.1},
        {"type": "area", "position": [0, 0, 3], "direction": [0, 0, -1], "up": [0, 1, 0], "size": [2, 0.5],
         "power": 50, "color": [0.5, 0.25, 1.0]},
        {"type": "directional", "direction": [-0.4, 0.3, -0.87], "irradiance": 4, "angle_deg": 0.5}
      ],
      "background": [0.35, 0.45, 0.6],
      "probes": [{"image": "probe.exr", "mapping": "equirect", "position": [0, 0, 1],
                  "forward": [0, 1, 0], "up": [0, 0, 1]}]
    })");
  }

  fs::path scene_path() const { return dir / "scene.json"; }
  // Writes `scene` and loads it; returns the InputError message.
  std::string load_error() {
    write_text(scene_path(), scene.dump(2));
    return input_error_message([&] { load_scene(scene_path()); });
  }

  TempDir dir;
  json scene;
};

// ------------------------------------------------------ scene.json errors

TEST_F(SceneFolder, ValidSceneLoads) {
  write_text(scene_path(), scene.dump(2));
  EXPECT_NO_THROW(load_scene(scene_path()));
}

TEST_F(SceneFolder, MissingSceneFileIsNamed) {
  const fs::path missing = dir / "no_such_scene.json";
  EXPECT_MENTIONS(input_error_message([&] { load_scene(missing); }), missing.string(), "not found");
}

TEST_F(SceneFolder, MalformedJsonGivesLineNumber) {
  write_text(scene_path(), "{\n  \"format\": \"relight-scene/1\",\n  \"photo\": \"photo.exr\" ]\n}\n");
  EXPECT_MENTIONS(input_error_message([&] { load_scene(scene_path()); }), scene_path().string(), "line 3",
                  "malformed JSON");
}

TEST_F(SceneFolder, EmptyFileIsMalformedJson) {
  write_text(scene_path(), "");
  EXPECT_MENTIONS(input_error_message([&] { load_scene(scene_path()); }), scene_path().string(), "JSON");
}

TEST_F(SceneFolder, TopLevelArrayIsRejected) {
  write_text(scene_path(), "[1, 2, 3]");
  EXPECT_MENTIONS(input_error_message([&] { load_scene(scene_path()); }), scene_path().string(), "object");
}

TEST_F(SceneFolder, WrongFormatString) {
  scene["format"] = "relight-scene/2";
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/format", "relight-scene/1", "relight-scene/2");
}

TEST_F(SceneFolder, RigFormatIsNotASceneFormat) {
  scene["format"] = "relight-rig/1";
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/format", "relight-scene/1");
}

TEST_F(SceneFolder, MissingFormat) {
  scene.erase("format");
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/format", "missing");
}

TEST_F(SceneFolder, MissingCamera) {
  scene.erase("camera");
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/camera", "missing");
}

TEST_F(SceneFolder, MissingPhotoKey) {
  scene.erase("photo");
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/photo", "missing");
}

TEST_F(SceneFolder, MissingGeometryKey) {
  scene.erase("geometry");
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/geometry", "missing");
}

TEST_F(SceneFolder, MissingCameraKey) {
  scene["camera"].erase("look_at");
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/camera/look_at", "missing");
}

TEST_F(SceneFolder, WrongTypeForVfov) {
  scene["camera"]["vfov_deg"] = "35";
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/camera/vfov_deg", "number", "string");
}

TEST_F(SceneFolder, VfovOutOfRange) {
  scene["camera"]["vfov_deg"] = 0;
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/camera/vfov_deg");
  scene["camera"]["vfov_deg"] = 200;
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/camera/vfov_deg");
}

TEST_F(SceneFolder, CameraPositionWithTwoNumbers) {
  scene["camera"]["position"] = json::array({1, 2});
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/camera/position", "3 numbers");
}

TEST_F(SceneFolder, CameraPositionWithAString) {
  scene["camera"]["position"] = json::array({1, "x", 3});
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/camera/position/1", "number");
}

TEST_F(SceneFolder, CameraUpParallelToView) {
  scene["camera"]["up"] = json::array({0, 5, -1});  // along look_at - position
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/camera/up", "parallel");
}

TEST_F(SceneFolder, CameraDistortionWithThreeNumbers) {
  scene["camera"]["distortion"] = json::array({-0.1, 0.01, 0.0});
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/camera/distortion", "[k1, k2]");
}

// k1 = k2 = -1 on a 35-degree lens: the radius bends back 92 % of the way to the corners.
TEST_F(SceneFolder, CameraDistortionThatFoldsWithinThePhoto) {
  scene["camera"]["distortion"] = json::array({-1.0, -1.0});
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/camera/distortion", "bend", "corners");
  scene["camera"]["distortion"] = json::array({-0.1});
  write_text(scene_path(), scene.dump(2));
  EXPECT_NEAR(load_scene(scene_path()).camera.spec().distortion.x(), -0.1f, 1e-7f);
}

TEST_F(SceneFolder, CameraLookingAtItself) {
  scene["camera"]["look_at"] = scene["camera"]["position"];
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/camera/look_at");
}

TEST_F(SceneFolder, LightsNotAnArray) {
  scene["lights"] = json::object();
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights", "array");
}

TEST_F(SceneFolder, LightOfUnknownType) {
  scene["lights"][0]["type"] = "laser";
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/0/type", "laser", "point");
}

TEST_F(SceneFolder, LightWithoutType) {
  scene["lights"][2].erase("type");
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/2/type", "missing");
}

TEST_F(SceneFolder, ZeroPower) {
  scene["lights"][0]["power"] = 0;
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/0/power", "greater than 0");
}

TEST_F(SceneFolder, NegativePowerOfSecondLight) {
  scene["lights"][1]["power"] = -5;
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/1/power", "greater than 0");
}

TEST_F(SceneFolder, NegativeAreaPower) {
  scene["lights"][2]["power"] = -1.5;
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/2/power");
}

TEST_F(SceneFolder, ZeroIrradiance) {
  scene["lights"][3]["irradiance"] = 0;
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/3/irradiance");
}

TEST_F(SceneFolder, MissingPower) {
  scene["lights"][0].erase("power");
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/0/power", "missing");
}

TEST_F(SceneFolder, PowerAsString) {
  scene["lights"][0]["power"] = "100 W";
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/0/power", "number");
}

TEST_F(SceneFolder, ZeroDirectionVector) {
  scene["lights"][3]["direction"] = json::array({0, 0, 0});
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/3/direction", "non-zero");
}

TEST_F(SceneFolder, ZeroSpotDirection) {
  scene["lights"][1]["direction"] = json::array({0.0, 0.0, 0.0});
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/1/direction", "non-zero");
}

TEST_F(SceneFolder, BadHexColourCharacters) {
  scene["lights"][1]["color"] = "#ff80zz";
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/1/color", "#ff80zz", "#rrggbb");
}

TEST_F(SceneFolder, BadHexColourLength) {
  scene["lights"][0]["color"] = "#ff80";
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/0/color", "#rrggbb");
}

TEST_F(SceneFolder, NegativeColourComponent) {
  scene["lights"][2]["color"] = json::array({0.5, -0.1, 1.0});
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/2/color/1");
}

TEST_F(SceneFolder, BadBackground) {
  scene["background"] = "blue";
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/background");
}

TEST_F(SceneFolder, SpotAngleZero) {
  scene["lights"][1]["spot_angle_deg"] = 0;
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/1/spot_angle_deg");
}

TEST_F(SceneFolder, BlendAboveOne) {
  scene["lights"][1]["blend"] = 1.5;
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/1/blend");
}

TEST_F(SceneFolder, NegativeRadius) {
  scene["lights"][0]["radius"] = -0.5;
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/0/radius");
}

TEST_F(SceneFolder, AreaSizeWithOneNumber) {
  scene["lights"][2]["size"] = json::array({2});
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/2/size");
}

TEST_F(SceneFolder, AreaSizeZero) {
  scene["lights"][2]["size"] = json::array({2, 0});
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/2/size/1");
}

TEST_F(SceneFolder, AreaUpParallelToDirection) {
  scene["lights"][2]["up"] = json::array({0, 0, 3});
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/2/up", "parallel");
}

TEST_F(SceneFolder, EnabledNotABoolean) {
  scene["lights"][0]["enabled"] = "yes";
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/0/enabled");
}

// Two objects, the second's triangles in two materials (no .mtl file: the
// names alone, as `usemtl` gives them).
const char* kGlossyObj =
    "o floor\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nusemtl tiles\nf 1 2 3\nf 1 3 4\n"
    "o table\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\nusemtl varnish\nf 5 6 7\nusemtl tiles\nf 5 7 8\n";

TEST_F(SceneFolder, MaterialsShineByObjectOrMaterialName) {
  write_text(dir / "geometry.obj", kGlossyObj);
  scene["materials"] = json::parse(R"({"floor": {"roughness": 0.3}, "varnish": {"roughness": 0.1, "specular": 1}})");
  write_text(scene_path(), scene.dump(2));
  const Scene loaded = load_scene(scene_path());
  ASSERT_EQ(loaded.mesh.triangles.size(), 4u);
  ASSERT_EQ(loaded.mesh.materials, (std::vector<std::string>{"tiles", "varnish"}));
  // The floor by its object's name (its material, tiles, is not named).
  for (uint32_t t : {0u, 1u}) {
    ASSERT_NE(loaded.gloss.at(t), nullptr);
    EXPECT_EQ(*loaded.gloss.at(t), (Gloss{0.3f, 0.5f}));  // specular defaults to 0.5
  }
  ASSERT_NE(loaded.gloss.at(2), nullptr);  // the table's varnished triangle by its material
  EXPECT_EQ(*loaded.gloss.at(2), (Gloss{0.1f, 1.0f}));
  EXPECT_EQ(loaded.gloss.at(3), nullptr);  // its tiled one is matte
  EXPECT_EQ(loaded.gloss.glossy_triangles(), 3u);
  // Written back as read.
  const json written = json::parse(scene_to_json(loaded, dir.path()));
  EXPECT_EQ(written["materials"]["varnish"]["roughness"].get<float>(), 0.1f);
  EXPECT_EQ(written["materials"]["floor"]["specular"].get<float>(), 0.5f);
}

TEST_F(SceneFolder, MaterialNamingNothingInTheGeometry) {
  write_text(dir / "geometry.obj", kGlossyObj);
  scene["materials"] = json::parse(R"({"flor": {"roughness": 0.3}})");
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/materials/flor", "no object or material named \"flor\"",
                  "\"floor\"", "\"varnish\"");
}

TEST_F(SceneFolder, MaterialRoughnessOutOfRange) {
  scene["materials"] = json::parse(R"({"floor": {"roughness": 1.5}})");
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/materials/floor/roughness");
  scene["materials"] = json::parse(R"({"floor": {"specular": 0.5}})");
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/materials/floor", "roughness");
  scene["materials"] = json::parse(R"({"floor": 0.3})");
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/materials/floor", "object");
}

TEST_F(SceneFolder, LightNotAnObject) {
  scene["lights"][1] = 42;
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/lights/1", "object");
}

TEST_F(SceneFolder, EquirectProbeMustBeTwoToOne) {
  write_exr(dir / "probe.exr", Image(6, 4, Vec3::Ones()));
  const std::string msg = load_error();
  EXPECT_MENTIONS(msg, (dir / "probe.exr").string(), "twice as wide", "6x4");
}

TEST_F(SceneFolder, MirrorballProbeMustBeSquare) {
  scene["probes"][0]["mapping"] = "mirrorball";  // probe.exr is 8 x 4
  EXPECT_MENTIONS(load_error(), (dir / "probe.exr").string(), "square", "8x4");
}

TEST_F(SceneFolder, UnknownProbeMapping) {
  scene["probes"][0]["mapping"] = "cubemap";
  EXPECT_MENTIONS(load_error(), scene_path().string(), "/probes/0/mapping", "cubemap", "equirect");
}

TEST_F(SceneFolder, ProbeImageMissing) {
  scene["probes"][0]["image"] = "nowhere.exr";
  EXPECT_MENTIONS(load_error(), (dir / "nowhere.exr").string(), "not found");
}

TEST_F(SceneFolder, PhotoFileMissing) {
  fs::remove(dir / "photo.exr");
  EXPECT_MENTIONS(load_error(), (dir / "photo.exr").string(), "not found");
}

TEST_F(SceneFolder, PhotoWithNaNPixel) {
  Image photo = test_photo(4, 3);
  photo.at(2, 1).y() = std::numeric_limits<float>::quiet_NaN();
  write_exr(dir / "photo.exr", photo);
  EXPECT_MENTIONS(load_error(), (dir / "photo.exr").string(), "pixel (2, 1)", "NaN");
}

TEST_F(SceneFolder, PhotoThatIsAFolder) {
  fs::remove(dir / "photo.exr");
  fs::create_directory(dir / "photo.exr");
  EXPECT_MENTIONS(load_error(), (dir / "photo.exr").string(), "folder");
}

TEST_F(SceneFolder, PhotoThatIsNotAnImage) {
  write_text(dir / "photo.exr", "this is not an EXR file");
  EXPECT_MENTIONS(load_error(), (dir / "photo.exr").string());
}

TEST_F(SceneFolder, GeometryFileMissing) {
  scene["geometry"] = "missing.obj";
  EXPECT_MENTIONS(load_error(), (dir / "missing.obj").string(), "not found");
}

TEST_F(SceneFolder, SceneJsonThatIsAFolder) {
  fs::create_directory(dir / "folder.json");
  EXPECT_MENTIONS(input_error_message([&] { load_scene(dir / "folder.json"); }), (dir / "folder.json").string(),
                  "folder");
}

// ------------------------------------------------------ image and mesh errors

TEST(ImageErrors, MissingFile) {
  TempDir dir;
  EXPECT_MENTIONS(input_error_message([&] { read_image(dir / "absent.exr"); }), (dir / "absent.exr").string(),
                  "not found");
}

// The default pixel limit is the largest photo whose analysis fits in half
// of this machine's memory (an analysis peaks at about 150 MiB + 135 bytes a
// pixel: docs/benchmarks.md, "Photo size"): a 45-Mpixel camera photo opens
// where that holds. Refused, the message says why; a limit the user set is
// just named.
std::string pixel_limit_message(int64_t width, int64_t height) {
  return input_error_message([&] { expect_within_pixel_limit("photo.exr", "image", width, height); });
}

TEST(ImageErrors, TheDefaultPixelLimitIsWhatHalfOfTheMachinesMemoryAnalyses) {
  const int64_t memory = int64_t(::sysconf(_SC_PHYS_PAGES)) * ::sysconf(_SC_PAGE_SIZE);
  ASSERT_GT(memory, 0);
  const int64_t camera_photo = int64_t(8256) * 5504;  // 45.4 Mpixel
  const bool fits = (int64_t(150) << 20) + 135 * camera_photo <= memory / 2;
  EXPECT_EQ(max_image_pixels(), default_max_image_pixels());
  if (fits)
    EXPECT_NO_THROW(expect_within_pixel_limit("photo.exr", "image", 8256, 5504)) << memory << " bytes of memory";
  else
    EXPECT_NE(pixel_limit_message(8256, 5504).find("is over the limit"), std::string::npos);
  EXPECT_NE(pixel_limit_message(100000, 100000).find("fits in half of this machine's"), std::string::npos);

  set_max_image_pixels(40);
  const std::string set_by_the_user = pixel_limit_message(8, 6);
  set_max_image_pixels(default_max_image_pixels());
  EXPECT_NE(set_by_the_user.find("is over the limit of 0.0 Mpixel (raise it with --max-pixels"), std::string::npos)
      << set_by_the_user;
}

TEST(ImageErrors, NaNPixelIsReportedWithItsPosition) {
  TempDir dir;
  Image img(3, 2, Vec3(1, 1, 1));
  img.at(1, 1).z() = std::numeric_limits<float>::quiet_NaN();
  write_exr(dir / "nan.exr", img);
  EXPECT_MENTIONS(input_error_message([&] { read_image(dir / "nan.exr"); }), (dir / "nan.exr").string(),
                  "pixel (1, 1)", "NaN");
}

TEST(ImageErrors, InfinitePixelIsReported) {
  TempDir dir;
  Image img(3, 2, Vec3(1, 1, 1));
  img.at(0, 1).x() = std::numeric_limits<float>::infinity();
  write_exr(dir / "inf.exr", img);
  EXPECT_MENTIONS(input_error_message([&] { read_image(dir / "inf.exr"); }), (dir / "inf.exr").string(),
                  "pixel (0, 1)", "infinite");
}

TEST(ImageErrors, PathThatIsAFolder) {
  TempDir dir;
  EXPECT_MENTIONS(input_error_message([&] { read_image(dir.path()); }), dir.path().string(), "folder");
}

TEST(ImageErrors, GarbageFile) {
  TempDir dir;
  write_text(dir / "garbage.png", "definitely not a PNG");
  EXPECT_MENTIONS(input_error_message([&] { read_image(dir / "garbage.png"); }), (dir / "garbage.png").string());
}

// A portrait taken with the camera turned, stored sideways with an EXIF
// Orientation of 6 (show it turned 90 degrees clockwise), is read as shown:
// the stored bottom-left pixel is the top-left one.
TEST(ImageErrors, APhotoStoredSidewaysIsReadUprightAsItsOrientationSays) {
  TempDir dir;
  const fs::path file = dir / "portrait.tif";
  OIIO::ImageSpec spec(3, 2, 3, OIIO::TypeDesc::FLOAT);
  spec.attribute("Orientation", 6);
  std::vector<float> stored(3 * 2 * 3);
  for (size_t i = 0; i < stored.size(); ++i) stored[i] = float(i) / float(stored.size());
  const auto out = OIIO::ImageOutput::create(file.string());
  ASSERT_TRUE(out && out->open(file.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, stored.data()) &&
              out->close());
  const Image upright = read_image(file);
  ASSERT_EQ(upright.width, 2);
  ASSERT_EQ(upright.height, 3);
  const auto stored_pixel = [&](int x, int y) { return stored[size_t(3 * (y * 3 + x))]; };
  EXPECT_EQ(upright.at(0, 0).x(), stored_pixel(0, 1));  // the stored bottom-left
  EXPECT_EQ(upright.at(1, 0).x(), stored_pixel(0, 0));  // the stored top-left
  EXPECT_EQ(upright.at(0, 2).x(), stored_pixel(2, 1));  // the stored bottom-right
}

TEST(MeshErrors, MissingFile) {
  TempDir dir;
  EXPECT_MENTIONS(input_error_message([&] { load_mesh(dir / "absent.obj"); }), (dir / "absent.obj").string(),
                  "not found");
}

TEST(MeshErrors, PathThatIsAFolder) {
  TempDir dir;
  EXPECT_MENTIONS(input_error_message([&] { load_mesh(dir.path()); }), dir.path().string(), "folder");
}

TEST(MeshErrors, OnlyVerticesNoTriangles) {
  TempDir dir;
  write_text(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  EXPECT_MENTIONS(input_error_message([&] { load_mesh(dir / "points.obj"); }), (dir / "points.obj").string(), "mesh");
}

TEST(MeshErrors, OnlyLinesNoTriangles) {
  TempDir dir;
  write_text(dir / "lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n");
  EXPECT_MENTIONS(input_error_message([&] { load_mesh(dir / "lines.obj"); }), (dir / "lines.obj").string(),
                  "triangles");
}

TEST(MeshErrors, OnlyDegenerateTriangles) {
  TempDir dir;
  write_text(dir / "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  EXPECT_MENTIONS(input_error_message([&] { load_mesh(dir / "flat.obj"); }), (dir / "flat.obj").string(),
                  "degenerate");
}

TEST(MeshErrors, NaNVertex) {
  TempDir dir;
  write_text(dir / "nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_MENTIONS(input_error_message([&] { load_mesh(dir / "nan.obj"); }), (dir / "nan.obj").string(), "NaN");
}

TEST(MeshErrors, EmptyFile) {
  TempDir dir;
  write_text(dir / "empty.obj", "");
  EXPECT_MENTIONS(input_error_message([&] { load_mesh(dir / "empty.obj"); }), (dir / "empty.obj").string());
}

TEST(Mesh, RefusesDegenerateTrianglesUnlessRepairing) {
  TempDir dir;
  write_text(dir / "mesh.obj", std::string(kQuadObj) + "v 5 5 5\nv 6 6 6\nv 7 7 7\nf 5 6 7\n");
  EXPECT_THROW(load_mesh(dir / "mesh.obj"), InputError);
  set_repair_meshes(true);
  TriangleMesh mesh;
  try {
    mesh = load_mesh(dir / "mesh.obj");
  } catch (...) {
    set_repair_meshes(false);
    throw;
  }
  set_repair_meshes(false);
  ASSERT_EQ(mesh.triangles.size(), 2u);
  // The two kept triangles are the quad's: their corners span [-1, 1]^2 in z = 0.
  Eigen::AlignedBox3f box;
  for (const auto& t : mesh.triangles)
    for (uint32_t i : t) {
      ASSERT_LT(i, mesh.positions.size());
      box.extend(mesh.positions[i]);
    }
  EXPECT_EQ(box.min(), Vec3(-1, -1, 0));
  EXPECT_EQ(box.max(), Vec3(1, 1, 0));
  EXPECT_FALSE(mesh.has_normals());
}

TEST(Mesh, KeepsNormalsWhenTheFileHasThem) {
  TempDir dir;
  write_text(dir / "n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n");
  const TriangleMesh mesh = load_mesh(dir / "n.obj");
  ASSERT_EQ(mesh.triangles.size(), 1u);
  ASSERT_TRUE(mesh.has_normals());
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  for (const auto& n : mesh.normals) EXPECT_LT((n - Vec3(0, 0, 1)).norm(), 1e-6f);
}

// ------------------------------------------------------------ rig errors

class RigFile : public ::testing::Test {
 protected:
  void SetUp() override {
    rig = json::parse(R"({
      "format": "relight-rig/1",
      "environment_scale": 0.5,
      "lights": [
        {"name": "key", "type": "spot", "position": [2, -3, 3], "direction": [-0.4, 0.6, -0.7],
         "color": "#ffd8a8", "power": 800, "spot_angle_deg": 40, "blend": 0.2},
        {"type": "point", "position": [0, 0, 2], "power": 10}
      ]
    })");
  }
  fs::path rig_path() const { return dir / "rig.json"; }
  std::string load_error() {
    write_text(rig_path(), rig.dump(2));
    return input_error_message([&] { load_rig(rig_path()); });
  }
  TempDir dir;
  json rig;
};

TEST_F(RigFile, ValidRigLoads) {
  write_text(rig_path(), rig.dump(2));
  const Rig r = load_rig(rig_path());
  EXPECT_FLOAT_EQ(r.environment_scale, 0.5f);
  ASSERT_EQ(r.lights.size(), 2u);
  EXPECT_EQ(r.lights[0].name, "key");
  EXPECT_EQ(r.lights[0].type, LightType::spot);
  EXPECT_EQ(r.lights[1].name, "point 1");
  EXPECT_NEAR(r.lights[0].direction.norm(), 1.0f, 1e-6f);
}

TEST_F(RigFile, DefaultEnvironmentScaleIsOne) {
  rig.erase("environment_scale");
  rig.erase("lights");
  write_text(rig_path(), rig.dump(2));
  const Rig r = load_rig(rig_path());
  EXPECT_EQ(r.environment_scale, 1.0f);
  EXPECT_TRUE(r.lights.empty());
}

TEST_F(RigFile, MissingFile) {
  EXPECT_MENTIONS(input_error_message([&] { load_rig(dir / "absent.json"); }), (dir / "absent.json").string(),
                  "not found");
}

TEST_F(RigFile, Folder) {
  EXPECT_MENTIONS(input_error_message([&] { load_rig(dir.path()); }), dir.path().string(), "folder");
}

TEST_F(RigFile, MalformedJsonGivesLineNumber) {
  write_text(rig_path(), "{\n\"format\": \"relight-rig/1\",\n\"lights\": [\n{\"type\": \"point\",,}\n]\n}\n");
  EXPECT_MENTIONS(input_error_message([&] { load_rig(rig_path()); }), rig_path().string(), "line 4", "malformed");
}

TEST_F(RigFile, SceneFormatIsNotARigFormat) {
  rig["format"] = "relight-scene/1";
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/format", "relight-rig/1", "relight-scene/1");
}

TEST_F(RigFile, NegativeEnvironmentScale) {
  rig["environment_scale"] = -1;
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/environment_scale");
}

TEST_F(RigFile, EnvironmentScaleAsString) {
  rig["environment_scale"] = "1";
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/environment_scale", "number");
}

// ------------------------------------------------------------ an animated rig's keys

TEST_F(RigFile, KeysLoadAndRoundTrip) {
  rig["lights"][0]["keys"] = json::parse(R"([
    {"frame": 1, "position": [2, -3, 3], "power": 800},
    {"frame": 24, "direction": [0, 1, -1], "interpolation": "linear"},
    {"frame": 48, "color": [1, 0.5, 0.25], "enabled": false, "interpolation": "constant"}
  ])");
  write_text(rig_path(), rig.dump(2));
  const Rig r = load_rig(rig_path());
  const std::vector<LightKey>& keys = r.lights.at(0).keys;
  ASSERT_EQ(keys.size(), 3u);
  EXPECT_EQ(keys[0].frame, 1);
  EXPECT_EQ(keys[0].interpolation, Interpolation::smooth);
  EXPECT_EQ(*keys[0].position, Vec3(2, -3, 3));
  EXPECT_EQ(*keys[0].power, 800.0f);
  EXPECT_FALSE(keys[0].direction.has_value());
  EXPECT_NEAR(keys[1].direction->y(), std::sqrt(0.5f), 1e-6f);  // normalised
  EXPECT_EQ(keys[1].interpolation, Interpolation::linear);
  EXPECT_EQ(*keys[2].enabled, false);
  EXPECT_EQ(keys[2].interpolation, Interpolation::constant);
  EXPECT_TRUE(r.lights.at(1).keys.empty());

  save_rig(dir / "saved.json", r);  // the studio's Save Rig keeps the animation
  const Rig back = load_rig(dir / "saved.json");
  ASSERT_EQ(back.lights.at(0).keys.size(), 3u);
  EXPECT_EQ(back.lights.at(0).keys[1].frame, 24);
  EXPECT_TRUE(back.lights.at(0).keys[1].direction->isApprox(*keys[1].direction, 1e-6f));
  EXPECT_EQ(back.lights.at(0).keys[2].interpolation, Interpolation::constant);
  EXPECT_EQ(*back.lights.at(0).keys[2].color, *keys[2].color);
}

TEST_F(RigFile, KeysOutOfOrder) {
  rig["lights"][0]["keys"] = json::parse(R"([{"frame": 10, "power": 1}, {"frame": 5, "power": 2}])");
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/lights/0/keys/1/frame", "5 after 10");
}

TEST_F(RigFile, KeyFrameNotWhole) {
  rig["lights"][1]["keys"] = json::parse(R"([{"frame": 1.5, "power": 1}])");
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/lights/1/keys/0/frame", "whole");
}

TEST_F(RigFile, KeyOfAValueTheLightHasNot) {
  rig["lights"][1]["keys"] = json::parse(R"([{"frame": 1, "direction": [0, 0, -1]}])");
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/lights/1/keys/0/direction", "point light has no direction");
}

TEST_F(RigFile, UnknownInterpolation) {
  rig["lights"][1]["keys"] = json::parse(R"([{"frame": 1, "power": 3, "interpolation": "bezier"}])");
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/lights/1/keys/0/interpolation", "bezier", "smooth");
}

// ------------------------------------------------------------ a rig's new environment

TEST_F(RigFile, WithoutEnvironmentTheSceneKeepsItsOwn) {
  write_text(rig_path(), rig.dump(2));
  EXPECT_FALSE(load_rig(rig_path()).environment.has_value());
}

TEST_F(RigFile, ConstantEnvironmentLoads) {
  rig["environment"] = {{"color", {0.2, 0.3, 0.4}}};
  write_text(rig_path(), rig.dump(2));
  const Rig r = load_rig(rig_path());
  ASSERT_TRUE(r.environment.has_value());
  EXPECT_EQ(r.environment->color, Vec3(0.2f, 0.3f, 0.4f));
  EXPECT_EQ(r.environment->image, nullptr);
}

// The image is relative to the rig's folder, mapped as a probe's.
TEST_F(RigFile, ImageEnvironmentLoads) {
  fs::create_directories(dir / "skies");
  write_exr(dir / "skies" / "sky.exr", Image(8, 4, Vec3(1.0f, 2.0f, 3.0f)));
  rig["environment"] = {{"image", "skies/sky.exr"}, {"mapping", "equirect"}, {"forward", {2, 0, 0}}, {"up", {0, 0, 1}}};
  write_text(rig_path(), rig.dump(2));
  const Rig r = load_rig(rig_path());
  ASSERT_TRUE(r.environment && r.environment->image);
  const Probe& sky = *r.environment->image;
  EXPECT_EQ(fs::path(sky.path), dir / "skies" / "sky.exr");
  EXPECT_EQ(sky.mapping, ProbeMapping::equirect);
  EXPECT_EQ(sky.forward, Vec3(1, 0, 0));
  EXPECT_EQ(sky.up, Vec3(0, 0, 1));
  EXPECT_EQ(sky.image.width, 8);
  EXPECT_EQ(sky.image.at(3, 2), Vec3(1.0f, 2.0f, 3.0f));
}

// Saved elsewhere (the studio's Save Rig As), the image path is rewritten
// relative to the new rig; the frame and the colour come back unchanged.
TEST_F(RigFile, EnvironmentRoundTrips) {
  write_exr(dir / "sky.exr", Image(4, 4, Vec3(0.5f, 0.5f, 0.5f)));
  rig["environment"] = {{"image", "sky.exr"}, {"mapping", "mirrorball"}, {"forward", {0, 1, 0}}, {"up", {0, 0, 1}}};
  write_text(rig_path(), rig.dump(2));
  const Rig r = load_rig(rig_path());
  fs::create_directories(dir / "saved");
  save_rig(dir / "saved" / "rig.json", r);
  EXPECT_EQ(json::parse(read_text(dir / "saved" / "rig.json"))["environment"]["image"], "../sky.exr");
  const Rig back = load_rig(dir / "saved" / "rig.json");
  ASSERT_TRUE(back.environment && back.environment->image);
  EXPECT_EQ(fs::path(back.environment->image->path).lexically_normal(), dir / "sky.exr");
  EXPECT_EQ(back.environment->image->mapping, ProbeMapping::mirrorball);
  EXPECT_EQ(back.environment->image->forward, Vec3(0, 1, 0));

  Rig constant = r;
  constant.environment = RigEnvironment{Vec3(0.25f, 0.5f, 1.0f), nullptr};
  save_rig(dir / "constant.json", constant);
  const Rig constant_back = load_rig(dir / "constant.json");
  ASSERT_TRUE(constant_back.environment.has_value());
  EXPECT_EQ(constant_back.environment->color, Vec3(0.25f, 0.5f, 1.0f));
  EXPECT_EQ(constant_back.environment->image, nullptr);
}

TEST_F(RigFile, EnvironmentWithBothColorAndImage) {
  write_exr(dir / "sky.exr", Image(8, 4, Vec3::Ones()));
  rig["environment"] = {{"color", {1, 1, 1}}, {"image", "sky.exr"}, {"mapping", "equirect"},
                        {"forward", {1, 0, 0}}, {"up", {0, 0, 1}}};
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/environment", "not both");
}

TEST_F(RigFile, EnvironmentMissingImage) {
  rig["environment"] = {{"image", "absent.exr"}, {"mapping", "equirect"}, {"forward", {1, 0, 0}}, {"up", {0, 0, 1}}};
  EXPECT_MENTIONS(load_error(), (dir / "absent.exr").string(), "not found");
}

TEST_F(RigFile, EnvironmentUnknownMapping) {
  write_exr(dir / "sky.exr", Image(8, 4, Vec3::Ones()));
  rig["environment"] = {{"image", "sky.exr"}, {"mapping", "cubemap"}, {"forward", {1, 0, 0}}, {"up", {0, 0, 1}}};
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/environment/mapping", "cubemap");
}

TEST_F(RigFile, EnvironmentForwardParallelToUp) {
  write_exr(dir / "sky.exr", Image(8, 4, Vec3::Ones()));
  rig["environment"] = {{"image", "sky.exr"}, {"mapping", "equirect"}, {"forward", {0, 0, 2}}, {"up", {0, 0, 1}}};
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/environment/up", "parallel");
}

TEST_F(RigFile, EnvironmentNegativeColor) {
  rig["environment"] = {{"color", {0.5, -0.1, 0.5}}};
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/environment/color/1");
}

TEST_F(RigFile, EnvironmentNeitherColorNorImage) {
  rig["environment"] = json::object();
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/environment", "color", "image");
}

// The studio's Image…: an HDR image alone is a new sky, equirect or mirror
// ball by its shape, in Blender's default frame; another shape, or an image
// that cannot be read, is an error naming the file.
TEST_F(RigFile, AnImageAloneIsANewSky) {
  write_exr(dir / "wide.exr", Image(8, 4, Vec3(1.0f, 2.0f, 3.0f)));
  write_exr(dir / "ball.exr", Image(6, 6, Vec3::Ones()));
  write_exr(dir / "odd.exr", Image(6, 4, Vec3::Ones()));
  const RigEnvironment wide = load_environment_image(dir / "wide.exr");
  ASSERT_TRUE(wide.image);
  EXPECT_EQ(wide.image->mapping, ProbeMapping::equirect);
  EXPECT_EQ(wide.image->forward, Vec3(1, 0, 0));
  EXPECT_EQ(wide.image->up, Vec3(0, 0, 1));
  EXPECT_EQ(wide.image->image.at(7, 3), Vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(load_environment_image(dir / "ball.exr").image->mapping, ProbeMapping::mirrorball);
  const auto error_of = [](const fs::path& path) {
    try {
      load_environment_image(path);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_MENTIONS(error_of(dir / "odd.exr"), (dir / "odd.exr").string(), "twice as wide", "6x4");
  EXPECT_MENTIONS(error_of(dir / "absent.exr"), (dir / "absent.exr").string(), "not found");
}

TEST_F(RigFile, ZeroPower) {
  rig["lights"][1]["power"] = 0;
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/lights/1/power");
}

TEST_F(RigFile, UnknownLightType) {
  rig["lights"][0]["type"] = "torch";
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/lights/0/type", "torch");
}

TEST_F(RigFile, BadHexColour) {
  rig["lights"][0]["color"] = "ffd8a8";  // no '#'
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/lights/0/color", "#rrggbb");
}

TEST_F(RigFile, ZeroDirection) {
  rig["lights"][0]["direction"] = json::array({0, 0, 0});
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/lights/0/direction", "non-zero");
}

TEST_F(RigFile, MissingSpotAngle) {
  rig["lights"][0].erase("spot_angle_deg");
  EXPECT_MENTIONS(load_error(), rig_path().string(), "/lights/0/spot_angle_deg", "missing");
}

// ------------------------------------------------------------ success

TEST_F(SceneFolder, LoadsTheRightValues) {
  // Load from another working directory: paths are relative to scene.json.
  write_text(scene_path(), scene.dump(2));
  const fs::path cwd = fs::current_path();
  fs::current_path(fs::temp_directory_path());
  Scene loaded;
  try {
    loaded = load_scene(scene_path());
  } catch (...) {
    fs::current_path(cwd);
    throw;
  }
  fs::current_path(cwd);
  const Scene& s = loaded;

  EXPECT_EQ(s.path, scene_path());
  EXPECT_EQ(s.photo_path, dir / "photo.exr");
  EXPECT_EQ(s.geometry_path, dir / "geometry.obj");

  // Photo and camera bound to it.
  ASSERT_EQ(s.photo.width, 4);
  ASSERT_EQ(s.photo.height, 3);
  const Image expected_photo = test_photo(4, 3);
  for (size_t i = 0; i < s.photo.size(); ++i) EXPECT_EQ(s.photo.pixels[i], expected_photo.pixels[i]) << i;
  EXPECT_EQ(s.camera.width(), 4);
  EXPECT_EQ(s.camera.height(), 3);
  EXPECT_EQ(s.camera.spec().position, Vec3(0, -5, 1));
  EXPECT_EQ(s.camera.spec().look_at, Vec3(0, 0, 0));
  EXPECT_FLOAT_EQ(s.camera.spec().vfov_deg, 35.0f);
  EXPECT_LT((s.camera.spec().up - Vec3(0, 0, 1)).norm(), 1e-6f);

  EXPECT_EQ(s.mesh.triangles.size(), 2u);
  EXPECT_EQ(s.background, Vec3(0.35f, 0.45f, 0.6f));

  ASSERT_EQ(s.lights.size(), 4u);
  // Light 0: every default.
  const Light& p = s.lights[0];
  EXPECT_EQ(p.type, LightType::point);
  EXPECT_EQ(p.name, "point 0");
  EXPECT_EQ(p.color, Vec3::Ones());
  EXPECT_TRUE(p.enabled);
  EXPECT_EQ(p.position, Vec3(1, 2, 3));
  EXPECT_EQ(p.power, 100.0f);
  EXPECT_EQ(p.radius, 0.0f);

  // Light 1: hex colour linearised, disabled, normalised direction.
  const Light& sp = s.lights[1];
  EXPECT_EQ(sp.type, LightType::spot);
  EXPECT_EQ(sp.name, "key");
  EXPECT_FALSE(sp.enabled);
  // sRGB decode of 0x80 = 128/255: ((c + 0.055)/1.055)^2.4 = 0.215861.
  const double c80 = std::pow((128.0 / 255.0 + 0.055) / 1.055, 2.4);
  EXPECT_NEAR(sp.color.x(), 1.0, 1e-6);
  EXPECT_NEAR(sp.color.y(), c80, 1e-5);
  EXPECT_NEAR(sp.color.y(), 0.215861, 1e-5);
  EXPECT_EQ(sp.color.z(), 0.0f);
  EXPECT_LT((sp.direction - Vec3(0, 0, -1)).norm(), 1e-6f);
  EXPECT_EQ(sp.power, 800.0f);
  EXPECT_FLOAT_EQ(sp.spot_angle_deg, 40.0f);
  EXPECT_FLOAT_EQ(sp.blend, 0.2f);
  EXPECT_FLOAT_EQ(sp.radius, 0.1f);

  const Light& a = s.lights[2];
  EXPECT_EQ(a.type, LightType::area);
  EXPECT_EQ(a.name, "area 2");
  EXPECT_EQ(a.color, Vec3(0.5f, 0.25f, 1.0f));
  EXPECT_EQ(a.size, Vec2(2.0f, 0.5f));
  EXPECT_EQ(a.power, 50.0f);
  EXPECT_LT((a.up - Vec3(0, 1, 0)).norm(), 1e-6f);
  EXPECT_EQ(a.emission(), Vec3(25.0f, 12.5f, 50.0f));

  const Light& d = s.lights[3];
  EXPECT_EQ(d.type, LightType::directional);
  EXPECT_EQ(d.name, "directional 3");
  EXPECT_LT((d.direction - Vec3(-0.4f, 0.3f, -0.87f).normalized()).norm(), 1e-6f);
  EXPECT_EQ(d.irradiance, 4.0f);
  EXPECT_FLOAT_EQ(d.angle_deg, 0.5f);

  ASSERT_EQ(s.probes.size(), 1u);
  EXPECT_EQ(s.probes[0].mapping, ProbeMapping::equirect);
  EXPECT_EQ(s.probes[0].image.width, 8);
  EXPECT_EQ(s.probes[0].image.height, 4);
  EXPECT_EQ(s.probes[0].position, Vec3(0, 0, 1));
  EXPECT_EQ(fs::path(s.probes[0].path), dir / "probe.exr");
}

// A probe's `scale` (what relight fit finds to bring it to the photo's
// units) multiplies its image as read, and is written back.
TEST_F(SceneFolder, AProbesScaleMultipliesItsImageAndIsSaved) {
  scene["probes"][0]["scale"] = {2.0, 0.5, 4.0};
  write_text(scene_path(), scene.dump(2));
  const Scene s = load_scene(scene_path());
  EXPECT_EQ(s.probes[0].image.at(3, 2), Vec3(1.0f, 0.25f, 2.0f));
  write_text(dir / "saved.json", scene_to_json(s, dir.path()));
  const Scene again = load_scene(dir / "saved.json");
  EXPECT_EQ(again.probes[0].scale, Vec3(2.0f, 0.5f, 4.0f));
  EXPECT_EQ(again.probes[0].image.at(3, 2), Vec3(1.0f, 0.25f, 2.0f));  // scaled once, not twice
}

TEST_F(SceneFolder, OptionalKeysDefault) {
  scene.erase("lights");
  scene.erase("background");
  scene.erase("probes");
  write_text(scene_path(), scene.dump(2));
  const Scene s = load_scene(scene_path());
  EXPECT_TRUE(s.lights.empty());
  EXPECT_EQ(s.background, Vec3::Zero());
  EXPECT_TRUE(s.probes.empty());
}

TEST_F(SceneFolder, UppercaseHexColourAndNullOptionalValues) {
  scene["background"] = "#FFFFFF";
  scene["lights"][0]["color"] = "#0A0B0C";
  scene["lights"][0]["name"] = nullptr;  // null counts as absent
  write_text(scene_path(), scene.dump(2));
  const Scene s = load_scene(scene_path());
  EXPECT_LT((s.background - Vec3::Ones()).norm(), 1e-6f);
  // 0x0a/255 = 0.0392 is in the linear segment of sRGB: c / 12.92.
  EXPECT_NEAR(s.lights[0].color.x(), 10.0 / 255.0 / 12.92, 1e-6);
  EXPECT_NEAR(s.lights[0].color.y(), std::pow((11.0 / 255.0 + 0.055) / 1.055, 2.4), 1e-6);
  EXPECT_NEAR(s.lights[0].color.z(), std::pow((12.0 / 255.0 + 0.055) / 1.055, 2.4), 1e-6);
  EXPECT_EQ(s.lights[0].name, "point 0");
}

TEST_F(SceneFolder, UnknownKeysAreIgnored) {
  scene["comment"] = "made by hand";
  scene["lights"][0]["flicker"] = true;
  write_text(scene_path(), scene.dump(2));
  EXPECT_EQ(load_scene(scene_path()).lights.size(), 4u);
}

// A value typed as 0.85 is saved as 0.85 (the shortest decimal that reads
// back as the float), not as 0.8500000238418579, and still reads back exactly.
TEST(RigRoundTrip, FloatsAreWrittenAsTyped) {
  Rig rig;
  Light lamp;
  lamp.color = Vec3(0.85f, 1.0f / 3.0f, 0.1f);
  lamp.power = 60.7f;
  rig.lights = {lamp};
  const std::string text = rig_to_json(rig);
  EXPECT_NE(text.find("0.85,"), std::string::npos) << text;
  EXPECT_NE(text.find("60.7"), std::string::npos) << text;
  EXPECT_EQ(text.find("0.8500000"), std::string::npos) << text;
  EXPECT_EQ(text.find("60.70000"), std::string::npos) << text;
  TempDir dir;
  save_rig(dir / "rig.json", rig);
  const Rig back = load_rig(dir / "rig.json");
  EXPECT_EQ(back.lights.at(0).color, lamp.color);
  EXPECT_EQ(back.lights.at(0).power, lamp.power);
}

TEST(RigRoundTrip, SaveThenLoadGivesTheSameLights) {
  TempDir dir;
  Rig rig;
  rig.environment_scale = 0.75f;
  Light point;
  point.type = LightType::point;
  point.name = "bulb";
  point.position = Vec3(1.25f, -2.5f, 3.0f);
  point.power = 60.0f;
  point.radius = 0.05f;
  point.color = Vec3(1.0f, 0.9f, 0.7f);
  Light spot;
  spot.type = LightType::spot;
  spot.name = "key";
  spot.enabled = false;
  spot.position = Vec3(2, -3, 3);
  spot.direction = Vec3(-0.4f, 0.6f, -0.7f).normalized();
  spot.power = 800.0f;
  spot.spot_angle_deg = 40.0f;
  spot.blend = 0.2f;
  Light area;
  area.type = LightType::area;
  area.name = "softbox";
  area.position = Vec3(0, 1, 2.5f);
  area.direction = Vec3(0.1f, -0.2f, -1.0f).normalized();
  area.up = Vec3(0, 1, 0);
  area.size = Vec2(1.2f, 0.6f);
  area.power = 300.0f;
  Light sun;
  sun.type = LightType::directional;
  sun.name = "sun";
  sun.direction = Vec3(-0.4f, 0.3f, -0.87f).normalized();
  sun.irradiance = 4.0f;
  sun.angle_deg = 0.5f;
  sun.color = Vec3(1.0f, 0.95f, 0.9f);
  rig.lights = {point, spot, area, sun};

  save_rig(dir / "rig.json", rig);
  const Rig back = load_rig(dir / "rig.json");
  EXPECT_EQ(back.environment_scale, rig.environment_scale);
  ASSERT_EQ(back.lights.size(), rig.lights.size());
  for (size_t i = 0; i < rig.lights.size(); ++i) {
    const Light& a = rig.lights[i];
    const Light& b = back.lights[i];
    SCOPED_TRACE(a.name);
    EXPECT_EQ(b.type, a.type);
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.enabled, a.enabled);
    EXPECT_LT((b.color - a.color).norm(), 1e-6f);
    EXPECT_EQ(b.power, a.power);
    EXPECT_EQ(b.irradiance, a.irradiance);
    EXPECT_EQ(b.emission(), a.emission());
    if (a.type != LightType::directional) {
      EXPECT_LT((b.position - a.position).norm(), 1e-6f);
    }
    if (a.type != LightType::point) {
      EXPECT_LT((b.direction - a.direction).norm(), 1e-6f);
    }
    if (a.type == LightType::point || a.type == LightType::spot) {
      EXPECT_EQ(b.radius, a.radius);
    }
    if (a.type == LightType::spot) {
      EXPECT_EQ(b.spot_angle_deg, a.spot_angle_deg);
      EXPECT_EQ(b.blend, a.blend);
    }
    if (a.type == LightType::area) {
      EXPECT_EQ(b.size, a.size);
      EXPECT_LT((b.up - a.up).norm(), 1e-6f);
    }
    if (a.type == LightType::directional) {
      EXPECT_EQ(b.angle_deg, a.angle_deg);
    }
  }
  // A second round trip changes nothing beyond float rounding.
  save_rig(dir / "rig2.json", back);
  const Rig again = load_rig(dir / "rig2.json");
  ASSERT_EQ(again.lights.size(), back.lights.size());
  for (size_t i = 0; i < back.lights.size(); ++i) {
    EXPECT_EQ(again.lights[i].name, back.lights[i].name);
    EXPECT_LT((again.lights[i].direction - back.lights[i].direction).norm(), 1e-6f);
    EXPECT_LT((again.lights[i].position - back.lights[i].position).norm(), 1e-6f);
  }
}

// ------------------------------------------------------------ writers

TEST(ImageWriters, ExrRoundTripIsExact) {
  TempDir dir;
  Image img(5, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x)
      img.at(x, y) = Vec3(std::ldexp(1.2345678f, x - 20), 0.1f * float(x * 7 + y) + 1e-3f, 12345.678f * float(y + 1));
  img.at(0, 0) = Vec3::Zero();
  write_exr(dir / "img.exr", img);
  const Image back = read_image(dir / "img.exr");
  ASSERT_EQ(back.width, 5);
  ASSERT_EQ(back.height, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) EXPECT_EQ(back.at(x, y), img.at(x, y)) << x << "," << y;
}

TEST(ImageWriters, HalfExrRoundTripIsClose) {
  TempDir dir;
  Image img(4, 2);
  for (size_t i = 0; i < img.size(); ++i) img.pixels[i] = Vec3(0.3f * i, 1.7f + i, 100.0f / (1 + i));
  write_exr(dir / "half.exr", img, ExrPrecision::half);
  const Image back = read_image(dir / "half.exr");
  ASSERT_EQ(back.size(), img.size());
  for (size_t i = 0; i < img.size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back.pixels[i][c], img.pixels[i][c], 1e-3f * img.pixels[i][c] + 1e-6f);
}

TEST(ImageWriters, ScalarExrRoundTrip) {
  TempDir dir;
  const std::vector<float> values = {0.0f, 0.25f, 1.0f, 0.5f, 0.75f, 1.0f};
  write_exr_scalar(dir / "mask.exr", values, 3, 2);
  int w = 0, h = 0;
  EXPECT_EQ(read_scalar_image(dir / "mask.exr", w, h), values);
  EXPECT_EQ(w, 3);
  EXPECT_EQ(h, 2);
}

TEST(ImageWriters, PngIsAReadable8BitSrgbFile) {
  TempDir dir;
  Image img(3, 2);
  img.at(0, 0) = Vec3(0.0f, 0.5f, 1.0f);
  img.at(1, 0) = Vec3(0.18f, 0.02f, 0.7f);
  img.at(2, 0) = Vec3(2.0f, 0.001f, 0.25f);  // 2 clips to 1
  img.at(0, 1) = Vec3(0.9f, 0.1f, 0.05f);
  img.at(1, 1) = Vec3(0.3f, 0.3f, 0.3f);
  img.at(2, 1) = Vec3(0.6f, 0.4f, 0.2f);
  const fs::path path = dir / "out.png";
  write_png(path, img);

  auto in = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  EXPECT_EQ(in->spec().width, 3);
  EXPECT_EQ(in->spec().height, 2);
  EXPECT_EQ(in->spec().nchannels, 3);
  EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT8);
  std::vector<unsigned char> bytes(3 * 2 * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, bytes.data()));
  in->close();
  // The bytes are the sRGB encoding of the clipped linear values.
  auto encode = [](double v) {
    v = std::clamp(v, 0.0, 1.0);
    const double e = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
    return int(std::lround(e * 255.0));
  };
  for (int p = 0; p < 6; ++p)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(int(bytes[p * 3 + c]), encode(img.pixels[p][c]), 1) << "pixel " << p << " channel " << c;
  EXPECT_EQ(bytes[0 * 3 + 2], 255);  // 1.0 is full white
  EXPECT_EQ(bytes[2 * 3 + 0], 255);  // 2.0 clips
  EXPECT_EQ(bytes[0], 0);

  // read_image takes it as sRGB and linearises it back.
  const Image back = read_image(path);
  for (size_t p = 0; p < img.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      const float expected = std::min(img.pixels[p][c], 1.0f);
      EXPECT_NEAR(back.pixels[p][c], expected, 0.01f * expected + 0.002f) << "pixel " << p << " channel " << c;
    }
}

TEST(ImageWriters, PngExposureScales) {
  TempDir dir;
  write_png(dir / "a.png", Image(1, 1, Vec3(0.1f, 0.1f, 0.1f)), 1.0f);  // x 2
  write_png(dir / "b.png", Image(1, 1, Vec3(0.2f, 0.2f, 0.2f)), 0.0f);
  EXPECT_EQ(read_image(dir / "a.png").pixels[0], read_image(dir / "b.png").pixels[0]);
}

TEST(ImageWriters, WritingIntoAMissingFolderIsAnInputError) {
  TempDir dir;
  const fs::path target = dir / "no_such_folder" / "out.exr";
  EXPECT_MENTIONS(input_error_message([&] { write_exr(target, Image(2, 2)); }), target.string(), "folder");
}

// --------------------------------------------------------- atomic writer

std::vector<std::string> folder_listing(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(folder)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(AtomicWriter, ThrowingWriterLeavesThePreviousFileIntact) {
  TempDir dir;
  const fs::path target = dir / "result.txt";
  write_text(target, "the previous contents");
  fs::path seen_temp;
  EXPECT_THROW(write_atomically(target,
                                [&](const fs::path& temp) {
                                  seen_temp = temp;
                                  std::ofstream out(temp);
                                  out << "half a fi";
                                  out.close();
                                  throw std::runtime_error("disk full");
                                }),
               std::runtime_error);
  EXPECT_EQ(read_text(target), "the previous contents");
  // The temporary was beside the target, with the same extension, and is gone.
  EXPECT_EQ(seen_temp.parent_path(), dir.path());
  EXPECT_EQ(seen_temp.extension(), ".txt");
  EXPECT_NE(seen_temp, target);
  EXPECT_FALSE(fs::exists(seen_temp));
  EXPECT_EQ(folder_listing(dir.path()), std::vector<std::string>{"result.txt"});
}

TEST(AtomicWriter, ThrowingWriterWithNoPreviousFileLeavesNothing) {
  TempDir dir;
  const fs::path target = dir / "new.exr";
  EXPECT_THROW(write_atomically(target,
                                [&](const fs::path& temp) {
                                  write_text(temp, "x");
                                  throw InputError(target.string(), "", "boom");
                                }),
               InputError);
  EXPECT_FALSE(fs::exists(target));
  EXPECT_TRUE(folder_listing(dir.path()).empty());
}

TEST(AtomicWriter, SuccessReplacesTheFileAndLeavesNoTemporary) {
  TempDir dir;
  const fs::path target = dir / "result.txt";
  write_text(target, "old");
  write_atomically(target, [&](const fs::path& temp) { write_text(temp, "new contents"); });
  EXPECT_EQ(read_text(target), "new contents");
  EXPECT_EQ(folder_listing(dir.path()), std::vector<std::string>{"result.txt"});
  write_text_atomically(target, "text");
  EXPECT_EQ(read_text(target), "text");
  EXPECT_EQ(folder_listing(dir.path()), std::vector<std::string>{"result.txt"});
}

TEST(AtomicWriter, TargetThatIsAFolderIsAnInputError) {
  TempDir dir;
  fs::create_directory(dir / "sub");
  EXPECT_MENTIONS(input_error_message([&] { write_text_atomically(dir / "sub", "x"); }), (dir / "sub").string(),
                  "folder");
}

}  // namespace
}  // namespace relight
