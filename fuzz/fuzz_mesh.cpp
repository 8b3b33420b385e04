// Fuzzes mesh loading through load_mesh (Assimp underneath). The first byte
// picks the file's extension, the rest is its content. A mesh that loads
// must be what the ray tracer can take: triangles, indices in range, finite
// bounded vertices, no degenerate triangle left.
#include "fuzz_support.h"
#include "io/mesh_io.h"

namespace fs = std::filesystem;
using namespace relight;
using relight::fuzz::check;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  static const char* const kExtensions[] = {".obj", ".ply", ".stl", ".off", ".gltf", ".glb"};
  const std::string name = std::string("mesh") + kExtensions[data[0] % 6];
  const fs::path path = fuzz::write_input(name, {reinterpret_cast<const char*>(data) + 1, size - 1});
  TriangleMesh mesh;
  if (!fuzz::loads_or_rejects([&] { mesh = load_mesh(path); })) return 0;

  check(!mesh.triangles.empty(), "a loaded mesh has triangles");
  check(mesh.normals.empty() || mesh.normals.size() == mesh.positions.size(), "one normal per vertex, or none");
  for (const auto& t : mesh.triangles)
    for (uint32_t i : t) check(i < mesh.positions.size(), "every index names a vertex");
  for (const Vec3& p : mesh.positions) check(is_finite(p) && p.cwiseAbs().maxCoeff() <= 1.0e7f, "vertices are finite metres");
  check(degenerate_triangles(mesh).empty(), "no degenerate triangle is left");
  return 0;
}
