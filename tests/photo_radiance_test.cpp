// Light that bounces many times, and light read from the photo:
// - a closed room keeps the light of every bounce (no cut after a few:
//   Russian roulette ends the paths), and a probe inside it shows no distant
//   environment;
// - PhotoRadiance gives the photo's pixel for a point the camera sees whole,
//   and nothing for a point hidden, seen from its other side, or clipped.
#include "analysis/photo_radiance.h"

#include <gtest/gtest.h>

#include <memory>

#include "analysis/probe_cleanup.h"
#include "analysis/strategy.h"
#include "core/sampling.h"
#include "render/gbuffer.h"
#include "render/integrator.h"
#include "render/ray_scene.h"
#include "scene/camera.h"
#include "scene/light.h"
#include "scene/triangle_mesh.h"

namespace relight {
namespace {

// Appends the square of half-size `half` centred on `centre` in the plane
// spanned by unit axes u and v.
void add_square(TriangleMesh& mesh, const Vec3& centre, const Vec3& u, const Vec3& v, float half) {
  const uint32_t base = uint32_t(mesh.positions.size());
  for (const auto& [a, b] : {std::pair{-1.0f, -1.0f}, {1.0f, -1.0f}, {1.0f, 1.0f}, {-1.0f, 1.0f}})
    mesh.positions.push_back(centre + half * (a * u + b * v));
  mesh.triangles.push_back({base + 0, base + 1, base + 2});
  mesh.triangles.push_back({base + 0, base + 2, base + 3});
}

// The six faces of the cube [-1, 1]^3.
TriangleMesh closed_cube() {
  TriangleMesh mesh;
  const Vec3 axes[3] = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  for (int a = 0; a < 3; ++a)
    for (float side : {-1.0f, 1.0f}) add_square(mesh, side * axes[a], axes[(a + 1) % 3], axes[(a + 2) % 3], 1.0f);
  return mesh;
}

// A point light of power P inside a closed room of albedo rho: every watt
// is absorbed in the end, (1 - rho) of what arrives each time, so the
// irradiance averaged over the walls is P / ((1 - rho) A). Five times the
// direct light for rho = 0.8; four bounces keep only 3.4 times it.
TEST(ClosedRoom, KeepsTheLightOfEveryBounce) {
  const TriangleMesh mesh = closed_cube();
  const RayScene scene(mesh);
  Lighting lighting;
  Light lamp;
  lamp.type = LightType::point;
  lamp.position = Vec3(0.1f, -0.2f, 0.3f);
  lamp.power = 100.0f;
  lighting.lights = {lamp};
  const float rho = 0.8f;
  const UniformAlbedo albedo(Vec3::Constant(rho));
  const Integrator integrator(scene, lighting, &albedo);

  // Points uniform over the walls, reached from inside.
  Rng rng(3, 0);
  double sum = 0.0;
  const int n = 40000;
  for (int i = 0; i < n; ++i) {
    const int face = std::min(5, int(rng.uniform() * 6.0f));
    const Vec2 uv = 2.0f * rng.uniform2() - Vec2::Ones();
    Vec3 target;
    target[face / 2] = face % 2 ? 1.0f : -1.0f;
    target[(face / 2 + 1) % 3] = uv.x();
    target[(face / 2 + 2) % 3] = uv.y();
    SurfacePoint p;
    ASSERT_TRUE(scene.intersect(Vec3::Zero(), target.normalized(), p));
    sum += kPi * luminance(integrator.illumination(p, rng));
  }
  const double area = 6.0 * 4.0;
  EXPECT_NEAR(sum / n, lamp.power / ((1.0 - rho) * area), 0.02 * lamp.power / ((1.0 - rho) * area));
}

// A probe in the middle of the closed room sees its walls everywhere: none of
// it is distant, and the environment of the analysis is the background,
// black here, so no bounce samples it (a bounce in a closed room cannot reach
// anything distant anyway).
TEST(ClosedRoom, AProbeInsideShowsNoDistantEnvironment) {
  Scene scene;
  scene.mesh = closed_cube();
  const RayScene rays(scene.mesh);
  Probe probe;
  probe.image = Image(64, 32, Vec3(0.4f, 0.3f, 0.2f));  // the walls, as the probe saw them
  probe.position = Vec3(0.1f, 0.0f, -0.2f);
  EXPECT_FALSE(remove_local_geometry_from_probe(probe, rays));
  scene.probes = {probe};
  Light lamp;
  lamp.type = LightType::point;
  lamp.position = Vec3(0.3f, 0.2f, 0.5f);
  scene.lights = {lamp};
  for (Strategy strategy : {Strategy::combined, Strategy::probe})
    EXPECT_TRUE(strategy_environment(scene, rays, strategy).is_black()) << to_string(strategy);
  scene.background = Vec3(0.1f, 0.1f, 0.1f);
  EXPECT_EQ(strategy_environment(scene, rays, Strategy::combined).radiance(nullptr, Vec3::UnitZ()), scene.background);
}

// A camera 2 m above the floor z = 0, looking down, and a small tile at
// height 0.5 hiding part of the floor.
class FloorSeenFromAbove : public testing::Test {
 protected:
  FloorSeenFromAbove()
      : mesh(floor_and_tile()), rays(mesh), camera(spec(), 64, 48), gbuffer(camera, rays, 9, 1, "test"), photo(64, 48) {
    for (int y = 0; y < photo.height; ++y)
      for (int x = 0; x < photo.width; ++x) photo.at(x, y) = Vec3(0.01f * x, 0.02f * y, 0.3f);
  }

