// Relaxation (thesis 4.4): the gradient landscape, the uphill climb, and
// vertices moving onto a shadow edge in their plane unless the move flips a
// triangle.
#include "mesh/relax.h"

#include <gtest/gtest.h>

#include <cmath>

#include "mesh_invariants.h"

using namespace relight;
using relight::test::signed_area_xy;
using relight::test::top_view;

namespace {

// Lit left of pixel column 52, a quarter as bright from there on; every
// pixel shows input triangle 0.
PhotoSamples shadow_from_column_52() {
  PhotoSamples p;
  p.width = p.height = 100;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 100; ++x) {
      p.intensity.push_back(x < 52 ? 1.0f : 0.25f);
      p.triangle.push_back(0);
    }
  return p;
}

// A vertex at the origin (the image centre, pixel (50, 50)) in a square
// ring of half-size r metres, as a fan of four triangles.
ConnectivityMesh fan(float r, float centre_height = 0) {
  TriangleMesh m;
  m.positions = {{0, 0, centre_height}, {r, -r, 0}, {r, r, 0}, {-r, r, 0}, {-r, -r, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}};
  return ConnectivityMesh(m);
}

TEST(Relax, LogGradientMarksBothSidesOfAStep) {
  const PhotoSamples photo = shadow_from_column_52();
  const std::vector<float> g = log_gradient_magnitude(photo);
  // Sobel across a log step of ln 4: 4 ln 4 / 8 on the two columns beside it.
  EXPECT_NEAR(g[50 * 100 + 51], 0.5f * std::log(4.0f), 1e-5f);
  EXPECT_NEAR(g[50 * 100 + 52], 0.5f * std::log(4.0f), 1e-5f);
  EXPECT_EQ(g[50 * 100 + 50], 0.0f);
  EXPECT_EQ(g[50 * 100 + 53], 0.0f);
}

TEST(Relax, ClimbsToTheTopAndStopsThere) {
  // A hill with its top at (7, 3).
  std::vector<float> hill(100);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) hill[y * 10 + x] = -float((x - 7) * (x - 7) + (y - 3) * (y - 3));
  EXPECT_EQ(climb(hill, 10, 10, 2, 3, 10), Eigen::Vector2i(7, 3));
  EXPECT_EQ(climb(hill, 10, 10, 2, 3, 2), Eigen::Vector2i(4, 3));  // two steps only
  EXPECT_EQ(climb(hill, 10, 10, 0, 9, 6), Eigen::Vector2i(6, 3));  // diagonally
  EXPECT_EQ(climb(hill, 10, 10, 7, 3, 10), Eigen::Vector2i(7, 3));
}

TEST(Relax, MovesAFreeVertexOntoTheShadowEdgeInItsPlane) {
  ConnectivityMesh mesh = fan(2.0f);  // the ring is 20 px from the centre
  const RelaxStats stats = relax_towards_shadow_edges(mesh, top_view(), shadow_from_column_52(), RelaxOptions{});
  EXPECT_EQ(stats.vertices_moved, 1u);  // the ring's vertices are on the boundary
  EXPECT_EQ(stats.moves_refused, 0u);
  // Uphill from pixel (50, 50) the first higher neighbour is (51, 49), on the
  // crest; the vertex goes to the point of the plane seen at its centre.
  const Vec3 p = mesh.vertices()[0].position;
  EXPECT_NEAR(p.x(), (51.5f / 50 - 1) * 5, 1e-5f);
  EXPECT_NEAR(p.y(), (1 - 49.5f / 50) * 5, 1e-5f);
  EXPECT_NEAR(p.z(), 0.0f, 1e-6f);
  for (uint32_t t = 0; t < 4; ++t) EXPECT_GT(signed_area_xy(mesh, t), 0.0f);
}

TEST(Relax, RefusesAMoveThatFlipsATriangle) {
  // The ring is 1 px from the centre: the crest at 51.5 px lies beyond it.
  for (FlipTest test : {FlipTest::side_of_edge, FlipTest::segment_intersection}) {
    ConnectivityMesh mesh = fan(0.1f);
    RelaxOptions options;
    options.flip_test = test;
    const RelaxStats stats = relax_towards_shadow_edges(mesh, top_view(), shadow_from_column_52(), options);
    EXPECT_EQ(stats.vertices_moved, 0u);
    EXPECT_EQ(stats.moves_refused, 2u);  // once per pass
    EXPECT_EQ(mesh.vertices()[0].position, Vec3::Zero());
  }
}

TEST(Relax, LeavesCreasesAndBoundariesWhereTheyAre) {
  ConnectivityMesh mesh = fan(2.0f, 0.5f);  // a pyramid: the centre is a corner of the geometry
  const RelaxStats stats = relax_towards_shadow_edges(mesh, top_view(), shadow_from_column_52(), RelaxOptions{});
  EXPECT_EQ(stats.vertices_moved + stats.moves_refused, 0u);
  EXPECT_EQ(mesh.vertices()[0].position, Vec3(0, 0, 0.5f));
}

}  // namespace
