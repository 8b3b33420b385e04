// fSpy import: project files and exported JSON made here from known cameras
// must give a relight camera that images every point where fSpy's own camera
// model does (fSpy's image-plane frame, principal point off centre).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/sampling.h"

#include "io/fspy.h"
#include "io/scene_io.h"
#include "scene_folder.h"

namespace relight::test {
namespace {

using namespace std::string_literals;
constexpr double kPiD = std::numbers::pi;

// A camera as fSpy describes it: a camera-to-world pose (looking along -Z,
// +Y up), a relative focal length and a principal point in image-plane
// coordinates (origin at the centre, y up, the longer side spanning [-1, 1]).
struct FspyTruth {
  Eigen::Vector3d position{3.0, -4.0, 1.6};
  Eigen::Vector3d target{0.2, 0.5, 0.7};
  double focal = 1.3;  // fSpy's relativeFocalLength
  Eigen::Vector2d principal{0.12, -0.07};
  int width = 800, height = 600;

  Eigen::Matrix3d rotation() const {  // columns: the camera's right, up, back in world coordinates
    const Eigen::Vector3d back = (position - target).normalized();
    const Eigen::Vector3d right = Eigen::Vector3d(0, 0, 1).cross(back).normalized();
    Eigen::Matrix3d r;
    r << right, back.cross(right), back;
    return r;
  }
  double aspect() const { return double(width) / height; }
  // fSpy's horizontal field of view (solver.ts, computeFieldOfView).
  double horizontal_fov() const { return 2.0 * std::atan((aspect() < 1.0 ? aspect() : 1.0) / focal); }

  json parameters() const {
    const Eigen::Matrix3d r = rotation();
    json rows = json::array();
    for (int i = 0; i < 3; ++i) rows.push_back({r(i, 0), r(i, 1), r(i, 2), position[i]});
    rows.push_back({0, 0, 0, 1});
    return {{"principalPoint", {{"x", principal.x()}, {"y", principal.y()}}},
            {"cameraTransform", {{"rows", rows}}},
            {"horizontalFieldOfView", horizontal_fov()},
            {"relativeFocalLength", focal},
            {"imageWidth", width},
            {"imageHeight", height}};
  }

