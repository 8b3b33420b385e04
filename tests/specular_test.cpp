// Glossy surfaces: the GGX lobe against its own definition, and the example
// room with a glossy floor and ball — its photo made with highlights by the
// program's own renderer — analysed (the highlights kept out of the albedo)
// and re-lit (the highlights moved with the light).
#include "render/specular.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "analysis/analysed_scene.h"
#include "io/image_io.h"
#include "io/scene_io.h"
#include "relight/render_rig.h"
#include "render/direct_light.h"
#include "render/render_illumination.h"
#include "room_scene.h"

using namespace relight;

namespace {

Vec3 direction_at(float theta_deg, float phi_deg) {
  const float t = radians(theta_deg), p = radians(phi_deg);
  return Vec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
}

// The lobe's directional albedo, the integral of brdf x cos over the
// hemisphere, by uniform directions (knowing nothing of how the lobe samples).
double albedo_by_uniform_directions(const GgxLobe& lobe, const Vec3& n, const Vec3& v, int count) {
  Rng rng(3, 1);
  double sum = 0.0;
  for (int i = 0; i < count; ++i) {
    Vec3 l = sample_uniform_sphere(rng.uniform2());
    if (l.z() < 0.0f) l.z() = -l.z();
    sum += lobe.brdf(n, l, v) * l.z() * 2.0 * kPi;
  }
  return sum / count;
}

TEST(GgxLobe, SamplingWeightsAgreeWithTheBrdf) {
  const Vec3 n(0, 0, 1);
  for (const float roughness : {0.2f, 0.5f})
    for (const float view_deg : {20.0f, 75.0f}) {
      const GgxLobe lobe(Gloss{roughness, 0.5f});
      const Vec3 v = direction_at(view_deg, 30.0f);
      Rng rng(5, 2);
      constexpr int kCount = 200000;
      double by_samples = 0.0, pdf_over_brdf = 0.0;
      int drawn = 0;
      for (int i = 0; i < kCount; ++i) {
        Vec3 l;
        float weight;
        if (!lobe.sample(n, v, rng.uniform2(), l, weight)) continue;
        by_samples += weight;
        ++drawn;
        // weight is brdf x cos / pdf: the lobe's own pdf and brdf agree with it.
        pdf_over_brdf += std::abs(lobe.brdf(n, l, v) * l.z() / lobe.pdf(n, l, v) - weight);
      }
      by_samples /= kCount;
      const double uniform = albedo_by_uniform_directions(lobe, n, v, 2000000);
      EXPECT_NEAR(by_samples, uniform, 0.02 * uniform) << "roughness " << roughness << ", view " << view_deg << " deg";
      EXPECT_LT(pdf_over_brdf / drawn, 1e-4);
      // A dielectric reflects a few percent (more at grazing view).
      EXPECT_GT(by_samples, 0.03);
      EXPECT_LT(by_samples, 0.25);
    }
}

TEST(GgxLobe, FresnelAndReciprocity) {
  EXPECT_NEAR(GgxLobe(Gloss{0.3f, 0.5f}).f0(), 0.04f, 1e-5f);  // Principled's specular 0.5: 4 %
  EXPECT_NEAR(GgxLobe(Gloss{0.3f, 1.0f}).f0(), 0.08f, 1e-5f);
  const GgxLobe lobe(Gloss{0.3f, 0.5f});
  const Vec3 n(0, 0, 1), a = direction_at(30, 10), b = direction_at(60, 200);
  EXPECT_NEAR(lobe.brdf(n, a, b), lobe.brdf(n, b, a), 1e-6f);
  EXPECT_EQ(lobe.brdf(n, Vec3(0, 0, -1), b), 0.0f);  // below the surface
  // The mirror direction is the lobe's peak.
  const Vec3 v = direction_at(40, 0), mirror = direction_at(40, 180);
  EXPECT_GT(lobe.brdf(n, mirror, v), 3.0f * lobe.brdf(n, direction_at(55, 180), v));
}

// The room with a glossy floor and ball, its photo made with their highlights.
struct GlossyRoom {
  Scene scene;
  Image albedo_gt;   // coverage-weighted
  Image evening;     // the photo under the evening rig, highlights and all
  Image highlights;  // the photo's own highlights, coverage-weighted
};

const std::map<std::string, Gloss> kRoomMaterials = {{"floor", {0.3f, 0.5f}}, {"ball", {0.2f, 0.5f}}};

// The photo under `lights`: the diffuse render plus the highlights, a
// reflected ray's surface reflecting its true albedo's light.
Image glossy_photo(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer, const std::vector<Light>& lights,
                   float environment_scale, Image* highlights_out = nullptr) {
  const example::RoomAlbedo albedo = example::room_albedo();
  const Lighting lighting = example::room_lighting(scene, lights, environment_scale);
  IntegratorOptions options;
  options.max_bounces = 6;
  options.gloss = &scene.gloss;
  const Integrator integrator(rays, lighting, &albedo, options);
  Image photo = synthesize_photo(gbuffer, scene.camera, integrator, albedo, 256, 99, Progress::silent());
  const ReflectedRadiance surfaces = [&](const SurfacePoint& hit, Rng& rng) -> Vec3 {
    return albedo.at(hit).cwiseProduct(integrator.illumination(hit, rng));
  };
  const SpecularReflection specular(integrator, scene.gloss, surfaces);
  Image highlights = render_specular(gbuffer, scene.camera, specular, 256, 98, Progress::silent());
  for (size_t i = 0; i < highlights.size(); ++i) highlights.pixels[i] *= gbuffer.coverage()[i];
  for (size_t i = 0; i < photo.size(); ++i) photo.pixels[i] += highlights.pixels[i];
  if (highlights_out) *highlights_out = std::move(highlights);
  return photo;
}

const GlossyRoom& glossy_room() {
  static const GlossyRoom room = [] {
    GlossyRoom r;
    r.scene = example::room_scene(160, 120);
    r.scene.path = "glossy room";
    set_materials(r.scene, kRoomMaterials);
    const RayScene rays(r.scene.mesh);
    const GBuffer gbuffer(r.scene.camera, rays, 16, 7, "room");  // another sampling than the analysis's
    r.scene.photo = glossy_photo(r.scene, rays, gbuffer, r.scene.lights, 1.0f, &r.highlights);
    const Rig evening = example::evening_rig();
    r.evening = glossy_photo(r.scene, rays, gbuffer, evening.lights, evening.environment_scale);
    r.albedo_gt = example::room_albedo_image(gbuffer);
    return r;
  }();
  return room;
}

std::unique_ptr<AnalysedScene> analysed(Scene scene) {
  AnalysisOptions options;
  options.strategy = Strategy::lights;
  return AnalysedScene::analyse(std::move(scene), options, Progress::silent());
}

TEST(GlossyRoom, AlbedoWithoutHighlightsAndHighlightsThatMove) {
  const GlossyRoom& r = glossy_room();
  // The lamp's highlight on the floor and the ball is most of what some pixels show.
  int bright = 0;
  for (size_t i = 0; i < r.highlights.size(); ++i)
    bright += luminance(r.highlights.pixels[i]) > 0.3f * luminance(r.scene.photo.pixels[i]);
  std::printf("[ figures  ] %d pixels of the glossy room's photo over 30 %% highlight\n", bright);
  EXPECT_GT(bright, 100);

  const auto glossy = analysed(Scene(r.scene));
  Scene matte_scene = r.scene;
  set_materials(matte_scene, {});
  const auto matte = analysed(std::move(matte_scene));

  const auto albedo_db = [&](const AnalysedScene& a) {
    return psnr(clip01(a.analysis().albedo.albedo_coverage), clip01(r.albedo_gt));
  };
  const double glossy_db = albedo_db(*glossy), matte_db = albedo_db(*matte);
  std::printf("[ figures  ] glossy room albedo PSNR: gloss known %.2f dB, taken as matte %.2f dB\n", glossy_db,
              matte_db);
  EXPECT_FALSE(glossy->analysis().specular.pixels.empty());
  EXPECT_TRUE(matte->analysis().specular.pixels.empty());
  EXPECT_GE(glossy_db, matte_db + 2.0);
  EXPECT_GE(glossy_db, 27.0);

  const Rig evening = example::evening_rig();
  const auto relit_db = [&](const AnalysedScene& a) {
    const Image relit = render_rig(a, evening, RenderOptions{}, Progress::silent());
    return psnr(tonemap_reinhard_srgb(relit), tonemap_reinhard_srgb(r.evening));
  };
  const double glossy_relit = relit_db(*glossy), matte_relit = relit_db(*matte);
  std::printf("[ figures  ] glossy room evening re-lit PSNR: gloss known %.2f dB, taken as matte %.2f dB\n",
              glossy_relit, matte_relit);
  EXPECT_GE(glossy_relit, matte_relit + 2.0);
  EXPECT_GE(glossy_relit, 30.0);
}

// The highlights a moving light makes (no ray of their own: from its direct
// light as the fast backend renders it) against its refined own highlights
// (the lobe's samples of it; the surfaces the gloss mirrors are not its
// own) at the pixels' central samples, in PSNR; and the share of the
// refined ones they carry (1: all).
struct MovingAgainstRefined {
  double db, share;
};
MovingAgainstRefined moving_against_refined(const Light& light) {
  Scene scene = example::room_scene(160, 120);
  set_materials(scene, kRoomMaterials);
  const RayScene rays(scene.mesh);
  const GBuffer gbuffer(scene.camera, rays, 1, 7, "room");  // one sample a pixel: the central one
  const PixelSurfaces surfaces = PixelSurfaces::central_samples(gbuffer);
  CpuDirectLight fast(surfaces, rays);
  Image direct, moving(gbuffer.width(), gbuffer.height());
  fast.render(light, direct);
  const MovingHighlights highlights(surfaces, scene.gloss, scene.camera.position());
  highlights.render(light, direct, moving);

  Lighting lighting;
  lighting.lights = {light};
  IntegratorOptions options;
  options.gloss = &scene.gloss;
  const Integrator integrator(rays, lighting, nullptr, options);
  const ReflectedRadiance unused = [](const SurfacePoint&, Rng&) -> Vec3 { return Vec3::Zero(); };
  const int paths = light.radius > 0.0f || light.type == LightType::area ? 1024 : 4;
  const Image refined =
      render_specular(gbuffer, scene.camera, SpecularReflection(integrator, scene.gloss, unused, SpecularParts::lights),
                      paths, 5, Progress::silent());
  double along = 0.0, norm = 0.0;
  for (size_t i = 0; i < refined.size(); ++i) {
    along += moving.pixels[i].cast<double>().dot(refined.pixels[i].cast<double>());
    norm += refined.pixels[i].cast<double>().squaredNorm();
  }
  return {psnr(moving, refined), along / norm};
}

// A hard lamp's are its refined own highlights but for the far tail taken
// off; a soft lamp's and a panel's, from their representative points, near
// them (from the lamp's centre a 30 cm lamp's were 35.8 dB, the panel's
// 29.5 dB).
TEST(MovingHighlights, NearTheRefinedOwnHighlightsOfHardAndSoftLights) {
  Light lamp = example::evening_rig().lights[0];
  Light panel = lamp;
  panel.type = LightType::area;
  panel.direction = Vec3(0, 0, -1);
  panel.up = Vec3(0, 1, 0);
  panel.size = Vec2(0.6f, 0.6f);
  const auto check = [](const char* what, const Light& light, double min_db) {
    const MovingAgainstRefined m = moving_against_refined(light);
    std::printf("[ figures  ] %s: moving highlights %.1f dB, %.3f of the refined ones\n", what, m.db, m.share);
    EXPECT_GT(m.db, min_db) << what;
    EXPECT_NEAR(m.share, 1.0, 0.35) << what;
  };
  lamp.radius = 0.0f;
  check("hard lamp", lamp, 55.0);
  lamp.radius = 0.3f;
  check("lamp of radius 0.3 m", lamp, 40.0);
  check("panel 0.6 m square", panel, 30.5);
}

// The glossy variants of the public studio and bookcase that Cycles made
// (tests/data/glossy), each against its matte twin: the albedo with the
// materials given within 1.5 dB of the twin's, and every rig re-lit at 34 dB
// or more.
class GlossyScene : public ::testing::TestWithParam<const char*> {};

std::filesystem::path glossy_data() { return std::filesystem::path(RELIGHT_SOURCE_DIR) / "tests" / "data" / "glossy"; }

// The analysis of a scene folder at the defaults, and its albedo's PSNR.
std::unique_ptr<AnalysedScene> analysed_folder(const std::filesystem::path& folder, double& albedo_db) {
  auto a = AnalysedScene::analyse(load_scene(folder / "scene.json"), AnalysisOptions{}, Progress::silent());
  const Image mask = read_image(folder / "mask.exr");
  std::vector<float> weight(mask.size());
  for (size_t i = 0; i < weight.size(); ++i) weight[i] = mask.pixels[i].x() > 0.99f;
  albedo_db = psnr(clip01(a->analysis().albedo.albedo_coverage), clip01(read_image(folder / "albedo_gt.exr")), &weight);
  return a;
}

TEST_P(GlossyScene, AlbedoNearTheMatteTwinsAndRigsRelit) {
  const std::string name = GetParam();
  double glossy_db = 0.0, matte_db = 0.0;
  const auto glossy = analysed_folder(glossy_data() / ("glossy_" + name), glossy_db);
  analysed_folder(glossy_data() / ("matte_" + name), matte_db);
  std::printf("[ figures  ] glossy %s albedo %.2f dB, its matte twin's %.2f dB\n", name.c_str(), glossy_db, matte_db);
  EXPECT_GE(glossy_db, matte_db - 1.5);
  for (const auto& rig : std::filesystem::directory_iterator(glossy_data() / ("glossy_" + name) / "rigs")) {
    const Image relit = render_rig(*glossy, load_rig(rig.path()), RenderOptions{}, Progress::silent());
    const Image truth =
        read_image(rig.path().parent_path().parent_path() / "relit" / rig.path().filename().replace_extension(".exr"));
    const double db = psnr(tonemap_reinhard_srgb(relit), tonemap_reinhard_srgb(truth));
    std::printf("[ figures  ] glossy %s rig %s re-lit %.2f dB\n", name.c_str(), rig.path().stem().c_str(), db);
    EXPECT_GE(db, 34.0) << rig.path();
  }
}

INSTANTIATE_TEST_SUITE_P(Cycles, GlossyScene, ::testing::Values("studio", "bookcase"));

}  // namespace
