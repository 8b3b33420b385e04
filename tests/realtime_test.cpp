// The OpenGL backend against the CPU one: the same rig's direct light through
// shadow maps and through shadow rays, on the reference scenes (the thesis
// showed real-time and ray-traced renders side by side; this measures them).
// Skipped where no OpenGL context can be opened headless, or where the
// reference scenes are absent.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "io/image_io.h"
#include "io/scene_io.h"
#include "realtime/shadow_maps.h"
#include "reference_scenes.h"
#include "render/direct_light.h"

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

class GlAgreesWithCpu : public testing::TestWithParam<std::string> {};

TEST_P(GlAgreesWithCpu, OnEveryRigOfTheScene) {
  const fs::path folder = relight::test::reference_scenes_folder() / GetParam();
  if (!fs::exists(folder / "scene.json"))
    GTEST_SKIP() << "reference scene " << folder << " not found (set RELIGHT_SCENES to the scenes folder)";
  const Scene scene = load_scene(folder / "scene.json");
  const RayScene rays(scene.mesh);
  const GBuffer gbuffer(scene.camera, rays, 1, 1, scene.path.string());  // one sample, at the pixel centre
  const PixelSurfaces surfaces = PixelSurfaces::central_samples(gbuffer);
  // The true albedo stands in for an analysis: both backends' light is modulated by the same one.
  const Image albedo = read_image(folder / "albedo_gt.exr");

  std::string why;
  const auto gl = GlRelighter::open(scene.mesh, surfaces, ShadowMapOptions{}, why);
  if (!gl) GTEST_SKIP() << "OpenGL unavailable (" << why << "): the CPU backend is used instead";

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
    keep_image(GetParam() + "_" + name + "_gl", on_gl);
    keep_image(GetParam() + "_" + name + "_cpu", on_cpu);
    const double db = relit_psnr(on_gl, on_cpu);
    std::printf("[ figures  ] %s rig %s: OpenGL (%s) vs CPU direct light PSNR %.2f dB\n", GetParam().c_str(),
                name.c_str(), gl->renderer().c_str(), db);
    EXPECT_GE(db, 35.0) << "rig " << name;
    ++rigs;
  }
  EXPECT_GT(rigs, 0);
}

INSTANTIATE_TEST_SUITE_P(Scenes, GlAgreesWithCpu, testing::Values("outdoor", "bookcase"));

}  // namespace
