// The connectivity mesh (thesis 4.1): building and cleaning, edge split,
// vertex move and its two flip tests (Fig. 4.13), non-manifold edges.
#include <gtest/gtest.h>

#include "core/sampling.h"
#include "mesh/connectivity_mesh.h"
#include "mesh_invariants.h"

using namespace relight;
using relight::test::connectivity_errors;
using relight::test::signed_area_xy;

namespace {

// The unit square in z = 0 as two counter-clockwise triangles on the diagonal 0-2.
TriangleMesh unit_square() {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

// A vertex at the origin with its one-ring `ring` (counter-clockwise), as a fan.
TriangleMesh fan(const std::vector<Vec2>& ring) {
  TriangleMesh m;
  m.positions.push_back(Vec3::Zero());
  for (const Vec2& p : ring) m.positions.push_back({p.x(), p.y(), 0});
  const uint32_t n = uint32_t(ring.size());
  for (uint32_t i = 0; i < n; ++i) m.triangles.push_back({0, 1 + i, 1 + (i + 1) % n});
  return m;
}

Vec2 drop_z(const Vec3& p) { return p.head<2>(); }

TEST(ConnectivityMesh, BuildsVerticesEdgesAndTriangles) {
  const ConnectivityMesh mesh(unit_square());
  EXPECT_EQ(mesh.vertices().size(), 4u);
  EXPECT_EQ(mesh.edges().size(), 5u);
  EXPECT_EQ(mesh.triangles().size(), 2u);
  const uint32_t diagonal = mesh.find_edge(0, 2);
  ASSERT_NE(diagonal, ConnectivityMesh::kNone);
  EXPECT_EQ(mesh.edges()[diagonal].triangles.size(), 2u);
  EXPECT_EQ(mesh.edges()[mesh.find_edge(0, 1)].triangles.size(), 1u);
  EXPECT_EQ(mesh.find_edge(1, 3), ConnectivityMesh::kNone);
  EXPECT_EQ(mesh.vertices()[0].triangles.size(), 2u);
  EXPECT_EQ(mesh.vertices()[1].triangles.size(), 1u);
  EXPECT_EQ(connectivity_errors(mesh), "");
}

TEST(ConnectivityMesh, SplitsAnInteriorEdgeAndBothItsTriangles) {
  ConnectivityMesh mesh(unit_square());
  const uint32_t m = mesh.split_edge(mesh.find_edge(0, 2), {0.5f, 0.5f, 0});
  EXPECT_EQ(m, 4u);
  EXPECT_EQ(mesh.vertices().size(), 5u);
  EXPECT_EQ(mesh.edges().size(), 8u);
  EXPECT_EQ(mesh.triangles().size(), 4u);
  EXPECT_EQ(mesh.vertices()[m].triangles.size(), 4u);
  EXPECT_EQ(mesh.vertices()[m].position, Vec3(0.5f, 0.5f, 0));
  for (uint32_t corner = 0; corner < 4; ++corner) EXPECT_NE(mesh.find_edge(m, corner), ConnectivityMesh::kNone);
  EXPECT_EQ(mesh.find_edge(0, 2), ConnectivityMesh::kNone);
  for (uint32_t t = 0; t < 4; ++t) EXPECT_FLOAT_EQ(signed_area_xy(mesh, t), 0.5f) << "triangle " << t;
  EXPECT_EQ(mesh.triangles()[2].source, 0u);
  EXPECT_EQ(mesh.triangles()[3].source, 1u);
  EXPECT_EQ(connectivity_errors(mesh), "");
}

TEST(ConnectivityMesh, SplitsABoundaryEdgeAndItsOneTriangle) {
  ConnectivityMesh mesh(unit_square());
  const uint32_t m = mesh.split_edge(mesh.find_edge(0, 1), {0.25f, 0, 0});
  EXPECT_EQ(mesh.vertices().size(), 5u);
  EXPECT_EQ(mesh.edges().size(), 7u);
  EXPECT_EQ(mesh.triangles().size(), 3u);
  EXPECT_EQ(mesh.vertices()[m].triangles.size(), 2u);
  EXPECT_EQ(mesh.edges()[mesh.find_edge(m, 2)].triangles.size(), 2u);
  EXPECT_FLOAT_EQ(signed_area_xy(mesh, 0), 0.25f);
  EXPECT_FLOAT_EQ(signed_area_xy(mesh, 2), 0.75f);
  EXPECT_FALSE(mesh.is_interior_vertex(m));
  EXPECT_EQ(connectivity_errors(mesh), "");
}

TEST(ConnectivityMesh, WeldsDuplicateVertices) {
  // The square's two triangles with their own copies of the shared corners.
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  const ConnectivityMesh exact(m);
  EXPECT_EQ(exact.cleanup().welded_vertices, 2u);
  EXPECT_EQ(exact.vertices().size(), 4u);
  EXPECT_EQ(exact.edges().size(), 5u);
  EXPECT_EQ(exact.edges()[exact.find_edge(0, 2)].triangles.size(), 2u);

  // Copies 10 micrometres off are welded only within a weld distance.
  m.positions[3] = {1e-5f, 0, 0};
  m.positions[4] = {1, 1 - 1e-5f, 0};
  EXPECT_EQ(ConnectivityMesh(m).vertices().size(), 6u);
  const ConnectivityMesh near(m, 1e-4f);
  EXPECT_EQ(near.cleanup().welded_vertices, 2u);
  EXPECT_EQ(near.vertices().size(), 4u);
  EXPECT_EQ(near.edges().size(), 5u);
  EXPECT_EQ(connectivity_errors(near), "");
}

TEST(ConnectivityMesh, DropsDegenerateTriangles) {
  TriangleMesh m = unit_square();
  m.positions.push_back({2, 0, 0});
  m.triangles.push_back({0, 0, 1});  // repeated corner
  m.triangles.push_back({0, 1, 4});  // collinear: zero area
  const ConnectivityMesh mesh(m);
  EXPECT_EQ(mesh.cleanup().degenerate_triangles, 2u);
  EXPECT_EQ(mesh.triangles().size(), 2u);
  EXPECT_EQ(mesh.edges().size(), 5u);
  EXPECT_EQ(mesh.triangles()[1].source, 1u);
  EXPECT_TRUE(mesh.vertices()[4].triangles.empty());
  EXPECT_EQ(mesh.to_triangle_mesh().positions.size(), 4u);
}

TEST(ConnectivityMesh, KeepsAndSplitsANonManifoldEdge) {
  // Three triangles (fins) on the edge 0-1.
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0.5f, 1, 0}, {0.5f, -1, 0}, {0.5f, 0, 1}};
  m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  ConnectivityMesh mesh(m);
  EXPECT_EQ(mesh.cleanup().non_manifold_edges, 1u);
  const uint32_t fin_edge = mesh.find_edge(0, 1);
  EXPECT_EQ(mesh.edges()[fin_edge].triangles.size(), 3u);
  EXPECT_FALSE(mesh.is_interior_vertex(0));
  const uint32_t v = mesh.split_edge(fin_edge, {0.5f, 0, 0});
  EXPECT_EQ(mesh.triangles().size(), 6u);
  EXPECT_EQ(mesh.vertices()[v].triangles.size(), 6u);
  EXPECT_EQ(mesh.edges()[mesh.find_edge(0, v)].triangles.size(), 3u);
  EXPECT_EQ(mesh.edges()[mesh.find_edge(v, 1)].triangles.size(), 3u);
  EXPECT_EQ(connectivity_errors(mesh), "");
}

