// A rig's new environment (docs/formats.md, "A new environment in a rig"):
// it lights the geometry and shows where the camera sees past it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "analysis/analysed_scene.h"
#include "relight/render_rig.h"
#include "render/render_illumination.h"

using namespace relight;

namespace {

class ConstantAlbedo final : public SurfaceAlbedo {
 public:
  explicit ConstantAlbedo(float albedo) : albedo_(albedo) {}
  Vec3 at(const SurfacePoint&) const override { return Vec3::Constant(albedo_); }

 private:
  float albedo_;
};

// A 40 x 40 m floor of albedo `albedo` under a uniform sky of radiance
// `sky`, seen from 2 m above it: the lower part of the photo is floor, the
// upper part sky.
Scene floor_under_a_sky(float albedo, float sky) {
  Scene scene;
  scene.path = "floor";
  scene.mesh.positions = {Vec3(-20, -20, 0), Vec3(20, -20, 0), Vec3(20, 20, 0), Vec3(-20, 20, 0)};
  scene.mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  CameraSpec spec;
  spec.position = Vec3(0, -5, 2);
  spec.look_at = Vec3(0, 5, 0.5f);
  spec.up = Vec3(0, 0, 1);
  spec.vfov_deg = 40.0f;
  scene.camera = Camera(spec, 64, 48);
  scene.background = Vec3::Constant(sky);
  const RayScene rays(scene.mesh);
  const GBuffer gbuffer(scene.camera, rays, 9, 3, "floor");
  Lighting lighting;
  lighting.environment = Environment::constant(scene.background);
  const ConstantAlbedo truth(albedo);
  const Integrator integrator(rays, lighting, &truth);
  scene.photo = synthesize_photo(gbuffer, scene.camera, integrator, truth, 64, 5, Progress::silent());
  return scene;
}

// Irradiance on an unoccluded plane under a uniform sky of radiance c is
// pi c, so the floor reflects a c; past the floor the camera sees c itself.
TEST(NewSky, AConstantSkyLightsAnOpenFloorAndShowsBehindIt) {
  constexpr float kAlbedo = 0.5f, kOldSky = 0.4f, kNewSky = 0.8f;
  AnalysisOptions options;
  options.strategy = Strategy::lights;
  const auto analysed = AnalysedScene::analyse(floor_under_a_sky(kAlbedo, kOldSky), options, Progress::silent());
  Rig rig;
  rig.environment = RigEnvironment{Vec3(kNewSky, 0.5f * kNewSky, 0.25f * kNewSky), nullptr};
  rig.environment_scale = 1.5f;
  const Image relit = render_rig(*analysed, rig, RenderOptions{}, Progress::silent());
  const Vec3 sky = rig.environment_scale * rig.environment->color;
  const std::vector<float>& coverage = analysed->analysis().coverage;
  int floor = 0, background = 0;
  Vec3 floor_sum = Vec3::Zero();
  double silhouette_sum = 0, silhouette_expected = 0;
  for (size_t i = 0; i < relit.size(); ++i) {
    if (coverage[i] == 0.0f) {
      // The mean of the pixel's samples: c up to rounding.
      EXPECT_LT((relit.pixels[i] - sky).cwiseAbs().maxCoeff(), 1e-6f) << "background pixel " << i;
      ++background;
    } else if (coverage[i] == 1.0f) {
      // The noise of the photo (64 paths) and of the new illumination.
      const Vec3 expected = kAlbedo * sky;
      EXPECT_LT((relit.pixels[i] - expected).cwiseAbs().maxCoeff(), 0.1f * expected.maxCoeff())
          << "floor pixel " << i << ": " << relit.pixels[i].transpose();
      floor_sum += relit.pixels[i];
      ++floor;
    } else {  // the horizon: c a sky + (1 - c) sky, the albedo of a sliver of floor less sure
      silhouette_sum += relit.pixels[i].x();
      silhouette_expected += (coverage[i] * kAlbedo + 1.0f - coverage[i]) * sky.x();
    }
  }
  std::printf("[ figures  ] horizon pixels: %.3f of the expected sum\n", silhouette_sum / silhouette_expected);
  EXPECT_NEAR(silhouette_sum / silhouette_expected, 1.0, 0.05);
  ASSERT_GT(floor, 1000);
  const Vec3 floor_mean = floor_sum / float(floor);
  std::printf("[ figures  ] floor under a constant sky: mean %.4f, expected a c = %.4f\n", floor_mean.x(),
              kAlbedo * sky.x());
  EXPECT_LT((floor_mean - kAlbedo * sky).cwiseAbs().maxCoeff(), 0.01f * kAlbedo * sky.maxCoeff());
  EXPECT_GT(background, 300);
}

// An image sky is looked up in the direction of each background sample: a
// sky bright in a band right of its forward shows on the right of the photo
// (which spans 26 degrees either side), and turned 40 degrees left about up
// (its forward turned), on the left.
TEST(NewSky, AnImageSkyTurnsWithItsForward) {
  AnalysisOptions options;
  options.strategy = Strategy::lights;
  const auto analysed = AnalysedScene::analyse(floor_under_a_sky(0.5f, 0.4f), options, Progress::silent());
  // Equirect, forward +y (the camera's view): the centre column looks along
  // forward, columns to the right of it look towards right = forward x up = +x.
  auto sky = std::make_shared<Probe>();
  sky->image = Image(64, 32, Vec3::Constant(0.1f));
  for (int y = 0; y < 32; ++y)
    for (int x = 34; x < 37; ++x) sky->image.at(x, y) = Vec3::Constant(10.0f);  // 11-28 deg right of forward
  sky->forward = Vec3(0, 1, 0);
  sky->up = Vec3(0, 0, 1);
  const auto mean_sky_brightness = [&](const Rig& rig, int x0, int x1) {
    const Image relit = render_rig(*analysed, rig, RenderOptions{16}, Progress::silent());
    double sum = 0;
    int n = 0;
    for (int y = 0; y < 8; ++y)  // top rows: sky only
      for (int x = x0; x < x1; ++x, ++n) sum += relit.at(x, y).x();
    return sum / n;
  };
  Rig rig;
  rig.environment = RigEnvironment{Vec3::Zero(), sky};
  const double right = mean_sky_brightness(rig, 48, 64), left = mean_sky_brightness(rig, 0, 16);
  EXPECT_GT(right, 2.0);
  EXPECT_LT(left, 0.2);
  auto turned = std::make_shared<Probe>(*sky);
  const float angle = 40.0f * kPi / 180.0f;
  turned->forward = Vec3(-std::sin(angle), std::cos(angle), 0);
  rig.environment = RigEnvironment{Vec3::Zero(), turned};
  EXPECT_LT(mean_sky_brightness(rig, 48, 64), 0.2);
  EXPECT_GT(mean_sky_brightness(rig, 0, 16), 2.0);
  // The rig convenience says the same: 40 degrees counter-clockwise seen
  // from above, the image shared, up kept.
  const RigEnvironment by_turning = turned_environment(RigEnvironment{Vec3::Zero(), sky}, 40.0f);
  EXPECT_LT((by_turning.image->forward - turned->forward).norm(), 1e-6f);
  EXPECT_EQ(by_turning.image->up, sky->up);
  EXPECT_NE(by_turning.image, sky);
  EXPECT_EQ(turned_environment(RigEnvironment{Vec3(1, 2, 3), nullptr}, 40.0f).color, Vec3(1, 2, 3));
}

}  // namespace
