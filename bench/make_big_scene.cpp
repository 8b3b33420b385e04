// Writes a large scene for measuring memory (docs/benchmarks.md, "Memory"):
// a rolling terrain of about TRIANGLES triangles seen from above by a camera
// whose photo is WIDTH x HEIGHT (a synthetic EXR), lit by a sun and a point
// light under a constant sky. Nothing is committed: write it to /tmp.
//   make_big_scene OUT_FOLDER [WIDTH HEIGHT TRIANGLES]   (default 3840 2160 1000000)
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/mesh_io.h"
#include "io/scene_io.h"

using namespace relight;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  if (argc != 2 && argc != 5) {
    std::fprintf(stderr, "usage: make_big_scene OUT_FOLDER [WIDTH HEIGHT TRIANGLES]\n");
    return 2;
  }
  const fs::path out = argv[1];
  const int width = argc == 5 ? std::stoi(argv[2]) : 3840, height = argc == 5 ? std::stoi(argv[3]) : 2160;
  const long triangles = argc == 5 ? std::stol(argv[4]) : 1000000;
  fs::create_directories(out);

  // An n x n grid of quads (2 triangles each) over [-10, 10]^2 m, gently rolling.
  const int n = int(std::ceil(std::sqrt(triangles / 2.0)));
  Scene scene;
  TriangleMesh& mesh = scene.mesh;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = -10.0f + 20.0f * i / n, y = -10.0f + 20.0f * j / n;
      mesh.positions.emplace_back(x, y, 0.4f * std::sin(1.3f * x) * std::cos(0.9f * y));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      mesh.triangles.push_back({a, b, d});
      mesh.triangles.push_back({a, d, c});
    }
  scene.geometry_path = out / "geometry.obj";
  save_obj(scene.geometry_path, mesh);

  // A smooth synthetic photo: any positive radiance does for measuring memory.
  Image photo(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      photo.at(x, y) = Vec3(0.2f + 0.1f * std::sin(x * 0.01f), 0.25f + 0.1f * std::cos(y * 0.013f), 0.2f);
  scene.photo_path = out / "photo.exr";
  write_exr(scene.photo_path, photo, ExrPrecision::half);

  CameraSpec camera;
  camera.position = Vec3(0, -9, 7);
  camera.look_at = Vec3(0, 0, 0);
  camera.up = Vec3(0, 0, 1);
  camera.vfov_deg = 45;
  scene.camera = Camera(camera, width, height);
  Light sun;
  sun.type = LightType::directional;
  sun.name = "sun";
  sun.direction = Vec3(-0.3f, 0.4f, -0.87f).normalized();
  sun.irradiance = 3.0f;
  Light lamp;
  lamp.name = "lamp";
  lamp.position = Vec3(2, -2, 3);
  lamp.power = 500.0f;
  scene.lights = {sun, lamp};
  scene.background = Vec3(0.3f, 0.35f, 0.45f);
  write_text_atomically(out / "scene.json", scene_to_json(scene, out));
  std::printf("%s: %dx%d photo, %zu triangles\n", (out / "scene.json").c_str(), width, height, mesh.triangles.size());
  return 0;
}
