// The environment and bounce light traced at every few pixels and
// interpolated along the surfaces (render_illumination.h): it gives what
// tracing every pixel gives, and a pole thinner than the stride, on which no
// traced pixel lies, traces its own rather than taking the floor's light.
// Along paths kept for light after light (KeptPaths), it gives what tracing
// each light's own paths gives. What a path costs follows the room.
#include <gtest/gtest.h>

#include <cstdio>

#include "render/render_illumination.h"

using namespace relight;

namespace {

constexpr int kW = 96, kH = 72, kPaths = 64;

void add_quad(TriangleMesh& mesh, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const auto base = uint32_t(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), {a, b, c, d});
  mesh.triangles.push_back({base, base + 1, base + 2});
  mesh.triangles.push_back({base, base + 2, base + 3});
}

// A floor 1 m below the camera (which looks along +y) and a pole 8 cm wide
// (columns 48.6 to 51.4: between the columns a stride of 5 traces, 47 and
// 52) 3 m ahead, facing the camera, under a white sky; light
// bounces off albedo 0.5. The floor sees the sky (~1), the pole half the sky
// and half the floor (~0.75).
struct PoleOnAFloor {
  static constexpr uint32_t kPoleTriangles[2] = {2, 3};
  TriangleMesh mesh;
  RayScene rays;
  GBuffer gbuffer;
  Lighting lighting{{}, Environment::constant(Vec3::Ones())};
  UniformAlbedo albedo{Vec3::Constant(0.5f)};
  Integrator integrator;

  PoleOnAFloor()
      : mesh(make_mesh()), rays(mesh), gbuffer(camera(), rays, 9, 1, "pole"), integrator(rays, lighting, &albedo) {}

  static Camera camera() { return Camera(CameraSpec{}, kW, kH); }
  static TriangleMesh make_mesh() {
    TriangleMesh m;
    add_quad(m, {-20, -1, -1}, {20, -1, -1}, {20, 40, -1}, {-20, 40, -1});        // normal +z
    add_quad(m, {0.02f, 3, -1}, {0.02f, 3, 10}, {0.10f, 3, 10}, {0.10f, 3, -1});  // normal -y
    return m;
  }
  bool on_pole(int x, int y) const {
    const GBufferSample s = gbuffer.central(x, y);
    return s.hit && s.surface.prim >= kPoleTriangles[0];
  }
  bool on_floor(int x, int y) const { return gbuffer.one_surface(x, y) && !on_pole(x, y); }

  Image render(int stride) const {
    IlluminationOptions options;
    options.paths_per_pixel = kPaths;
    options.indirect_stride = stride;
    return render_indirect_part(gbuffer, integrator, options, Progress::silent());
  }
};

TEST(SparseIndirect, GivesWhatTracingEveryPixelGives) {
  const PoleOnAFloor scene;
  const Image dense = scene.render(1), sparse = scene.render(3);
  double dense_sum = 0.0, sparse_sum = 0.0, squared_difference = 0.0;
  int n = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if (scene.on_floor(x, y)) {
        const double d = luminance(dense.at(x, y)), s = luminance(sparse.at(x, y));
        dense_sum += d;
        sparse_sum += s;
        squared_difference += (s - d) * (s - d);
        ++n;
      }
  ASSERT_GT(n, kW * kH / 3);
  EXPECT_NEAR(sparse_sum / dense_sum, 1.0, 0.01);
  const double rms = std::sqrt(squared_difference / n) / (dense_sum / n);
  EXPECT_LT(rms, 0.03) << "relative rms difference per pixel";
}

TEST(SparseIndirect, APoleThinnerThanTheStrideTracesItsOwn) {
  const PoleOnAFloor scene;
  const Image dense = scene.render(1), sparse = scene.render(5);
  double dense_pole = 0.0, sparse_pole = 0.0, floor = 0.0;
  int poles = 0, floors = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if (scene.on_pole(x, y) && scene.gbuffer.one_surface(x, y)) {
        dense_pole += luminance(dense.at(x, y));
        sparse_pole += luminance(sparse.at(x, y));
        ++poles;
      } else if (scene.on_floor(x, y)) {
        floor += luminance(dense.at(x, y));
        ++floors;
      }
  ASSERT_GT(poles, 10);
  dense_pole /= poles;
  sparse_pole /= poles;
  floor /= floors;
  EXPECT_LT(dense_pole, 0.9 * floor) << "the pole sees less sky than the floor";
  EXPECT_NEAR(sparse_pole / dense_pole, 1.0, 0.03) << "the floor's light taken for the pole's";
}

// A closed room around the camera, light bouncing off albedo 0.6: most of
// a point light's bounce light has bounced more than once.
struct ClosedRoom {
  TriangleMesh mesh;
  RayScene rays;
  GBuffer gbuffer;
  UniformAlbedo albedo{Vec3::Constant(0.6f)};

  ClosedRoom() : mesh(make_mesh()), rays(mesh), gbuffer(PoleOnAFloor::camera(), rays, 4, 1, "room") {}

  static TriangleMesh make_mesh() {  // x -2..2, y -1..5, z -1..2, every face's normal inwards
    TriangleMesh m;
    add_quad(m, {-2, -1, -1}, {2, -1, -1}, {2, 5, -1}, {-2, 5, -1});  // floor
    add_quad(m, {-2, -1, 2}, {-2, 5, 2}, {2, 5, 2}, {2, -1, 2});      // ceiling
    add_quad(m, {-2, 5, -1}, {2, 5, -1}, {2, 5, 2}, {-2, 5, 2});      // back
    add_quad(m, {-2, -1, -1}, {-2, -1, 2}, {2, -1, 2}, {2, -1, -1});  // front
    add_quad(m, {-2, -1, -1}, {-2, 5, -1}, {-2, 5, 2}, {-2, -1, 2});  // left
    add_quad(m, {2, -1, -1}, {2, -1, 2}, {2, 5, 2}, {2, 5, -1});      // right
    return m;
  }
  static Lighting bulb_at(const Vec3& position) {
    Light bulb;
    bulb.position = position;
    bulb.power = 100.0f;
    bulb.radius = 0.05f;
    return {{bulb}};
  }
};

