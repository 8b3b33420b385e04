// Gathering radiosity (src/render/radiosity.h) and the even edge splitting
// its scene mesh needs: node counts, closed-form irradiance, and agreement
// with the path tracer where light bounces.
#include <gtest/gtest.h>

#include <memory>

#include "mesh/subdivide.h"
#include "render/radiosity.h"

namespace relight {
namespace {

// A square of half-size `half` at height z, wound counter-clockwise seen
// from above (normal +z), as two triangles.
TriangleMesh square(float half, float z = 0.0f) {
  TriangleMesh m;
  m.positions = {{-half, -half, z}, {half, -half, z}, {half, half, z}, {-half, half, z}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

// The unit cube's twelve triangles, wound outwards.
TriangleMesh cube() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) m.positions.emplace_back(float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1));
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    m.triangles.push_back({uint32_t(f[0]), uint32_t(f[1]), uint32_t(f[2])});
    m.triangles.push_back({uint32_t(f[0]), uint32_t(f[2]), uint32_t(f[3])});
  }
  return m;
}

// The mesh split evenly to edges of at most `length`, with its sources.
NodeMesh split_node_mesh(const TriangleMesh& mesh, float length, NodeMesh::Sides sides) {
  ConnectivityMesh c(mesh);
  split_long_edges(c, [&](const Vec3& a, const Vec3& b) { return (b - a).norm() / length; }, 1'000'000);
  std::vector<uint32_t> sources;
  TriangleMesh split = c.to_triangle_mesh(&sources);
  return NodeMesh(std::move(split), std::move(sources), mesh, sides, Vec3(0, 0, 10));
}

TEST(SplitLongEdges, SplitsTheUnitSquareLongestEdgeFirst) {
  // The diagonal (1.41) first: four triangles round the centre; then the
  // four sides (1.0): eight. Half-diagonals (0.71) and halves (0.5) stay.
  ConnectivityMesh mesh(square(0.5f));
  const size_t splits =
      split_long_edges(mesh, [](const Vec3& a, const Vec3& b) { return (b - a).norm() / 0.8f; }, 1000);
  EXPECT_EQ(splits, 5u);
  EXPECT_EQ(mesh.triangles().size(), 8u);
  EXPECT_EQ(mesh.vertices().size(), 9u);
  for (const MeshEdge& e : mesh.edges())
    EXPECT_LE((mesh.vertices()[e.vertices[1]].position - mesh.vertices()[e.vertices[0]].position).norm(), 0.8f);
}

TEST(SplitLongEdges, StopsAtTheTriangleLimit) {
  ConnectivityMesh mesh(square(0.5f));
  split_long_edges(mesh, [](const Vec3& a, const Vec3& b) { return (b - a).norm() / 0.01f; }, 100);
  EXPECT_GE(mesh.triangles().size(), 100u);
  EXPECT_LE(mesh.triangles().size(), 102u);  // one split adds at most two
}

TEST(NodeMesh, OneNodePerVertexAndSide) {
  EXPECT_EQ(NodeMesh(square(1), {0, 1}, square(1), NodeMesh::Sides::facing_viewpoint, Vec3(0, 0, 5)).nodes(), 4u);
  EXPECT_EQ(NodeMesh(square(1), {0, 1}, square(1), NodeMesh::Sides::both).nodes(), 8u);
}

TEST(NodeMesh, OneNodePerFaceWhereFacesMeetAtACrease) {
  // Each cube corner joins three faces at right angles: three nodes a side.
  std::vector<uint32_t> sources(12);
  for (uint32_t t = 0; t < 12; ++t) sources[t] = t;
  EXPECT_EQ(NodeMesh(cube(), sources, cube(), NodeMesh::Sides::both).nodes(), 8u * 3u * 2u);
}

TEST(NodeMesh, InterpolatesLinearlyAndPicksTheSide) {
  const NodeMesh mesh(square(1), {0, 1}, square(1), NodeMesh::Sides::both);
  std::vector<Vec3> values(mesh.nodes());
  for (size_t n = 0; n < values.size(); ++n) values[n] = Vec3::Constant(float(n));
  const Vec3 bary = mesh.barycentric(0, Vec3(0.5f, -0.5f, 0.0f));
  EXPECT_NEAR(bary.sum(), 1.0f, 1e-6f);
  const Vec3 front = mesh.interpolate(values, 0, bary, false), back = mesh.interpolate(values, 0, bary, true);
  EXPECT_NE(front.x(), back.x());
  // The corners' values weighted by the barycentric coordinates, on each side.
  const Vec3 at_corner = mesh.interpolate(values, 0, Vec3(1, 0, 0), false);
  EXPECT_EQ(mesh.interpolate(values, 1, Vec3(1, 0, 0), false), at_corner);  // corner 0 is shared
}

TEST(NodeMesh, TakesTheSideTheViewpointSeesFromTheFaceNotTheShadingNormal) {
  // Near a silhouette a smooth surface's shading normal can turn away from
  // the viewer while its face still faces it: the node must stay on the
  // face's seen side (+z here), not flip under the surface.
  TriangleMesh grazing = square(1);
  const Vec3 tilted = Vec3(0.99f, 0.0f, 0.14f).normalized();
  grazing.normals.assign(4, tilted);
  const NodeMesh mesh(grazing, {0, 1}, grazing, NodeMesh::Sides::facing_viewpoint, Vec3(-10, 0, 1));
  const SurfacePoint p = mesh.point_at(0, Vec3::Constant(1.0f / 3.0f), false);
  EXPECT_NEAR(p.normal.dot(tilted), 1.0f, 1e-5f);
  EXPECT_GT(p.geometric_normal.z(), 0.0f);
}

