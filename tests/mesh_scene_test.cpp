// The refined mesh on the outdoor reference scene follows the sun's shadow
// edges: the share of shadow-edge pixels (where photo / albedo_gt jumps)
// within 1.5 px of a visible mesh edge, before and after refinement.
// Skipped where the reference scenes are absent.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <numeric>

#include "io/image_io.h"
#include "io/scene_io.h"
#include "mesh/mesh_picture.h"
#include "mesh/refine.h"
#include "reference_scenes.h"

namespace fs = std::filesystem;
using namespace relight;

namespace {

TEST(OutdoorMesh, FollowsTheSunsShadowEdges) {
  const fs::path folder = relight::test::reference_scenes_folder() / "outdoor";
  if (!fs::exists(folder / "scene.json")) GTEST_SKIP() << "reference scene " << folder << " not found";
  const Scene scene = load_scene(folder / "scene.json");
  const RayScene rays(scene.mesh);
  const GBuffer gbuffer(scene.camera, rays, 1, 1, "outdoor");
  const PhotoSamples photo = photo_samples(scene.photo, gbuffer);
  int w, h;
  const std::vector<float> mask = read_scalar_image(folder / "mask.exr", w, h);
  const std::vector<uint8_t> shadow =
      shadow_edge_pixels(scene.photo, read_image(folder / "albedo_gt.exr"), mask, gbuffer);
  const size_t shadow_pixels = std::accumulate(shadow.begin(), shadow.end(), size_t(0));
  ASSERT_GT(shadow_pixels, 1000u);  // the sun's shadows: 4484 pixels

  ConnectivityMesh unrefined(scene.mesh);
  clip_to_view(unrefined, scene.camera);
  const double before = share_within_1_5_px(shadow, visible_edge_pixels(unrefined, scene.camera, photo), w, h);

  RefineReport report;
  const ConnectivityMesh refined = refine_mesh_for_photo(scene.mesh, scene.camera, photo, RefineOptions{}, report);
  const double after = share_within_1_5_px(shadow, visible_edge_pixels(refined, scene.camera, photo), w, h);
  std::printf(
      "[ figures  ] outdoor: %zu shadow-edge pixels, %.1f %% within 1.5 px of an edge before (%zu triangles "
      "in view), %.1f %% after (%zu triangles)\n",
      shadow_pixels, 100 * before, report.triangles_clipped, 100 * after, refined.triangles().size());
  // Measured: 46.8 % before (the modelled edges: columns, blocks), 94.8 % after.
  EXPECT_LT(before, 0.6);
  EXPECT_GE(after, 0.9);
  // With at most four times the triangles in view (measured: 1866 -> 5867).
  EXPECT_GT(refined.triangles().size(), report.triangles_clipped);
  EXPECT_LT(refined.triangles().size(), 4 * report.triangles_clipped);
}

}  // namespace
