#include "mesh/clip.h"

#include <array>

namespace relight {

namespace {

// A half-space n.p + d >= 0 of the view.
struct Plane {
  Vec3 n;
  float d;
  float distance(const Vec3& p) const { return n.dot(p) + d; }
};

// The near plane and the four planes through the eye and the image borders,
// each facing into the view.
std::array<Plane, 5> view_planes(const Camera& camera, float near) {
  const Vec3 eye = camera.position();
  const float w = float(camera.width()), h = float(camera.height());
  const std::array<Vec3, 4> corner = {camera.ray_direction(0, 0), camera.ray_direction(w, 0),
                                      camera.ray_direction(w, h), camera.ray_direction(0, h)};
  const Vec3 centre = camera.ray_direction(0.5f * w, 0.5f * h);
  std::array<Plane, 5> planes;
  planes[0] = {camera.forward(), -camera.forward().dot(eye) - near};
  for (int k = 0; k < 4; ++k) {
    Vec3 n = corner[k].cross(corner[(k + 1) % 4]).normalized();
    if (n.dot(centre) < 0) n = -n;
    planes[k + 1] = {n, -n.dot(eye)};
  }
  return planes;
}

// Splits every edge whose ends lie strictly on opposite sides of the plane
// at the crossing; returns how many. The edges a split appends lie on one
// side, so one pass over the edges there were is enough.
size_t split_at_plane(ConnectivityMesh& mesh, const Plane& plane, float tolerance) {
  size_t splits = 0;
  const size_t edges = mesh.edges().size();
  for (size_t e = 0; e < edges; ++e) {
    const auto& ends = mesh.edges()[e].vertices;
    const Vec3 a = mesh.vertices()[ends[0]].position, b = mesh.vertices()[ends[1]].position;
    const float da = plane.distance(a), db = plane.distance(b);
    if (!((da > tolerance && db < -tolerance) || (da < -tolerance && db > tolerance))) continue;
    mesh.split_edge(uint32_t(e), a + (b - a) * (da / (da - db)));
    ++splits;
  }
  return splits;
}

}  // namespace

ClipStats clip_to_view(ConnectivityMesh& mesh, const Camera& camera, float near) {
  ClipStats stats;
  for (const Plane& plane : view_planes(camera, near)) {
    // Points within a micrometre-scale band count as on the plane, so no
    // sliver triangles are made along it.
    const float tolerance = 1e-6f * std::max(1.0f, std::abs(plane.d));
    stats.edges_split += split_at_plane(mesh, plane, tolerance);
    const size_t before = mesh.triangles().size();
    mesh.keep_triangles([&](const MeshTriangle& t) {
      for (uint32_t v : t.vertices)
        if (plane.distance(mesh.vertices()[v].position) > tolerance) return true;
      return false;
    });
    stats.triangles_dropped += before - mesh.triangles().size();
  }
  return stats;
}

}  // namespace relight