// KeptPaths: the paths traced once, without lights, then the bounce light of
// a bulb in one place and another along them gives what tracing the paths
// for each gives.
TEST(KeptPaths, GiveEachLightsBounceLightAsTracingItsOwnPathsDoes) {
  const ClosedRoom room;
  IlluminationOptions options;
  options.paths_per_pixel = kPaths;
  options.indirect_stride = 2;
  const Lighting no_lights;  // the integrator keeps a reference
  const Integrator unlit(room.rays, no_lights, &room.albedo);
  const KeptPaths kept(room.gbuffer, unlit, options, Progress::silent());
  EXPECT_GT(kept.bytes(), size_t(kW / 2) * (kH / 2) * kPaths * sizeof(Integrator::PathVertex));  // > 1 vertex a path
  // Two renders' relative rms difference per pixel, and their means' ratio.
  const auto compare = [](const Image& a, const Image& b, double& rms) {
    double a_sum = 0.0, b_sum = 0.0, squared_difference = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
      const double u = luminance(a.pixels[i]), v = luminance(b.pixels[i]);
      a_sum += u;
      b_sum += v;
      squared_difference += (u - v) * (u - v);
    }
    rms = std::sqrt(squared_difference / double(a.size())) / (b_sum / double(a.size()));
    return a_sum / b_sum;
  };
  for (const Vec3& place : {Vec3(-1.0f, 3.0f, 1.0f), Vec3(1.5f, 1.0f, -0.5f)}) {
    const Lighting bulb = ClosedRoom::bulb_at(place);
    const Integrator lit(room.rays, bulb, &room.albedo);
    const Image traced = render_indirect_part(room.gbuffer, lit, options, Progress::silent());
    const Image along_kept =
        render_indirect_part(room.gbuffer, lit, options, Progress::silent(), "illumination", &kept);
    IlluminationOptions other_seed = options;
    other_seed.seed = 2;
    const Image traced_again = render_indirect_part(room.gbuffer, lit, other_seed, Progress::silent());
    double kept_rms, noise_rms;
    EXPECT_NEAR(compare(along_kept, traced, kept_rms), 1.0, 0.02) << "bulb at " << place.transpose();
    compare(traced_again, traced, noise_rms);
    // As far from the traced render as another seed's: the noise, no more.
    EXPECT_LT(kept_rms, 1.2 * noise_rms) << "bulb at " << place.transpose();
    EXPECT_GT(noise_rms, 0.0);
  }
  // Paths that would take more than their budget are not kept.
  const KeptPaths over(room.gbuffer, unlit, options, Progress::silent(), kept.bytes() / 2);
  EXPECT_FALSE(over.within_budget());
  EXPECT_LE(over.bytes(), kept.bytes() / 2);
  EXPECT_THROW(
      render_indirect_part(room.gbuffer, Integrator(room.rays, ClosedRoom::bulb_at(Vec3(0, 2, 0)), &room.albedo),
                           options, Progress::silent(), "illumination", &over),
      std::logic_error);
  EXPECT_TRUE(kept.within_budget());
  // Paths of another render's pixels are refused, not misread.
  options.indirect_stride = 3;
  EXPECT_THROW(
      render_indirect_part(room.gbuffer, Integrator(room.rays, ClosedRoom::bulb_at(Vec3(0, 2, 0)), &room.albedo),
                           options, Progress::silent(), "illumination", &kept),
      std::logic_error);
}

// What a path costs (mean_path_vertices, for an analysis's time left): in
// a closed room a path meets a surface after its first and bounces on,
// the more the brighter the walls; under an open sky it leaves; where every
// surface's radiance is known it ends at the first it meets.
struct EveryRadianceKnown : KnownRadiance {
  std::optional<Vec3> at(const SurfacePoint&) const override { return Vec3::Constant(0.5f); }
};

TEST(PathLengths, FollowTheRoomAndWhatIsKnown) {
  const ClosedRoom room;
  const Lighting bulb = ClosedRoom::bulb_at({0, 2, 1});
  const UniformAlbedo bright(Vec3::Constant(0.9f));
  const EveryRadianceKnown known;
  const double dim_room = mean_path_vertices(room.gbuffer, Integrator(room.rays, bulb, &room.albedo), 2000, 1),
               bright_room = mean_path_vertices(room.gbuffer, Integrator(room.rays, bulb, &bright), 2000, 1),
               known_room =
                   mean_path_vertices(room.gbuffer, Integrator(room.rays, bulb, &room.albedo, {}, &known), 2000, 1);
  const PoleOnAFloor open;
  const double open_floor = mean_path_vertices(open.gbuffer, open.integrator, 2000, 1);
  std::printf(
      "[ figures  ] mean vertices a path: room of albedo 0.6 %.2f, 0.9 %.2f, its radiance known %.2f; "
      "a floor under the sky %.2f\n",
      dim_room, bright_room, known_room, open_floor);
  EXPECT_GT(dim_room, 1.5);  // the first wall met, then at least every other bounce survives
  EXPECT_GT(bright_room, 2.0 * dim_room);
  EXPECT_EQ(known_room, 0.0);
  EXPECT_LT(open_floor, 0.1);  // the pole, seen from a few of the floor's pixels
}

}  // namespace
