// Clipping to the view (thesis 4.3): edges split at the image border, what
// is outside dropped, connectivity kept.
#include "mesh/clip.h"

#include <gtest/gtest.h>

#include "mesh_invariants.h"

using namespace relight;
using relight::test::connectivity_errors;
using relight::test::signed_area_xy;
using relight::test::top_view;

namespace {

TEST(ClipToView, SplitsTheTwoEdgesCrossingABorderAndDropsTheOutsideCorner) {
  TriangleMesh m;
  m.positions = {{-7, 0, 0}, {0, -2, 0}, {0, 2, 0}};  // the first corner is left of x = -5
  m.triangles = {{0, 1, 2}};
  ConnectivityMesh mesh(m);
  const ClipStats stats = clip_to_view(mesh, top_view());
  EXPECT_EQ(stats.edges_split, 2u);
  EXPECT_EQ(stats.triangles_dropped, 1u);
  EXPECT_EQ(mesh.triangles().size(), 2u);
  EXPECT_EQ(mesh.vertices().size(), 4u);
  EXPECT_EQ(mesh.edges().size(), 5u);
  int on_border = 0;
  for (const MeshVertex& v : mesh.vertices())
    if (std::abs(v.position.x() + 5) < 1e-5f) {
      ++on_border;
      EXPECT_NEAR(std::abs(v.position.y()), 2.0f * 2.0f / 7.0f, 1e-5f);  // 2/7 of the way from (-7, 0) to (0, +-2)
    }
  EXPECT_EQ(on_border, 2);
  // What is left is the triangle (area 14) minus its tip beyond x = -5, similar with ratio 2/7.
  float area = 0;
  for (uint32_t t = 0; t < mesh.triangles().size(); ++t) area += 0.5f * signed_area_xy(mesh, t);
  EXPECT_NEAR(area, 14.0f - 14.0f * 4.0f / 49.0f, 1e-4f);
  EXPECT_EQ(connectivity_errors(mesh), "");
}

TEST(ClipToView, CutsALargePlaneToExactlyWhatTheCameraSees) {
  TriangleMesh m;
  m.positions = {{-20, -20, 0}, {20, -20, 0}, {20, 20, 0}, {-20, 20, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  ConnectivityMesh mesh(m);
  clip_to_view(mesh, top_view());
  float area = 0;
  for (uint32_t t = 0; t < mesh.triangles().size(); ++t) {
    EXPECT_GT(signed_area_xy(mesh, t), 0.0f) << "triangle " << t << " flipped";
    area += 0.5f * signed_area_xy(mesh, t);
  }
  EXPECT_NEAR(area, 100.0f, 1e-3f);
  for (const MeshVertex& v : mesh.vertices()) {
    EXPECT_LE(std::abs(v.position.x()), 5.0f + 1e-4f);
    EXPECT_LE(std::abs(v.position.y()), 5.0f + 1e-4f);
  }
  EXPECT_EQ(connectivity_errors(mesh), "");
}

TEST(ClipToView, DropsWhatIsBehindTheCamera) {
  // A wall through the camera's position: only the half in front stays.
  const Camera camera = top_view();
  TriangleMesh m;
  m.positions = {{-1, 0, 10}, {1, 0, 10}, {0, 0, 0}};
  m.triangles = {{0, 1, 2}};
  ConnectivityMesh mesh(m);
  const ClipStats stats = clip_to_view(mesh, camera, 0.5f);
  EXPECT_GT(stats.edges_split, 0u);
  for (const MeshVertex& v : mesh.vertices()) {
    EXPECT_LE(v.position.z(), 4.5f + 1e-4f);
    ASSERT_TRUE(camera.project(v.position).has_value());
  }
  EXPECT_EQ(connectivity_errors(mesh), "");
}

}  // namespace
