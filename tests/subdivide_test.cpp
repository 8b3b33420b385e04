// Image-based adaptive subdivision (thesis 4.2): the line fit (eqs. 4.2-4.4),
// where an edge is split and where not, the three criteria, the visible-only
// pixel read, the 3D placement (4.2.4), and whole meshes along a shadow edge.
#include "mesh/subdivide.h"

#include <gtest/gtest.h>

#include "mesh/clip.h"
#include "mesh_invariants.h"

using namespace relight;
using relight::test::connectivity_errors;

namespace {

std::vector<LineSample> samples_of(const std::vector<float>& intensity) {
  std::vector<LineSample> s;
  for (size_t i = 0; i < intensity.size(); ++i) s.push_back({float(i), intensity[i]});
  return s;
}

// 40 pixels, bright up to `step` and 0.2 from there on.
std::vector<LineSample> step_at(int step) {
  std::vector<float> v(40, 1.0f);
  for (int i = step; i < 40; ++i) v[i] = 0.2f;
  return samples_of(v);
}

TEST(LineFit, SolvesTheNormalEquations) {
  std::vector<LineSample> s;
  for (int i = 0; i < 10; ++i) s.push_back({float(i), 2.0f + 0.5f * i});
  const LineFit exact = fit_line(s);
  EXPECT_NEAR(exact.a, 2.0, 1e-9);
  EXPECT_NEAR(exact.b, 0.5, 1e-9);
  // Three points (0,0), (1,1), (2,1): a = 1/6, b = 1/2 by eqs. 4.3-4.4.
  const LineFit fit = fit_line(std::vector<LineSample>{{0, 0}, {1, 1}, {2, 1}});
  EXPECT_NEAR(fit.a, 1.0 / 6.0, 1e-9);
  EXPECT_NEAR(fit.b, 0.5, 1e-9);
}

TEST(FindSplit, SplitsAShadowStepAtTheStep) {
  const SubdivisionOptions options;
  const auto at = find_split(step_at(25), 40.0f, options);
  ASSERT_TRUE(at.has_value());
  EXPECT_GE(*at, 24.0f);
  EXPECT_LE(*at, 25.0f);
}

TEST(FindSplit, LeavesALinearGradientWhole) {
  std::vector<float> ramp;
  for (int i = 0; i < 40; ++i) ramp.push_back(0.2f + 0.02f * i);
  EXPECT_FALSE(find_split(samples_of(ramp), 40.0f, SubdivisionOptions{}).has_value());
}

TEST(FindSplit, NeverSplitsAtOrNextToAnEnd) {
  // A straight gradient whose first pixel is far off: the largest error is
  // there, but a split there would make a sliver.
  std::vector<float> ramp;
  for (int i = 0; i < 40; ++i) ramp.push_back(0.5f + 0.01f * i);
  ramp[0] = 1.5f;
  EXPECT_FALSE(find_split(samples_of(ramp), 40.0f, SubdivisionOptions{}).has_value());
  // Steps near the ends split, but never within the margin (4 px) of an end.
  for (int step : {1, 2, 3, 37, 38, 39}) {
    const auto at = find_split(step_at(step), 40.0f, SubdivisionOptions{});
    if (at) {
      EXPECT_GE(*at, 4.0f) << "step at " << step;
      EXPECT_LE(*at, 36.0f) << "step at " << step;
    }
  }
  // Far enough in, a step is split at the step.
  const auto at = find_split(step_at(6), 40.0f, SubdivisionOptions{});
  ASSERT_TRUE(at.has_value());
  EXPECT_GE(*at, 5.0f);
  EXPECT_LE(*at, 6.0f);
}

TEST(FindSplit, RespectsTheMinimumEdgeLength) {
  SubdivisionOptions options;
  options.min_edge_px = 25;  // a 40-pixel edge is shorter than two minimum edges
  EXPECT_FALSE(find_split(step_at(20), 40.0f, options).has_value());
  options.min_edge_px = 15;  // the split must then be in [15, 25]
  const auto at = find_split(step_at(30), 40.0f, options);
  ASSERT_TRUE(at.has_value());
  EXPECT_GE(*at, 15.0f);
  EXPECT_LE(*at, 25.0f);
}

TEST(FindSplit, ComparingEndPointsMissesAShadowStabbingTheEdge) {
  // Fig. 4.6: a thin shadow across the middle; both ends are lit.
  std::vector<float> v(40, 1.0f);
  for (int i = 18; i < 23; ++i) v[i] = 0.1f;
  SubdivisionOptions options;
  options.criterion = SplitCriterion::compare_end_points;
  EXPECT_FALSE(find_split(samples_of(v), 40.0f, options).has_value());
  options.criterion = SplitCriterion::standard_deviation;
  EXPECT_EQ(find_split(samples_of(v), 40.0f, options), std::optional<float>(20.0f));
  options.criterion = SplitCriterion::line_fit;
  const auto at = find_split(samples_of(v), 40.0f, options);
  ASSERT_TRUE(at.has_value());
  EXPECT_GE(*at, 18.0f);
  EXPECT_LE(*at, 22.0f);
  // A step between the ends: all three split, the two options in the middle.
  options.criterion = SplitCriterion::compare_end_points;
  EXPECT_EQ(find_split(step_at(10), 40.0f, options), std::optional<float>(20.0f));
}

TEST(ReadLine, ReadsEveryPixelUnderTheEdgeWhereItIsVisible) {
  PhotoSamples photo;
  photo.width = photo.height = 10;
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) {
      photo.intensity.push_back(float(x));
      photo.triangle.push_back(x == 5 ? 1u : 0u);  // column 5 shows another surface
    }
  std::vector<LineSample> out;
  const std::vector<uint32_t> visible = {0};
  read_line(photo, {0.5f, 3.5f}, {9.5f, 3.5f}, visible, out);
  ASSERT_EQ(out.size(), 9u);
  for (const LineSample& s : out) {
    EXPECT_NE(s.intensity, 5.0f);
    EXPECT_FLOAT_EQ(s.distance, s.intensity);
  }
  // A diagonal: Bresenham visits one pixel per column.
  read_line(photo, {0.5f, 0.5f}, {9.5f, 9.5f}, std::vector<uint32_t>{0, 1}, out);
  EXPECT_EQ(out.size(), 10u);
}