struct Solved {
  std::unique_ptr<NodeMesh> nodes;
  std::unique_ptr<RayScene> rays;
  std::vector<Vec3> irradiance;
};

// Solves the radiosity of `mesh` (split to `length`, both sides) under `lighting`.
Solved solve(const TriangleMesh& mesh, const RayScene& scene_rays, const Lighting& lighting,
             const RadiosityOptions& options, float length) {
  Solved s;
  s.nodes = std::make_unique<NodeMesh>(split_node_mesh(mesh, length, NodeMesh::Sides::both));
  s.rays = std::make_unique<RayScene>(s.nodes->mesh());
  RadiosityGather gather(*s.nodes, *s.nodes, *s.rays, scene_rays, lighting, options, Progress::silent(), "test");
  gather.set_albedo(WhiteAlbedo());
  solve_radiosity(gather, options, s.irradiance);
  return s;
}

// The solution's irradiance on the surface seen straight down from above (x, y).
Vec3 irradiance_below(const Solved& s, float x, float y) {
  SurfacePoint hit;
  EXPECT_TRUE(s.rays->intersect(Vec3(x, y, 5.0f), Vec3(0, 0, -1), hit));
  return s.nodes->interpolate(s.irradiance, hit.prim, s.nodes->barycentric(hit.prim, hit.position), false);
}

TEST(Radiosity, AnOpenPlaneUnderAUniformSkyGetsPiTimesItsRadiance) {
  const TriangleMesh plane = square(20.0f);
  const RayScene rays(plane);
  Lighting lighting;
  lighting.environment = Environment::constant(Vec3(1.0f, 0.5f, 0.25f));
  RadiosityOptions options;
  options.light_samples = 2048;
  const Solved s = solve(plane, rays, lighting, options, 10.0f);
  // Both sides see a whole hemisphere of the sky: E = pi L on every node
  // (each an estimate from its samples; their mean from all of them).
  Vec3 mean = Vec3::Zero();
  for (const Vec3& e : s.irradiance) {
    EXPECT_NEAR(e.x(), kPi, 0.05f * kPi);
    mean += e / float(s.irradiance.size());
  }
  EXPECT_NEAR(mean.x(), kPi, 0.01f * kPi);
  EXPECT_NEAR(mean.z(), 0.25f * kPi, 0.01f * 0.25f * kPi);
}

TEST(Radiosity, APointLightGivesTheInverseSquareIrradianceBelowIt) {
  const TriangleMesh plane = square(2.0f);
  const RayScene rays(plane);
  Lighting lighting;
  Light light;
  light.type = LightType::point;
  light.position = Vec3(0, 0, 3);
  light.power = 100.0f;
  lighting.lights = {light};
  RadiosityOptions options;
  options.light_samples = 256;  // spread over each node's triangles (its hat function)
  const Solved s = solve(plane, rays, lighting, options, 0.25f);
  // FORMAT.md: a point light of power P gives E = P cos / (4 pi d^2).
  const auto expected = [&](float x, float y) {
    const Vec3 to_light = light.position - Vec3(x, y, 0);
    const float d2 = to_light.squaredNorm();
    return light.power * (to_light.z() / std::sqrt(d2)) / (4.0f * kPi * d2);
  };
  for (const auto& [x, y] : {std::pair{0.0f, 0.0f}, {1.0f, 0.5f}, {-1.5f, 1.5f}})
    EXPECT_NEAR(irradiance_below(s, x, y).x(), expected(x, y), 0.02f * expected(x, y)) << x << " " << y;
}

TEST(Radiosity, BounceLightAgreesWithThePathTracer) {
  // A floor and a wall standing on it, lit by a low sun that reaches the
  // wall's face and the floor in front of it, under a dim sky: the floor by
  // the wall gets as much light again from the wall.
  TriangleMesh scene = square(2.0f);
  const uint32_t base = uint32_t(scene.positions.size());
  scene.positions.insert(scene.positions.end(), {{0, -2, 0}, {0, 2, 0}, {0, 2, 2}, {0, -2, 2}});
  scene.triangles.push_back({base, base + 1, base + 2});
  scene.triangles.push_back({base, base + 2, base + 3});
  const RayScene rays(scene);
  Lighting lighting;
  Light sun;
  sun.type = LightType::directional;
  sun.direction = Vec3(-1.0f, 0.0f, -0.6f).normalized();
  sun.irradiance = 3.0f;
  lighting.lights = {sun};
  lighting.environment = Environment::constant(Vec3::Constant(0.1f));
  RadiosityOptions options;
  options.max_bounces = 2;
  options.light_samples = 64;
  options.gather_rays = 512;
  const Solved s = solve(scene, rays, lighting, options, 0.2f);

  // The solution's last bounce is the view's final gather (RadiosityIllumination):
  // the scene nodes alone hold one bounce less.
  IntegratorOptions path_options;
  path_options.max_bounces = options.max_bounces - 1;
  path_options.roulette_after = 100;
  const Integrator path(rays, lighting, nullptr, path_options);
  for (const float x : {0.3f, 0.7f, 1.5f}) {
    SurfacePoint p;
    ASSERT_TRUE(rays.intersect(Vec3(x, 0.2f, 5.0f), Vec3(0, 0, -1), p));
    Vec3 sum = Vec3::Zero();
    const int paths = 40000;
    Rng rng(7, uint64_t(x * 1000));
    for (int i = 0; i < paths; ++i) sum += path.illumination(p, rng);
    const float expected = kPi * sum.x() / float(paths);
    EXPECT_NEAR(irradiance_below(s, x, 0.2f).x(), expected, 0.03f * expected) << "x = " << x;
  }
}

}  // namespace
}  // namespace relight
