// The OpenGL backend against the CPU one: the same rig's direct light through
// shadow maps and through shadow rays, on the reference scenes (the thesis
// showed real-time and ray-traced renders side by side; this measures them).
// And its two ways of shading against each other on the example room.
// Skipped where no OpenGL context can be opened headless, or where the
// reference scenes are absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <tuple>

#include "io/image_io.h"
#include "io/scene_io.h"
#include "realtime/shadow_maps.h"
#include "reference_scenes.h"
#include "render/direct_light.h"
#include "render/gbuffer.h"
#include "render/ray_scene.h"
#include "room_scene.h"

namespace fs = std::filesystem;
using namespace relight;

namespace {

// Where to write the images for a look (RELIGHT_TEST_IMAGES=folder), if anywhere.
void keep_image(const std::string& name, const Image& image) {
  if (const char* folder = std::getenv("RELIGHT_TEST_IMAGES")) {
    fs::create_directories(folder);
    write_png(fs::path(folder) / (name + ".png"), image);
  }
}

// albedo x the sum of the enabled lights' direct light, each rendered by
// render_one(light, image).
template <class Render>
Image direct_relit(const Image& albedo, const std::vector<Light>& lights, Render render_one) {
  Image sum(albedo.width, albedo.height), one;
  for (const Light& light : lights) {
    if (!light.enabled) continue;
    render_one(light, one);
    for (size_t i = 0; i < sum.size(); ++i) sum.pixels[i] += one.pixels[i];
  }
  for (size_t i = 0; i < sum.size(); ++i) sum.pixels[i] = sum.pixels[i].cwiseProduct(albedo.pixels[i]);
  return sum;
}

double relit_psnr(const Image& test, const Image& reference) {
  return psnr(tonemap_reinhard_srgb(test), tonemap_reinhard_srgb(reference));
}

// A reference scene, and whether the backend shades by compute shader (else
// by fragment shader).
class GlAgreesWithCpu : public testing::TestWithParam<std::tuple<std::string, bool>> {};

TEST_P(GlAgreesWithCpu, OnEveryRigOfTheScene) {
  const auto& [scene_name, compute] = GetParam();
  const fs::path folder = relight::test::reference_scenes_folder() / scene_name;
  if (!fs::exists(folder / "scene.json"))
    GTEST_SKIP() << "reference scene " << folder << " not found (set RELIGHT_SCENES to the scenes folder)";
  const Scene scene = load_scene(folder / "scene.json");
  const RayScene rays(scene.mesh);
  const GBuffer gbuffer(scene.camera, rays, 1, 1, scene.path.string());  // one sample, at the pixel centre
  const PixelSurfaces surfaces = PixelSurfaces::central_samples(gbuffer);
  // The true albedo stands in for an analysis: both backends' light is modulated by the same one.
  const Image albedo = read_image(folder / "albedo_gt.exr");

  std::string why;
  ShadowMapOptions options;
  options.shading = compute ? ShadowMapOptions::Shading::compute : ShadowMapOptions::Shading::fragment;
  const auto gl = GlRelighter::open(scene.mesh, surfaces, options, why);
  if (!gl) GTEST_SKIP() << "OpenGL unavailable (" << why << "): the CPU backend is used instead";
  if (gl->shades_by_compute() != compute)
    GTEST_SKIP() << gl->renderer() << " has no compute shaders (OpenGL 4.3): shading by fragment shader only";

  int rigs = 0;
  for (const auto& entry : fs::directory_iterator(folder / "rigs")) {
    const std::string name = entry.path().stem().string();
    const Rig rig = load_rig(entry.path());
    const Image on_gl =
        direct_relit(albedo, rig.lights, [&](const Light& light, Image& out) { gl->render(light, out); });
    // The CPU reference samples each light densely enough for its soft shadows to be smooth.
    DirectLightSettings dense;
    dense.light_samples = 256;
    const Image on_cpu = direct_relit(albedo, rig.lights, [&](const Light& light, Image& out) {
      render_direct_light(surfaces, rays, light, dense, out);
    });
    const std::string shader = compute ? "compute" : "fragment";
    keep_image(scene_name + "_" + name + "_gl_" + shader, on_gl);
    keep_image(scene_name + "_" + name + "_cpu", on_cpu);
    const double db = relit_psnr(on_gl, on_cpu);
    std::printf("[ figures  ] %s rig %s: OpenGL (%s, %s shader) vs CPU direct light PSNR %.2f dB\n", scene_name.c_str(),
                name.c_str(), gl->renderer().c_str(), shader.c_str(), db);
    EXPECT_GE(db, 35.0) << "rig " << name;
    ++rigs;
  }
  EXPECT_GT(rigs, 0);
}

// The two ways of shading, by compute and by fragment shader, draw the same
// light: every light type on the example room (no reference scene needed).
TEST(GlShading, ComputeAndFragmentShadersDrawTheSameLight) {
  const Scene scene = example::room_scene(160, 120);
  const RayScene rays(scene.mesh);
  const GBuffer gbuffer(scene.camera, rays, 1, 1, "room");
  const PixelSurfaces surfaces = PixelSurfaces::central_samples(gbuffer);
  std::string why;
  ShadowMapOptions options;
  options.shading = ShadowMapOptions::Shading::compute;
  const auto by_compute = GlRelighter::open(scene.mesh, surfaces, options, why);
  if (!by_compute) GTEST_SKIP() << "OpenGL unavailable (" << why << ")";
  if (!by_compute->shades_by_compute()) GTEST_SKIP() << by_compute->renderer() << " has no compute shaders";
  options.shading = ShadowMapOptions::Shading::fragment;
  const auto by_fragment = GlRelighter::open(scene.mesh, surfaces, options, why);
  ASSERT_TRUE(by_fragment) << why;
  EXPECT_FALSE(by_fragment->shades_by_compute());

  const Light lamp = scene.lights.front();  // a soft point (it has a radius)
  Light point = lamp, spot = lamp, area = lamp, sun = lamp;
  point.radius = 0.0f;
  spot.type = LightType::spot;
  spot.direction = (Vec3(0.0f, 0.3f, 0.3f) - spot.position).normalized();
  spot.spot_angle_deg = 40.0f;
  area.type = LightType::area;
  area.direction = Vec3(0.3f, 0.3f, -1.0f).normalized();
  area.up = Vec3(0, 1, 0);
  area.size = Vec2(0.4f, 0.3f);
  sun.type = LightType::directional;
  sun.direction = Vec3(0.4f, 0.5f, -0.8f).normalized();
  sun.irradiance = 5.0f;
  sun.angle_deg = 1.0f;
  for (const Light& light : {lamp, point, spot, area, sun}) {
    Image a, b;
    by_compute->render(light, a);
    by_fragment->render(light, b);
    ASSERT_EQ(a.size(), b.size());
    float peak = 0.0f, difference = 0.0f;
    for (size_t i = 0; i < a.size(); ++i) {
      peak = std::max(peak, a.pixels[i].maxCoeff());
      difference = std::max(difference, (a.pixels[i] - b.pixels[i]).cwiseAbs().maxCoeff());
    }
    EXPECT_GT(peak, 0.0f) << to_string(light.type) << ": lights nothing";
    EXPECT_LE(difference, 1e-4f * peak) << to_string(light.type);
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, GlAgreesWithCpu,
                         testing::Combine(testing::Values("outdoor", "bookcase"), testing::Bool()));

}  // namespace