TEST(ConnectivityMesh, KeepTrianglesRenumbersWhatIsLeft) {
  ConnectivityMesh mesh(unit_square());
  mesh.keep_triangles([](const MeshTriangle& t) { return t.source == 1; });
  EXPECT_EQ(mesh.triangles().size(), 1u);
  EXPECT_EQ(mesh.vertices().size(), 3u);
  EXPECT_EQ(mesh.edges().size(), 3u);
  EXPECT_EQ(mesh.vertices()[1].position, Vec3(1, 1, 0));
  EXPECT_EQ(connectivity_errors(mesh), "");
}

TEST(VertexMove, MovesInsideItsRingAndRefusesAFlip) {
  ConnectivityMesh mesh(fan({{1, -1}, {1, 1}, {-1, 1}, {-1, -1}}));
  EXPECT_TRUE(mesh.is_interior_vertex(0));
  for (FlipTest test : {FlipTest::side_of_edge, FlipTest::segment_intersection}) {
    ConnectivityMesh m = mesh;
    EXPECT_TRUE(m.move_vertex(0, {0.5f, 0.25f, 0}, drop_z, test));
    EXPECT_EQ(m.vertices()[0].position, Vec3(0.5f, 0.25f, 0));
    EXPECT_FALSE(m.move_vertex(0, {1.5f, 0.25f, 0}, drop_z, test));  // past the edge x = 1
    EXPECT_FALSE(m.move_vertex(0, {1.0f, 0.0f, 0}, drop_z, test));   // onto it: flat triangle
    EXPECT_EQ(m.vertices()[0].position, Vec3(0.5f, 0.25f, 0));
    for (uint32_t t = 0; t < 4; ++t) EXPECT_GT(signed_area_xy(m, t), 0.0f);
  }
}

