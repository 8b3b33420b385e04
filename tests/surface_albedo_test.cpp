// PhotoAlbedo: the albedo light bounces off where the photo does not show the
// surface. A triangle the photo shows by only a sliver of pixels (a wall at
// the frame's edge) must not stand on those pixels for the whole surface.
#include "analysis/surface_albedo.h"

#include <gtest/gtest.h>

#include "flat_walls.h"

using namespace relight;

namespace {

constexpr int kW = 40, kH = 20;

// Wall A at 5 m fills the view but its last column and a half; wall B, at
// 6 m behind it, shows there: whole in the last column, mixed with A in the
// one before.
struct SliverOfAWall {
  TriangleMesh mesh = test::walls_mesh({{5.0f, -10.0f, 3.4f}, {6.0f, -10.0f, 10.0f}});
  RayScene rays{mesh};
  Camera camera = test::walls_camera(kW, kH);
  GBuffer gbuffer{camera, rays, 9, 1, "walls"};
  Image albedo{kW, kH};
  static constexpr uint32_t kWallB = 2;  // its first triangle

  // Wall A's pixels read 0.2; every pixel that shows any of B reads 0.9.
  SliverOfAWall() {
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        std::vector<GBufferSample> samples;
        gbuffer.pixel_samples(x, y, samples);
        const bool shows_b = std::any_of(samples.begin(), samples.end(),
                                         [](const GBufferSample& s) { return s.hit && s.surface.prim >= kWallB; });
        albedo.at(x, y) = Vec3::Constant(shows_b ? 0.9f : 0.2f);
      }
  }
  // A point of B behind A, as light bouncing between the walls reaches it.
  SurfacePoint hidden_point_of_b() const {
    SurfacePoint p;
    EXPECT_TRUE(rays.intersect(Vec3(0.0f, 5.5f, 0.0f), Vec3(0.0f, 1.0f, 0.0f), p));
    return p;
  }
};

TEST(WholePixelsPerTriangle, CountsOnlyPixelsThatShowOneSurface) {
  const SliverOfAWall s;
  const std::vector<uint32_t> count = whole_pixels_per_triangle(s.gbuffer, s.mesh.triangles.size());
  ASSERT_EQ(count.size(), 4u);
  // B is whole in one column of 20 rows; the column where it meets A is not counted.
  EXPECT_EQ(count[2] + count[3], uint32_t(kH));
  EXPECT_LT(count[2] + count[3], kFewPixels);
  EXPECT_GT(count[0] + count[1], uint32_t((kW - 2) * kH) - 1);
}

TEST(PhotoAlbedo, ASliverOfATriangleDoesNotStandForItsUnseenPart) {
  const SliverOfAWall s;
  const SurfacePoint hidden = s.hidden_point_of_b();
  ASSERT_GE(hidden.prim, SliverOfAWall::kWallB);
  const Vec3 probes_albedo(0.5f, 0.4f, 0.3f);
  const std::vector<TriangleAlbedo> from_probes = {{2, probes_albedo}, {3, probes_albedo}};
  // With what the probes show of B, B's unseen part takes that.
  const PhotoAlbedo with_probes(s.camera, s.gbuffer, s.albedo, Vec3::Constant(0.6f), from_probes);
  EXPECT_LT((with_probes.at(hidden) - probes_albedo).cwiseAbs().maxCoeff(), 1e-6f);
  // Without, the mean of B's whole pixels (not the mixed ones).
  const PhotoAlbedo photo_only(s.camera, s.gbuffer, s.albedo, Vec3::Constant(0.6f));
  EXPECT_LT((photo_only.at(hidden) - Vec3::Constant(0.9f)).cwiseAbs().maxCoeff(), 1e-6f);
  // A well-seen wall keeps the photo's mean, where a probe's albedo is listed for it too:
  // a point of A above the frame.
  SurfacePoint out_of_view;
  ASSERT_TRUE(s.rays.intersect(Vec3(0.0f, 4.0f, 9.5f), Vec3(0.0f, 1.0f, 0.0f), out_of_view));
  ASSERT_LT(out_of_view.prim, SliverOfAWall::kWallB);
  const std::vector<TriangleAlbedo> a_listed = {{0, probes_albedo}, {1, probes_albedo}};
  const PhotoAlbedo a_seen(s.camera, s.gbuffer, s.albedo, Vec3::Constant(0.6f), a_listed);
  EXPECT_LT((a_seen.at(out_of_view) - Vec3::Constant(0.2f)).cwiseAbs().maxCoeff(), 1e-6f);
}

}  // namespace