  static TriangleMesh floor_and_tile() {
    TriangleMesh m;
    add_square(m, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 10.0f);
    add_square(m, Vec3(0.4f, 0.0f, 0.5f), Vec3::UnitX(), Vec3::UnitY(), 0.2f);
    return m;
  }
  static CameraSpec spec() {
    CameraSpec s;
    s.position = Vec3(0, 0, 2);
    s.look_at = Vec3(0, 0, 0);
    s.up = Vec3(0, 1, 0);
    s.vfov_deg = 50.0f;
    return s;
  }
  // The point of the scene a ray from `from` towards `to` reaches.
  SurfacePoint reach(const Vec3& from, const Vec3& to) const {
    SurfacePoint p;
    EXPECT_TRUE(rays.intersect(from, (to - from).normalized(), p));
    return p;
  }
  Vec3 pixel_of(const Vec3& point) const {
    const Vec2 pos = *camera.project(point);
    return photo.at(int(pos.x()), int(pos.y()));
  }

  TriangleMesh mesh;
  RayScene rays;
  Camera camera;
  GBuffer gbuffer;
  Image photo;
};

TEST_F(FloorSeenFromAbove, APointTheCameraSeesSendsOutThePhotosRadiance) {
  const PhotoRadiance radiance(camera, gbuffer, photo, {}, rays, {});
  const Vec3 point(-0.5f, 0.3f, 0.0f);
  const std::optional<Vec3> l = radiance.at(reach(Vec3(-0.2f, 0.1f, 1.0f), point));
  ASSERT_TRUE(l.has_value());
  EXPECT_EQ(*l, pixel_of(point));
}

TEST_F(FloorSeenFromAbove, NothingIsKnownOfAPointHiddenOrSeenFromBelow) {
  const PhotoRadiance radiance(camera, gbuffer, photo, {}, rays, {});
  // Under the tile: the camera sees the tile there, not the floor.
  EXPECT_FALSE(radiance.at(reach(Vec3(1.5f, 0.0f, 0.2f), Vec3(0.4f, 0.0f, 0.0f))).has_value());
  // The tile's underside, at the pixel that shows its top.
  EXPECT_FALSE(radiance.at(reach(Vec3(0.4f, 0.0f, 0.1f), Vec3(0.4f, 0.0f, 0.5f))).has_value());
  // The top of the tile is seen.
  EXPECT_TRUE(radiance.at(reach(Vec3(0.4f, 0.0f, 1.0f), Vec3(0.4f, 0.0f, 0.5f))).has_value());
}

TEST_F(FloorSeenFromAbove, NothingIsKnownWherePixelsMixSurfacesOrAreClipped) {
  // A pixel on the tile's edge mixes the tile and the floor.
  const Vec3 edge(0.6f, 0.0f, 0.5f);
  const Vec2 pos = *camera.project(edge);
  EXPECT_FALSE(gbuffer.one_surface(int(pos.x()), int(pos.y())));
  // A plateau of pixels at the largest value is clipped.
  for (int x = 0; x < 20; ++x) photo.at(x, 40) = Vec3(0.3f, 5.0f, 0.3f);
  const PhotoRadiance radiance(camera, gbuffer, photo, {}, rays, {});
  EXPECT_EQ(photo_clip_level(photo), 5.0f);
  const Vec3 clipped_point = reach(camera.position(), camera.position() + camera.ray_direction(10.5f, 40.5f)).position;
  EXPECT_FALSE(radiance.at(reach(Vec3(0.0f, 0.0f, 1.0f), clipped_point)).has_value());
  EXPECT_TRUE(radiance.at(reach(Vec3(0.0f, 0.0f, 1.0f), Vec3(-0.5f, 0.3f, 0.0f))).has_value());
}

}  // namespace
}  // namespace relight
