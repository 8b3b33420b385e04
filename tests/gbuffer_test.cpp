// The compact G-buffer: a pixel whose samples all see one triangle keeps
// only the triangle, and gives back the samples it traced when asked; a
// pixel on an edge keeps its samples whole.
#include "render/gbuffer.h"

#include <gtest/gtest.h>

#include "flat_walls.h"

using namespace relight;

namespace {

TEST(CompactGBuffer, GivesBackTheSamplesItTracedInAFractionOfTheMemory) {
  // A near wall half across a far one: the near wall's edge and the image's
  // top and bottom rows' triangles' diagonals are the only edges.
  const TriangleMesh mesh = test::walls_mesh({{4.0f, -10.0f, 10.0f}, {2.0f, -10.0f, 0.3f}});
  const RayScene rays(mesh);
  const Camera camera = test::walls_camera(64, 48);
  const GBuffer g(camera, rays, 9, 1, "walls");
  int kept_whole = 0;
  for (int y = 0; y < g.height(); ++y)
    for (int x = 0; x < g.width(); ++x) {
      kept_whole += !g.one_surface(x, y);
      for (int k = 0; k < g.samples_per_pixel(); ++k) {
        const Vec2 pos = g.sample_position(x, y, k);
        SurfacePoint traced;
        const bool hit = rays.intersect(camera.position(), camera.ray_direction(pos.x(), pos.y()), traced);
        const GBufferSample s = g.sample(x, y, k);
        ASSERT_EQ(s.hit, hit) << x << " " << y << " " << k;
        if (!hit) continue;
        EXPECT_EQ(s.surface.prim, traced.prim);
        EXPECT_LT((s.surface.position - traced.position).norm(), 1e-5f * traced.distance);
        EXPECT_LT((s.surface.normal - traced.normal).norm(), 1e-5f);
        EXPECT_NEAR(s.surface.distance, traced.distance, 1e-5f * traced.distance);
      }
    }
  EXPECT_GT(kept_whole, 0) << "the near wall's edge";
  // 16 bytes a pixel, and whole samples for the pixels on an edge (the
  // walls' diagonals are edges between triangles too: a few percent here).
  EXPECT_LT(g.bytes_per_pixel(), 16.0 + 0.1 * 9 * sizeof(GBufferSample));
}

}  // namespace