TEST(PointAtImageFraction, LandsOnTheSplitPixel) {
  CameraSpec spec;
  spec.position = {10, -3.4f, 3.9f};
  spec.look_at = {0, 0, 0.8f};
  const Camera camera(spec, 640, 480);
  const Vec3 a(-3, 2, 0), b(4, -1, 0);  // a ground edge running away from the camera
  const Vec2 pa = *camera.project(a), pb = *camera.project(b);
  for (float s : {0.1f, 0.3f, 0.5f, 0.9f}) {
    const Vec3 p = point_at_image_fraction(camera, a, b, s);
    EXPECT_LT((*camera.project(p) - (pa + s * (pb - pa))).norm(), 1e-3f) << "s = " << s;
    EXPECT_LT((p - a).cross(b - a).norm(), 1e-4f);  // on the 3D edge
  }
  // Not the 3D midpoint: the far half looks shorter.
  EXPECT_GT((point_at_image_fraction(camera, a, b, 0.5f) - 0.5f * (a + b)).norm(), 0.1f);
}

// The top view of clip_test over a plane, its photo lit left of image
// column 37 and in shadow right of it.
struct ShadowedPlane {
  Camera camera = test::top_view();
  ConnectivityMesh mesh = [this] {
    TriangleMesh m;
    m.positions = {{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}};  // fills the view exactly
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    ConnectivityMesh c(m);
    clip_to_view(c, camera);
    return c;
  }();
  PhotoSamples photo = [] {
    PhotoSamples p;
    p.width = p.height = 100;
    for (int y = 0; y < 100; ++y)
      for (int x = 0; x < 100; ++x) {
        p.intensity.push_back(x < 37 ? 1.0f : 0.2f);
        // The input triangle each pixel sees: the diagonal runs from the
        // bottom-left to the top-right corner of the image.
        p.triangle.push_back(x + 0.5f > 99.5f - y ? 0u : 1u);
      }
    return p;
  }();
};