TEST(VertexMove, BothFlipTestsAgreeInAConvexRing) {
  // A convex ring: a move flips a triangle exactly when it crosses its
  // opposite edge, so both tests must give the same answer every time.
  const ConnectivityMesh mesh(fan({{1, -1}, {1.5f, 0.5f}, {0, 1}, {-1, 0.5f}, {-1, -1}}));
  Rng rng(7, 0);
  int agree = 0, allowed = 0;
  const int moves = 2000;
  for (int i = 0; i < moves; ++i) {
    const Vec2 to = (rng.uniform2() * 4.0f).array() - 2.0f;
    ConnectivityMesh a = mesh, b = mesh;
    const bool side = a.move_vertex(0, {to.x(), to.y(), 0}, drop_z, FlipTest::side_of_edge);
    const bool segment = b.move_vertex(0, {to.x(), to.y(), 0}, drop_z, FlipTest::segment_intersection);
    agree += side == segment;
    allowed += side;
    if (side) {
      for (uint32_t t = 0; t < 5; ++t) EXPECT_GT(signed_area_xy(a, t), 0.0f);
    }
  }
  EXPECT_EQ(agree, moves);
  EXPECT_GT(allowed, moves / 8);  // both outcomes occur
  EXPECT_LT(allowed, moves - moves / 8);
}

TEST(VertexMove, OnlyTheSideTestCatchesAFlipInANonConvexRing) {
  // The ring is notched at (-0.2, 0): moving to (0.5, 0.9) crosses no edge of
  // the ring but passes the line through the notch's lower edge, reversing
  // the triangle (v, notch, (-1, -1)).
  const ConnectivityMesh mesh(fan({{1, -1}, {1, 1}, {-1, 1}, {-0.2f, 0}, {-1, -1}}));
  const Vec3 to(0.5f, 0.9f, 0);
  ConnectivityMesh side = mesh, segment = mesh;
  EXPECT_FALSE(side.move_vertex(0, to, drop_z, FlipTest::side_of_edge));
  EXPECT_TRUE(segment.move_vertex(0, to, drop_z, FlipTest::segment_intersection));
  EXPECT_LT(signed_area_xy(segment, 3), 0.0f);  // the flip the segment test let through
  EXPECT_FALSE(stays_on_side_of_edge({-0.2f, 0}, {-1, -1}, {0, 0}, {0.5f, 0.9f}));
  EXPECT_FALSE(move_crosses_edge({-0.2f, 0}, {-1, -1}, {0, 0}, {0.5f, 0.9f}));
}

}  // namespace
