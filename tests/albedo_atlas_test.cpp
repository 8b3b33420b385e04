// A shot's albedo fused into one per surface (analysis/albedo_atlas.h): on
// the example room seen by a camera moving sideways, the fused albedo is
// nearer the truth than each frame's own and, at the surface points two
// frames share, changes from frame to frame far less (it does not flicker).
#include "analysis/albedo_atlas.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>

#include "analysis/analysed_scene.h"
#include "io/image_io.h"
#include "room_scene.h"

using namespace relight;

namespace {

constexpr int kWidth = 160, kHeight = 120;

// Where to write the images for a look (RELIGHT_TEST_IMAGES=folder), if anywhere.
void keep_image(const std::string& name, const Image& image) {
  if (const char* folder = std::getenv("RELIGHT_TEST_IMAGES")) {
    std::filesystem::create_directories(folder);
    write_png(std::filesystem::path(folder) / (name + ".png"), image);
  }
}

// The room seen from its camera moved `step` x 12 cm to the right (and the
// point it looks at with it): a dolly.
Scene room_frame(int step) {
  Scene scene = example::room_scene(kWidth, kHeight);
  CameraSpec spec = scene.camera.spec();
  const Vec3 right = (spec.look_at - spec.position).cross(spec.up).normalized();
  spec.position += 0.12f * float(step) * right;
  spec.look_at += 0.12f * float(step) * right;
  scene.camera = Camera(spec, kWidth, kHeight);
  scene.path = "room frame " + std::to_string(step);
  return scene;
}

PixelSurfaces view_of(const Scene& scene, const RayScene& rays) {
  return PixelSurfaces::central_samples(GBuffer(scene.camera, rays, 1, 1, scene.path.string()));
}

// Mean |a - truth| / mean truth over the pixels that see a surface.
double relative_error(const Image& a, const Image& truth, const PixelSurfaces& view) {
  double error = 0.0, level = 0.0;
  for (size_t i = 0; i < view.hit.size(); ++i) {
    if (!view.hit[i]) continue;
    error += (a.pixels[i] - truth.pixels[i]).cwiseAbs().mean();
    level += truth.pixels[i].mean();
  }
  return error / level;
}

Image true_albedo(const PixelSurfaces& view) {
  const example::RoomAlbedo albedo = example::room_albedo();
  Image out(view.width, view.height);
  for (size_t i = 0; i < view.hit.size(); ++i)
    if (view.hit[i]) out.pixels[i] = albedo.at(view.surface[i]);
  return out;
}

struct Frame {
  Scene scene;
  PixelSurfaces view;
  Image albedo;  // the frame's own
  std::vector<float> weight;
};

// The fused albedo of each frame, the atlas sized for every frame first.
std::vector<Image> fused(const TriangleMesh& mesh, const std::vector<Frame>& frames) {
  AlbedoAtlas atlas(mesh);
  for (const Frame& f : frames) atlas.size_for(f.view, f.scene.camera);
  for (const Frame& f : frames) atlas.add(f.view, f.albedo, f.weight);
  std::vector<Image> out;
  for (const Frame& f : frames) out.push_back(atlas.albedo_for(f.view, f.albedo));
  return out;
}

TEST(AlbedoAtlas, AveragesEachSurfaceOverTheFramesThatSeeIt) {
  const Scene first = room_frame(0);
  const RayScene rays(first.mesh);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> noise(-0.2f, 0.2f);
  std::vector<Frame> frames;
  for (int step = 0; step < 4; ++step) {
    Frame f{room_frame(step), {}, {}, {}};
    f.view = view_of(f.scene, rays);
    f.albedo = true_albedo(f.view);  // the truth, each pixel off by up to 20 %, differently in each frame
    for (Vec3& a : f.albedo.pixels) a *= 1.0f + noise(random);
    f.weight.assign(f.albedo.size(), 1.0f);
    frames.push_back(std::move(f));
  }
  const std::vector<Image> fused_albedo = fused(first.mesh, frames);
  for (size_t t = 0; t < frames.size(); ++t) {
    const Image truth = true_albedo(frames[t].view);
    const double own = relative_error(frames[t].albedo, truth, frames[t].view);
    const double atlas = relative_error(fused_albedo[t], truth, frames[t].view);
    std::printf("[ figures  ] frame %zu: albedo off the truth by %.3f (its own), %.3f (fused)\n", t, own, atlas);
    EXPECT_NEAR(own, 0.1, 0.01);  // uniform noise of +-20 %: 10 % on average
    EXPECT_LT(atlas, 0.75 * own);
  }
  for (size_t t = 0; t + 1 < frames.size(); ++t) {
    const auto pairs = shared_points(frames[t].view, frames[t].scene.camera, frames[t + 1].view);
    ASSERT_GT(pairs.size(), size_t(kWidth * kHeight / 2)) << "the frames share most of the view";
    const double own = change_at_shared_points(frames[t].albedo, frames[t + 1].albedo, pairs);
    const double atlas = change_at_shared_points(fused_albedo[t], fused_albedo[t + 1], pairs);
    std::printf("[ figures  ] frames %zu-%zu: albedo change at shared points %.3f (own), %.3f (fused)\n", t, t + 1, own,
                atlas);
    EXPECT_LT(atlas, 0.3 * own);
  }
}

// The same from the frames' photos, analysed each by itself: the photos'
// own noise is in each frame's albedo and not in the fused one.
TEST(AlbedoAtlas, ATrackedShotsAlbedoDoesNotFlicker) {
  const Scene first = room_frame(0);
  const RayScene rays(first.mesh);
  std::vector<Frame> frames;
  std::vector<Image> photos;
  for (int step = 0; step < 4; ++step) {
    Scene scene = room_frame(step);
    scene.photo = example::room_photo(scene, scene.camera, rays, 8, 3 + uint64_t(step));
    photos.push_back(scene.photo);
    AnalysisOptions options;
    options.strategy = Strategy::lights;  // the room has no probe: its lights as given
    options.paths_per_pixel = 16;
    const auto analysed = AnalysedScene::analyse(std::move(scene), options, Progress::silent());
    Frame f{analysed->scene(), {}, analysed->analysis().albedo.albedo, albedo_weights(analysed->analysis())};
    f.view = view_of(f.scene, rays);
    frames.push_back(std::move(f));
  }
  const std::vector<Image> fused_albedo = fused(first.mesh, frames);
  for (size_t t = 0; t < frames.size(); ++t) {
    keep_image("shot_frame" + std::to_string(t) + "_albedo_own", frames[t].albedo);
    keep_image("shot_frame" + std::to_string(t) + "_albedo_fused", fused_albedo[t]);
  }
  double own_error = 0.0, fused_error = 0.0;
  for (size_t t = 0; t < frames.size(); ++t) {
    const Image truth = true_albedo(frames[t].view);
    own_error += relative_error(frames[t].albedo, truth, frames[t].view) / double(frames.size());
    fused_error += relative_error(fused_albedo[t], truth, frames[t].view) / double(frames.size());
  }
  std::printf(
      "[ figures  ] tracked room shot, 4 frames: albedo off the truth by %.4f (each frame's own), %.4f (fused)\n",
      own_error, fused_error);
  EXPECT_LT(fused_error, own_error);
  for (size_t t = 0; t + 1 < frames.size(); ++t) {
    const auto pairs = shared_points(frames[t].view, frames[t].scene.camera, frames[t + 1].view);
    const double photo = change_at_shared_points(photos[t], photos[t + 1], pairs);
    const double own = change_at_shared_points(frames[t].albedo, frames[t + 1].albedo, pairs);
    const double atlas = change_at_shared_points(fused_albedo[t], fused_albedo[t + 1], pairs);
    std::printf("[ figures  ] frames %zu-%zu, change at shared points: photo %.4f, albedo %.4f (own), %.4f (fused)\n",
                t, t + 1, photo, own, atlas);
    EXPECT_LT(atlas, 0.5 * photo) << "the fused albedo changes less than the photos' own noise";
    EXPECT_LT(atlas, 0.5 * own);
  }
}

}  // namespace