TEST(SubdivideAlongShadows, PutsEveryNewVertexOnTheShadowEdge) {
  ShadowedPlane plane;
  const size_t before = plane.mesh.vertices().size(), triangles_before = plane.mesh.triangles().size();
  const SubdivisionOptions options;
  const SubdivisionStats stats = subdivide_along_shadows(plane.mesh, plane.camera, plane.photo, options);
  EXPECT_GE(stats.edges_split, 3u);  // at least the two borders and the diagonal cross the shadow edge
  EXPECT_EQ(plane.mesh.vertices().size(), before + stats.edges_split);
  // A split adds two triangles, one on the border of the view.
  size_t on_border = 0;
  for (size_t v = before; v < plane.mesh.vertices().size(); ++v) {
    const Vec2 p = *plane.camera.project(plane.mesh.vertices()[v].position);
    on_border += p.y() < 1e-3f || p.y() > 100 - 1e-3f;
    EXPECT_NEAR(p.x(), 37.0f, 1.5f) << "vertex " << v;
    EXPECT_NEAR(plane.mesh.vertices()[v].position.z(), 0.0f, 1e-5f);
  }
  EXPECT_EQ(on_border, 2u);
  EXPECT_EQ(plane.mesh.triangles().size(), triangles_before + 2 * stats.edges_split - on_border);
  // No edge is left crossing the shadow edge farther than the margin from both its ends.
  const float margin = options.min_edge_px + 1.5f;
  for (const MeshEdge& e : plane.mesh.edges()) {
    const Vec2 p0 = *plane.camera.project(plane.mesh.vertices()[e.vertices[0]].position);
    const Vec2 p1 = *plane.camera.project(plane.mesh.vertices()[e.vertices[1]].position);
    if ((p0.x() - 37) * (p1.x() - 37) >= 0) continue;
    const float length = (p1 - p0).norm(), d = length * (37 - p0.x()) / (p1.x() - p0.x());
    EXPECT_TRUE(d < margin || length - d < margin) << "edge from " << p0.transpose() << " to " << p1.transpose();
  }
  EXPECT_EQ(connectivity_errors(plane.mesh), "");

  // With a minimum edge of 60 px only edges over 120 px can be split: the
  // diagonal (141 px), once, 60 px from its end (the shadow edge, 52 px from
  // the end, is too near it); what that split makes is too short to split.
  ShadowedPlane coarse;
  SubdivisionOptions large;
  large.min_edge_px = 60;
  EXPECT_EQ(subdivide_along_shadows(coarse.mesh, coarse.camera, coarse.photo, large).edges_split, 1u);
}

TEST(SubdivideAlongShadows, IgnoresWhatASurfaceInFrontShows) {
  // A dark occluder (triangle id 7) in front of the middle of the plane: the
  // plane's edges behind it must not be split at its outline.
  ShadowedPlane plane;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 100; ++x) {
      const size_t i = size_t(y) * 100 + x;
      const bool occluded = x >= 30 && x < 70 && y >= 30 && y < 70;
      plane.photo.intensity[i] = occluded ? 0.1f : 1.0f;
      if (occluded) plane.photo.triangle[i] = 7;
    }
  EXPECT_EQ(subdivide_along_shadows(plane.mesh, plane.camera, plane.photo, SubdivisionOptions{}).edges_split, 0u);
  // Read without the visibility test, the same photo splits the diagonal.
  ShadowedPlane blind;
  for (size_t i = 0; i < plane.photo.intensity.size(); ++i) blind.photo.intensity[i] = plane.photo.intensity[i];
  EXPECT_GT(subdivide_along_shadows(blind.mesh, blind.camera, blind.photo, SubdivisionOptions{}).edges_split, 0u);
}

}  // namespace
