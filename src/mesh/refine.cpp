#include "mesh/refine.h"

#include <chrono>

namespace relight {

ConnectivityMesh refine_mesh_for_photo(const TriangleMesh& input, const Camera& camera, const PhotoSamples& photo,
                                       const RefineOptions& options, RefineReport& report) {
  ConnectivityMesh mesh(input);
  const auto start = std::chrono::steady_clock::now();
  report.cleanup = mesh.cleanup();
  report.triangles_input = mesh.triangles().size();
  report.clip = clip_to_view(mesh, camera);
  report.triangles_clipped = mesh.triangles().size();
  if (options.max_edge_px > 0.0f) {
    // Every vertex is in front of the camera after clipping.
    const auto image = [&](const Vec3& p) { return camera.project(p).value_or(Vec2::Zero()); };
    report.long_edges_split = split_long_edges(
        mesh, [&](const Vec3& a, const Vec3& b) { return (image(b) - image(a)).norm() / options.max_edge_px; },
        options.subdivision.max_triangles);
  }
  report.subdivision = subdivide_along_shadows(mesh, camera, photo, options.subdivision);
  report.relax = relax_towards_shadow_edges(mesh, camera, photo, options.relax);
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return mesh;
}

}  // namespace relight
