// The round trip that always runs: render the example room with a known
// albedo by the program's own path tracer, analyse the photo, and compare the
// recovered albedo and a re-lit image with the truth.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstdio>

#include "analysis/albedo.h"
#include "analysis/photo_blur.h"
#include "relight/render_rig.h"
#include "render/render_illumination.h"
#include "room_scene.h"

using namespace relight;

namespace {

struct RoomTruth {
  Scene scene;
  Image albedo_gt;  // coverage-weighted, like albedo_gt.exr
  Image evening;    // the photo under the evening rig
};

Image photo_of(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer, const SurfaceAlbedo& albedo,
               const std::vector<Light>& lights, float environment_scale) {
  const Lighting lighting = example::room_lighting(scene, lights, environment_scale);
  IntegratorOptions options;
  options.max_bounces = 6;
  const Integrator integrator(rays, lighting, &albedo, options);
  return synthesize_photo(gbuffer, scene.camera, integrator, albedo, 256, 99, Progress::silent());
}

const RoomTruth& room_truth() {
  static const RoomTruth truth = [] {
    RoomTruth t;
    t.scene = example::room_scene(160, 120);
    t.scene.path = "room";
    const example::RoomAlbedo albedo = example::room_albedo();
    const RayScene rays(t.scene.mesh);
    const GBuffer gbuffer(t.scene.camera, rays, 16, 7, "room");  // another sampling than the analysis's
    t.scene.photo = photo_of(t.scene, rays, gbuffer, albedo, t.scene.lights, 1.0f);
    const Rig evening = example::evening_rig();
    t.evening = photo_of(t.scene, rays, gbuffer, albedo, evening.lights, evening.environment_scale);
    t.albedo_gt = example::room_albedo_image(gbuffer);
    return t;
  }();
  return truth;
}

Analysis analyse_room(const RayScene& rays, const GBuffer& gbuffer, bool interreflection) {
  AnalysisOptions options;
  options.strategy = Strategy::lights;
  options.interreflection = interreflection;
  return analyze(room_truth().scene, rays, gbuffer, options, Progress::silent());
}

// A pixel whose albedo came out brighter than a surface can be is filled in
// the albedo, but re-lit as divided (photo / the model's light), times its
// coverage: the unchanged rig gives the photo back there.
TEST(PhotoLayers, ReLightThePixelsTooBrightAsDivided) {
  Scene scene;
  scene.photo = Image(4, 3);
  Analysis analysis;
  analysis.albedo.albedo_coverage = Image(4, 3, Vec3::Constant(0.5f));
  analysis.illumination.background = Image(4, 3);
  analysis.coverage.assign(12, 1.0f);
  analysis.coverage[5] = 0.5f;
  analysis.albedo.as_divided = {{5, Vec3(4.0f, 3.0f, 2.0f)}};
  const RelitLayers layers = photo_layers(scene, analysis);
  EXPECT_EQ(layers.albedo_coverage.pixels[5], Vec3(2.0f, 1.5f, 1.0f));
  EXPECT_EQ(layers.albedo_coverage.pixels[4], Vec3::Constant(0.5f));
}

TEST(RoundTrip, RecoversTheKnownAlbedoAndRelights) {
  const RoomTruth& t = room_truth();
  AnalysisOptions options;
  options.strategy = Strategy::lights;
  const std::unique_ptr<AnalysedScene> analysed = AnalysedScene::analyse(Scene(t.scene), options, Progress::silent());
  const Analysis& analysis = analysed->analysis();
  const double albedo_db = psnr(clip01(analysis.albedo.albedo_coverage), clip01(t.albedo_gt));
  std::printf("[ figures  ] room albedo PSNR %.2f dB\n", albedo_db);
  EXPECT_GE(albedo_db, 28.0);

  const Image relit = render_rig(*analysed, example::evening_rig(), RenderOptions{}, Progress::silent());
  const double relit_db = psnr(tonemap_reinhard_srgb(relit), tonemap_reinhard_srgb(t.evening));
  std::printf("[ figures  ] room evening re-lit PSNR %.2f dB\n", relit_db);
  EXPECT_GE(relit_db, 32.0);
}

TEST(RoundTrip, InterreflectionBeatsWhiteDiffuse) {
  const RoomTruth& t = room_truth();
  const RayScene rays(t.scene.mesh);
  const GBuffer gbuffer = scene_gbuffer(t.scene, rays, AnalysisOptions{});
  const double white = psnr(clip01(analyse_room(rays, gbuffer, false).albedo.albedo_coverage), clip01(t.albedo_gt));
  const double iterated = psnr(clip01(analyse_room(rays, gbuffer, true).albedo.albedo_coverage), clip01(t.albedo_gt));
  std::printf("[ figures  ] room albedo PSNR white %.2f dB, with interreflection %.2f dB\n", white, iterated);
  EXPECT_GT(iterated, white + 1.0);
}

// A photo softer than the render (a Gaussian of 1 px, as a real lens and
// sensor give) is found so, and the illumination blurred alike divides it
// without the bright and dark lines beside the shadows' edges and the
// silhouettes; the blur undone then brings the albedo nearer the sharp
// truth. The photo as rendered is found as sharp as the render.
// (gaussian_blur of no width is the image itself.)
TEST(PhotoBlur, ASofterPhotoIsFoundAndDividedByIlluminationAsSoft) {
  const RoomTruth& t = room_truth();
  const RayScene rays(t.scene.mesh);
  const GBuffer gbuffer = scene_gbuffer(t.scene, rays, AnalysisOptions{});
  const Analysis sharp = analyse_room(rays, gbuffer, true);
  EXPECT_EQ(sharp.photo_blur_px, 0.0f);
  EXPECT_EQ(gaussian_blur(t.scene.photo, 0.0f).pixels, t.scene.photo.pixels);

  const Image soft_photo = gaussian_blur(t.scene.photo, 1.0f), soft_truth = gaussian_blur(t.albedo_gt, 1.0f);
  const PhotoBlur found = measure_photo_blur(soft_photo, sharp.illumination, gbuffer);
  AlbedoImages soft =
      recover_albedo(soft_photo, {}, blur_illumination(sharp.illumination, gbuffer, found.sigma_px), gbuffer);
  const double divided_sharp =
      psnr(clip01(recover_albedo(soft_photo, {}, sharp.illumination, gbuffer).albedo_coverage), clip01(soft_truth));
  const double divided_soft = psnr(clip01(soft.albedo_coverage), clip01(soft_truth));
  // Then the blur undone in the albedo (sharpen_albedo), against the truth.
  const double soft_db = psnr(clip01(soft.albedo_coverage), clip01(t.albedo_gt));
  sharpen_albedo(soft, gbuffer, found.sigma_px);
  const double sharpened_db = psnr(clip01(soft.albedo_coverage), clip01(t.albedo_gt));
  std::printf(
      "[ figures  ] photo blurred 1 px: found %.2f px (roughness %.3f -> %.3f over %zu pixels); albedo against "
      "the blurred truth %.2f dB divided by the sharp illumination, %.2f dB by the blurred; against the truth "
      "%.2f dB, sharpened %.2f dB\n",
      found.sigma_px, found.roughness_sharp, found.roughness_blurred, found.edge_pixels, divided_sharp, divided_soft,
      soft_db, sharpened_db);
  EXPECT_GE(found.sigma_px, 0.5f);
  EXPECT_LE(found.sigma_px, 1.5f);
  // The room's soft lights leave few sharp edges at 160 x 120 (the public
  // scenes gain 1-4 dB, docs/benchmarks.md "A photo softer than the render").
  EXPECT_GT(divided_soft, divided_sharp);
  EXPECT_GT(sharpened_db, soft_db + 0.3);
}

TEST(RoundTrip, SameSeedGivesTheSameImageWhateverTheThreads) {
  const RoomTruth& t = room_truth();
  const RayScene rays(t.scene.mesh);
  AnalysisOptions options;
  options.paths_per_pixel = 16;
  const GBuffer gbuffer = scene_gbuffer(t.scene, rays, options);
  const Lighting lighting = strategy_lighting(t.scene, rays, Strategy::lights);
  const Integrator integrator(rays, lighting, nullptr);
  const Image a =
      render_illumination(gbuffer, t.scene.camera, integrator, illumination_options(options), Progress::silent())
          .surface;
  Image b;
  {
    tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    b = render_illumination(gbuffer, t.scene.camera, integrator, illumination_options(options), Progress::silent())
            .surface;
  }
  for (size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a.pixels[i], b.pixels[i]) << "pixel " << i;
}

}  // namespace
