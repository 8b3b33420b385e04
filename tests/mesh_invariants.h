// A check of ConnectivityMesh's connectivity, shared by the mesh tests:
// every triangle's edges join its corners and list it, every edge's
// triangles have it, every vertex lists exactly the triangles it is a corner of.
#pragma once

#include <algorithm>
#include <string>

#include "mesh/connectivity_mesh.h"
#include "scene/camera.h"

namespace relight::test {

inline std::string connectivity_errors(const ConnectivityMesh& mesh) {
  std::string errors;
  const auto has = [](const std::vector<uint32_t>& list, uint32_t x) {
    return std::count(list.begin(), list.end(), x) == 1;
  };
  for (uint32_t t = 0; t < mesh.triangles().size(); ++t) {
    const MeshTriangle& tri = mesh.triangles()[t];
    for (int k = 0; k < 3; ++k) {
      const MeshEdge& e = mesh.edges()[tri.edges[k]];
      const uint32_t a = tri.vertices[k], b = tri.vertices[(k + 1) % 3];
      if (!((e.vertices[0] == a && e.vertices[1] == b) || (e.vertices[0] == b && e.vertices[1] == a)))
        errors += "triangle " + std::to_string(t) + " edge " + std::to_string(k) + " joins other vertices; ";
      if (!has(e.triangles, t))
        errors += "edge " + std::to_string(tri.edges[k]) + " misses triangle " + std::to_string(t) + "; ";
      if (!has(mesh.vertices()[a].triangles, t))
        errors += "vertex " + std::to_string(a) + " misses triangle " + std::to_string(t) + "; ";
    }
  }
  for (uint32_t e = 0; e < mesh.edges().size(); ++e)
    for (uint32_t t : mesh.edges()[e].triangles)
      if (std::count(mesh.triangles()[t].edges.begin(), mesh.triangles()[t].edges.end(), e) != 1)
        errors += "edge " + std::to_string(e) + " lists triangle " + std::to_string(t) + " not on it; ";
  for (uint32_t v = 0; v < mesh.vertices().size(); ++v)
    for (uint32_t t : mesh.vertices()[v].triangles)
      if (std::count(mesh.triangles()[t].vertices.begin(), mesh.triangles()[t].vertices.end(), v) != 1)
        errors += "vertex " + std::to_string(v) + " lists triangle " + std::to_string(t) + " not on it; ";
  return errors;
}

// The z component of a triangle's normal (twice its signed area in xy).
inline float signed_area_xy(const ConnectivityMesh& mesh, uint32_t t) {
  const auto& c = mesh.triangles()[t].vertices;
  const Vec3 a = mesh.vertices()[c[0]].position, b = mesh.vertices()[c[1]].position, d = mesh.vertices()[c[2]].position;
  return (b - a).cross(d - a).z();
}

// Looking straight down from 5 m, 90 degrees, 100 x 100 pixels: the image
// shows exactly x, y in [-5, 5] of the plane z = 0; pixel x shows
// X = (x / 50 - 1) * 5, pixel y shows Y = (1 - y / 50) * 5.
inline Camera top_view() {
  CameraSpec spec;
  spec.position = {0, 0, 5};
  spec.look_at = {0, 0, 0};
  spec.up = {0, 1, 0};
  spec.vfov_deg = 90;
  return Camera(spec, 100, 100);
}

}  // namespace relight::test
