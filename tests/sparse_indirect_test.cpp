// The environment and bounce light traced at every few pixels and
// interpolated along the surfaces (render_illumination.h): it gives what
// tracing every pixel gives, and a pole thinner than the stride, on which no
// traced pixel lies, traces its own rather than taking the floor's light.
#include <gtest/gtest.h>

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

}  // namespace
