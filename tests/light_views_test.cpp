// Where the OpenGL backend's shadow maps look from and how they project:
// matrices and light samples, checked without an OpenGL context.
#include "realtime/light_views.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace relight;

namespace {

Vec3 transform(const Mat4& m, const Vec3& p) {
  const Eigen::Vector4f q = m * p.homogeneous();
  return q.head<3>() / q.w();
}

void expect_near(const Vec3& a, const Vec3& b, float tolerance = 1e-5f) {
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), tolerance) << a.transpose() << " vs " << b.transpose();
}

// A 4 x 3 x 2.5 m room; the view sees n points of its floor, the i-th at
// distance i + 1 from the camera.
const Eigen::AlignedBox3f kRoom(Vec3(0, 0, 0), Vec3(4, 3, 2.5f));

PixelSurfaces floor_view(int n) {
  PixelSurfaces surfaces;
  surfaces.width = n;
  surfaces.height = 1;
  for (int i = 0; i < n; ++i) {
    SurfacePoint s;
    s.position = Vec3(0.5f + 3.0f * float(i) / float(n - 1), 1.5f, 0.0f);
    s.normal = s.geometric_normal = Vec3::UnitZ();
    s.distance = float(i + 1);
    surfaces.surface.push_back(s);
    surfaces.hit.push_back(1);
  }
  return surfaces;
}

TEST(LightViews, LookAtPutsTheEyeAtTheOriginLookingDownMinusZ) {
  const Vec3 eye(1, 2, 3), forward(0, 1, 0);
  const Mat4 view = look_at(eye, forward, Vec3(0, 0, 1));
  expect_near(transform(view, eye), Vec3::Zero());
  expect_near(transform(view, eye + 2.0f * forward), Vec3(0, 0, -2));
  expect_near(transform(view, eye + Vec3(0, 0, 1)), Vec3(0, 1, 0));  // up stays up
  // An up hint along the view axis is replaced, not divided by zero.
  EXPECT_TRUE(look_at(eye, Vec3(0, 0, 1), Vec3(0, 0, 1)).allFinite());
}

TEST(LightViews, ProjectionsMapTheirVolumeOntoTheClipCube) {
  const float fovy = radians(60.0f), near = 0.1f, far = 10.0f;
  const Mat4 p = perspective(fovy, near, far);
  EXPECT_NEAR(transform(p, Vec3(0, 0, -near)).z(), -1.0f, 1e-5f);
  EXPECT_NEAR(transform(p, Vec3(0, 0, -far)).z(), 1.0f, 1e-4f);
  EXPECT_NEAR(transform(p, Vec3(0, 2.0f * std::tan(fovy / 2), -2.0f)).y(), 1.0f, 1e-5f);
  const Mat4 o = orthographic(-1, 3, -2, 2, 1, 5);
  expect_near(transform(o, Vec3(-1, -2, -1)), Vec3(-1, -1, -1));
  expect_near(transform(o, Vec3(3, 2, -5)), Vec3(1, 1, 1));
}

// OpenGL's cube faces +x, -x, +y, -y, +z, -z, each with the up its
// texture coordinates imply (the OpenGL specification's table of cube faces).
TEST(LightViews, CubeFacesLookAlongTheirAxesWithOpenGLsUp) {
  const Vec3 eye(1, 1, 1);
  const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const Vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  for (int face = 0; face < 6; ++face) {
    const Mat4 view = cube_face_view(eye, face);
    expect_near(transform(view, eye + axes[face]), Vec3(0, 0, -1));
    expect_near(transform(view, eye + axes[face] + ups[face]), Vec3(0, 1, -1));
  }
}

TEST(LightViews, APointLightIsOneCubeMapHoldingTheWholeScene) {
  ShadowMapOptions options;
  const LightViews views(options, kRoom, floor_view(9));
  Light lamp;
  lamp.position = Vec3(2, 1.5f, 2);
  lamp.power = 100;
  const std::vector<LightSamplePoint> samples = views.samples_of(lamp);
  ASSERT_EQ(samples.size(), 1u);
  const LightSamplePoint& s = samples[0];
  EXPECT_EQ(s.map, LightSamplePoint::Map::cube);
  expect_near(s.eye, lamp.position);
  EXPECT_EQ(s.side, options.size / 2);
  EXPECT_EQ(s.weight, 1.0f);
  for (int i = 0; i < 8; ++i) {
    const float depth = (kRoom.corner(Eigen::AlignedBox3f::CornerType(i)) - s.eye).cwiseAbs().maxCoeff();
    EXPECT_GT(depth, s.near);
    EXPECT_LT(depth, s.far);
  }
}

