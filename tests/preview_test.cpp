// The preview analysis's photo: reduced to at most kPreviewPixels with its
// light, shape and camera kept, and what is given in its pixels (a grey
// card's polygon) moved with it.
#include <gtest/gtest.h>

#include "analysis/analyze.h"
#include "room_scene.h"

using namespace relight;

namespace {

TEST(PreviewAnalysis, ReducesALargePhotoKeepingItsLightShapeAndCamera) {
  constexpr int kW = 1200, kH = 900;  // 1.08 Mpixel
  Scene scene = example::room_scene(kW, kH);
  scene.photo = Image(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) scene.photo.at(x, y) = Vec3((x + 0.5f) / kW, 0.5f, (y + 0.5f) / kH);
  AlbedoReference reference;
  reference.polygon = {Vec2(120, 90), Vec2(600, 90), Vec2(600, 450)};
  scene.reference = reference;
  reduce_for_preview(scene);

  const int w = scene.photo.width, h = scene.photo.height;
  EXPECT_LE(int64_t(w) * h, kPreviewPixels);
  EXPECT_GT(int64_t(w) * h, kPreviewPixels * 9 / 10);
  EXPECT_NEAR(double(w) / h, double(kW) / kH, 0.005);
  EXPECT_EQ(scene.camera.width(), w);
  EXPECT_EQ(scene.camera.height(), h);
  // Each reduced pixel holds the mean of the photo it covers: the ramps
  // run through it as they did.
  for (int x = 0; x < w; x += 37) EXPECT_NEAR(scene.photo.at(x, h / 2).x(), (x + 0.5f) / w, 0.5f / w);
  for (int y = 0; y < h; y += 29) EXPECT_NEAR(scene.photo.at(w / 2, y).z(), (y + 0.5f) / h, 0.5f / h);
  const float scale = float(w) / kW;
  EXPECT_NEAR(scene.reference->polygon[1].x(), 600 * scale, 0.01f);
  EXPECT_NEAR(scene.reference->polygon[2].y(), 450 * float(h) / kH, 0.01f);
}

TEST(PreviewAnalysis, LeavesASmallPhotoAsItIs) {
  Scene scene = example::room_scene(640, 480);
  scene.photo = Image(640, 480, Vec3::Constant(0.25f));
  reduce_for_preview(scene);
  EXPECT_EQ(scene.photo.width, 640);
  EXPECT_EQ(scene.camera.height(), 480);
}

}  // namespace