  // Where fSpy images a world point, as fractions of the width and height from the top left.
  Eigen::Vector2d relative_image_position(const Eigen::Vector3d& world) const {
    const Eigen::Vector3d c = rotation().transpose() * (world - position);
    const Eigen::Vector2d plane = principal + focal * Eigen::Vector2d(c.x(), c.y()) / -c.z();
    // coordinates-util.ts, imagePlaneToRelative
    if (aspect() <= 1.0) return {0.5 * (plane.x() / aspect() + 1.0), 0.5 * (1.0 - plane.y())};
    return {0.5 * (plane.x() + 1.0), 0.5 * (1.0 - plane.y() * aspect())};
  }
};

std::string project_file(const json& state, const std::string& image, uint32_t version = 1) {
  const std::string text = state.dump();
  std::string bytes = "fspy";
  for (uint32_t v : {version, uint32_t(text.size()), uint32_t(image.size())})
    for (int i = 0; i < 4; ++i) bytes += char((v >> (8 * i)) & 0xff);
  return bytes + text + image;
}

json project_state(const FspyTruth& truth) {
  return {{"cameraParameters", truth.parameters()}, {"calibrationSettingsBase", {{"referenceDistanceUnit", "Meters"}}}};
}

// Checks that `camera` (of any pixel size with fSpy's aspect ratio) images
// points spread over the view where fSpy does.
void expect_images_as_fspy(const Camera& camera, const FspyTruth& truth) {
  Rng rng(5, 0);
  int checked = 0;
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d p = truth.target + Eigen::Vector3d(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5) * 3.0;
    const Eigen::Vector2d expected = truth.relative_image_position(p);
    const auto pixel = camera.project(p.cast<float>());
    ASSERT_TRUE(pixel.has_value());
    const Eigen::Vector2d got(pixel->x() / camera.width(), pixel->y() / camera.height());
    ASSERT_LT((got - expected).norm(), 1e-5) << "point " << p.transpose();
    ++checked;
  }
  EXPECT_EQ(checked, 500);
}

TEST(Fspy, ProjectFileCameraImagesPointsAsFspyDoes) {
  const FspyTruth truth;
  SceneFolder folder("fspy_project");
  write_text(folder / "match.fspy", project_file(project_state(truth), "\x89PNG fake image bytes"s));
  const FspyCamera fspy = read_fspy_camera(folder / "match.fspy");
  EXPECT_EQ(fspy.image_width, 800);
  EXPECT_EQ(fspy.image_height, 600);
  // Wide image: the principal point's x spans the width, its y 1/aspect of the height.
  EXPECT_NEAR(fspy.camera.principal_point.x(), 0.5 + 0.12 / 2, 1e-6);
  EXPECT_NEAR(fspy.camera.principal_point.y(), 0.5 + 0.07 * 4.0 / 3.0 / 2, 1e-6);
  EXPECT_NEAR(fspy.camera.vfov_deg, 2.0 * std::atan(0.75 / 1.3) * 180.0 / kPiD, 1e-4);
  EXPECT_LT((fspy.camera.position.cast<double>() - truth.position).norm(), 1e-6);
  expect_images_as_fspy(Camera(fspy.camera, 800, 600), truth);
  expect_images_as_fspy(Camera(fspy.camera, 80, 60), truth);  // a smaller photo of the same shot
}

TEST(Fspy, ExportedJsonOfAPortraitPhoto) {
  FspyTruth truth;
  truth.width = 600;
  truth.height = 900;
  truth.principal = Eigen::Vector2d(-0.2, 0.15);
  truth.focal = 2.1;
  SceneFolder folder("fspy_portrait");
  write_text(folder / "camera.json", truth.parameters().dump(2));
  const FspyCamera fspy = read_fspy_camera(folder / "camera.json");
  // Tall image: the principal point's y spans the height, its x aspect of the width.
  EXPECT_NEAR(fspy.camera.principal_point.x(), 0.5 - 0.2 / (2.0 * 600.0 / 900.0), 1e-6);
  EXPECT_NEAR(fspy.camera.principal_point.y(), 0.5 - 0.15 / 2, 1e-6);
  expect_images_as_fspy(Camera(fspy.camera, 600, 900), truth);
}

TEST(Fspy, CommandReplacesTheCameraOfASceneAndKeepsTheRest) {
  const FspyTruth truth;  // 800 x 600, the aspect ratio of SceneFolder's 8 x 6 photo
  SceneFolder folder("fspy_scene");
  folder.write_json();
  const json before = json::parse(read_text(folder / "scene.json"));
  write_text(folder / "match.fspy", project_file(project_state(truth), "image"));
  const CliResult r = run_cli({"camera-from-fspy", (folder / "match.fspy").string(), "--scene", (folder / "scene.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  json after = json::parse(read_text(folder / "scene.json"));
  EXPECT_EQ(after["camera"]["principal_point"].size(), 2u);
  after.erase("camera");
  json rest = before;
  rest.erase("camera");
  EXPECT_EQ(after, rest);
  const Scene scene = load_scene(folder / "scene.json");
  expect_images_as_fspy(scene.camera, truth);
}

TEST(Fspy, CommandWritesTheCameraBlock) {
  const FspyTruth truth;
  SceneFolder folder("fspy_out");
  write_text(folder / "camera_export.json", truth.parameters().dump());
  ASSERT_EQ(run_cli({"camera-from-fspy", (folder / "camera_export.json").string(), "-o", (folder / "camera.json").string()}).status, 0);
  const json camera = json::parse(read_text(folder / "camera.json"));
  folder.scene["camera"] = camera;
  folder.write_json();
  expect_images_as_fspy(load_scene(folder / "scene.json").camera, truth);
}

// The camera block records the aspect ratio of fSpy's image: a photo cropped
// since (here to 16:9, 8 x 4.5 -> 16 x 9) is refused, naming the photo.
TEST(Fspy, APhotoCroppedAfterTheMatchIsRefused) {
  const FspyTruth truth;  // 800 x 600
  SceneFolder folder("fspy_cropped");
  write_text(folder / "camera_export.json", truth.parameters().dump());
  ASSERT_EQ(run_cli({"camera-from-fspy", (folder / "camera_export.json").string(), "-o", (folder / "camera.json").string()}).status, 0);
  const json camera = json::parse(read_text(folder / "camera.json"));
  EXPECT_NEAR(camera["aspect"].get<double>(), 4.0 / 3.0, 1e-6);
  folder.scene["camera"] = camera;
  folder.write_json();
  write_exr(folder / "photo.exr", Image(16, 9, Vec3::Constant(0.3f)));
  const CliResult r = run_cli({"analyze", (folder / "scene.json").string(), "-o", (folder / "analysis").string()});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("photo.exr"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("aspect ratio is 1.7778 (16x9)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("1.3333"), std::string::npos) << r.err;
}

TEST(Fspy, BadFilesAreOneLineErrorsNamingTheFile) {
  const FspyTruth truth;
  SceneFolder folder("fspy_bad");
  folder.write_json();
  const std::string scene_before = read_text(folder / "scene.json");
  json no_solution = project_state(truth);
  no_solution["cameraParameters"] = nullptr;
  const std::string good = project_file(project_state(truth), "image");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {project_file(project_state(truth), "image", 2), "version 2 is not supported"},
      {good.substr(0, good.size() - 3), "truncated fSpy project"},
      {good.substr(0, 10), "shorter than its 16-byte header"},
      {project_file(no_solution, "image"), "no camera solution"},
      {R"({"format": "relight-scene/1"})", "neither an fSpy project nor"},
      {"fspy\x01\0\0\0\x05\0\0\0\0\0\0\0{oops"s, "malformed JSON"},
  };
  for (const auto& [bytes, message] : cases) {
    write_text(folder / "bad.fspy", bytes);
    const CliResult r = run_cli({"camera-from-fspy", (folder / "bad.fspy").string(), "--scene", (folder / "scene.json").string()});
    EXPECT_EQ(r.status, 2) << message;
    EXPECT_NE(r.err.find("bad.fspy"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_EQ(read_text(folder / "scene.json"), scene_before) << message;
  }
}

}  // namespace
}  // namespace relight::test