TEST(LightViews, ASpotIsAPerspectiveMapUnlessItIsNearlyAHemisphere) {
  const LightViews views(ShadowMapOptions{}, kRoom, floor_view(9));
  Light spot;
  spot.type = LightType::spot;
  spot.position = Vec3(2, 1.5f, 2.4f);
  spot.direction = Vec3(0, 0, -1);
  spot.spot_angle_deg = 40.0f;
  spot.power = 100;
  const LightSamplePoint narrow = views.samples_of(spot)[0];
  EXPECT_EQ(narrow.map, LightSamplePoint::Map::perspective);
  // The cone's edge is inside the map.
  const Vec3 edge = spot.position + Vec3(std::tan(radians(20.0f)), 0, -1);
  EXPECT_LT(std::abs(transform(narrow.view_projection, edge).x()), 1.0f);
  spot.spot_angle_deg = 170.0f;
  EXPECT_EQ(views.samples_of(spot)[0].map, LightSamplePoint::Map::cube);
}

TEST(LightViews, AnAreaLightsSamplesShareItAndLieOnItsRectangle) {
  ShadowMapOptions options;
  options.soft_samples = 8;
  const PixelSurfaces view = floor_view(9);
  const LightViews views(options, kRoom, view);
  Light panel;
  panel.type = LightType::area;
  panel.position = Vec3(2, 1.5f, 2.4f);
  panel.direction = Vec3(0, 0, -1);
  panel.up = Vec3(0, 1, 0);
  panel.size = Vec2(1.0f, 0.5f);
  panel.power = 100;
  const std::vector<LightSamplePoint> samples = views.samples_of(panel);
  ASSERT_EQ(samples.size(), 8u);
  float weights = 0.0f;
  for (const LightSamplePoint& s : samples) {
    weights += s.weight;
    EXPECT_EQ(s.map, LightSamplePoint::Map::perspective);
    const Vec3 d = s.area_point - panel.position;
    EXPECT_LE(std::abs(d.x()), 0.5f + 1e-5f);
    EXPECT_LE(std::abs(d.y()), 0.25f + 1e-5f);
    EXPECT_NEAR(d.z(), 0.0f, 1e-6f);
    expect_near(s.eye, s.area_point);
    // Every point the view sees is inside the sample's map.
    for (const SurfacePoint& p : view.surface) {
      const Vec3 ndc = transform(s.view_projection, p.position);
      EXPECT_LE(ndc.head<2>().cwiseAbs().maxCoeff(), 1.0f);
    }
  }
  EXPECT_NEAR(weights, 1.0f, 1e-6f);
}

TEST(LightViews, TheSunsCascadesSplitThePixelsAndHoldEveryOccluder) {
  ShadowMapOptions options;
  options.sun_cascades = 3;
  const PixelSurfaces view = floor_view(9);
  const LightViews views(options, kRoom, view);
  Light sun;
  sun.type = LightType::directional;
  sun.direction = Vec3(0.3f, 0.2f, -1.0f).normalized();
  sun.irradiance = 3;
  sun.angle_deg = 0.5f;  // at most a degree: drawn from its centre alone
  const std::vector<LightSamplePoint> samples = views.samples_of(sun);
  ASSERT_EQ(samples.size(), 3u);
  EXPECT_EQ(samples[0].distance_range.x(), 0.0f);
  EXPECT_TRUE(std::isinf(samples[2].distance_range.y()));
  for (size_t c = 0; c < samples.size(); ++c) {
    const LightSamplePoint& s = samples[c];
    EXPECT_EQ(s.map, LightSamplePoint::Map::orthographic);
    EXPECT_EQ(s.weight, 1.0f);
    EXPECT_EQ(s.side, options.sun_size);
    if (c > 0) {
      EXPECT_EQ(s.distance_range.x(), samples[c - 1].distance_range.y());
    }
    int served = 0;
    for (const SurfacePoint& p : view.surface) {
      if (p.distance < s.distance_range.x() || p.distance >= s.distance_range.y()) continue;
      ++served;
      EXPECT_LE(transform(s.view_projection, p.position).head<2>().cwiseAbs().maxCoeff(), 1.0f);
    }
    EXPECT_EQ(served, 3);  // equal shares of the pixels
    for (int i = 0; i < 8; ++i) {
      const float z = transform(s.view_projection, kRoom.corner(Eigen::AlignedBox3f::CornerType(i))).z();
      EXPECT_GE(z, -1.0f);
      EXPECT_LE(z, 1.0f);
    }
  }
  sun.angle_deg = 5.0f;  // a wider sun is spread over soft_samples directions
  EXPECT_EQ(views.samples_of(sun).size(), size_t(3 * options.soft_samples));
}

}  // namespace
