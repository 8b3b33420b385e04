// ConnectivityMesh: the mesh the image-based refinement works on (thesis
// 4.1). Vertices know their triangles, edges their two end vertices and the
// triangles on them, triangles their three vertices and edges. Supports the
// two operations of refinement, edge split and vertex move (refused when it
// would flip a triangle in the image), and cleans its input: duplicate
// vertices are welded, degenerate triangles dropped, non-manifold edges (on
// three or more triangles) kept and counted.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "scene/triangle_mesh.h"

namespace relight {

struct MeshVertex {
  Vec3 position;
  std::vector<uint32_t> triangles;  // triangles it is a corner of
};

struct MeshEdge {
  std::array<uint32_t, 2> vertices;
  std::vector<uint32_t> triangles;  // 1: boundary, 2: manifold, more: non-manifold
};

struct MeshTriangle {
  std::array<uint32_t, 3> vertices;  // counter-clockwise as in the input
  std::array<uint32_t, 3> edges;     // edges[i] joins vertices[i] and vertices[(i + 1) % 3]
  uint32_t source;                   // the input triangle it was cut from
};

// What building the mesh cleaned up.
struct MeshCleanup {
  size_t welded_vertices = 0;       // input vertices merged into another
  size_t degenerate_triangles = 0;  // dropped: repeated corners or zero area
  size_t non_manifold_edges = 0;    // edges on three or more triangles (kept)
};

// The two tests of thesis Fig. 4.13 for a corner moving from `from` to `to`
// in the image, against the opposite edge a-b of one of its triangles.
// Side of edge: true when `to` stays strictly on the side of line a-b that
// `from` is on (the triangle keeps its orientation).
bool stays_on_side_of_edge(const Vec2& a, const Vec2& b, const Vec2& from, const Vec2& to);
// Segment intersection: true when the move's segment meets segment a-b.
bool move_crosses_edge(const Vec2& a, const Vec2& b, const Vec2& from, const Vec2& to);

enum class FlipTest { side_of_edge, segment_intersection };

// Maps a world point to the image plane for the flip tests.
using ToImage = std::function<Vec2(const Vec3&)>;

class ConnectivityMesh {
 public:
  // Welds vertices closer than weld_distance (exact duplicates at 0), drops
  // degenerate triangles; triangle i of `mesh` is the source of what it becomes.
  explicit ConnectivityMesh(const TriangleMesh& mesh, float weld_distance = 0.0f);

  const std::vector<MeshVertex>& vertices() const { return vertices_; }
  const std::vector<MeshEdge>& edges() const { return edges_; }
  const std::vector<MeshTriangle>& triangles() const { return triangles_; }
  const MeshCleanup& cleanup() const { return cleanup_; }

  // The edge joining vertices a and b, or kNone.
  static constexpr uint32_t kNone = UINT32_MAX;
  uint32_t find_edge(uint32_t a, uint32_t b) const;
  // The input triangles an edge lies on (what a pixel showing it may see).
  void edge_sources(uint32_t e, std::vector<uint32_t>& out) const;
  // On the mesh boundary or a non-manifold edge: not free to move.
  bool is_interior_vertex(uint32_t v) const;

  // Splits edge `e` at `position` (a point on it): the new vertex's index is
  // returned; every triangle on the edge becomes two, edge `e` keeps its
  // first end vertex, the other half and the edges to the opposite corners
  // are appended.
  uint32_t split_edge(uint32_t e, const Vec3& position);

  // Moves vertex v to `position` unless, seen through to_image, the move
  // would flip one of its triangles under the chosen test; returns whether it moved.
  bool move_vertex(uint32_t v, const Vec3& position, const ToImage& to_image, FlipTest test);

  // Drops the triangles for which keep() is false, and the vertices and
  // edges left without triangles (indices are renumbered).
  void keep_triangles(const std::function<bool(const MeshTriangle&)>& keep);

  // The plain triangle mesh (unused vertices left out), triangles in the
  // same order; with `sources`, each triangle's input triangle too.
  TriangleMesh to_triangle_mesh(std::vector<uint32_t>* sources = nullptr) const;

 private:
  // The kept triangles' vertices, corners (renumbered) and sources.
  struct Parts {
    std::vector<Vec3> positions;
    std::vector<std::array<uint32_t, 3>> corners;
    std::vector<uint32_t> sources;
  };
  Parts compact(const std::function<bool(const MeshTriangle&)>& keep) const;
  void build(const std::vector<Vec3>& positions, const std::vector<std::array<uint32_t, 3>>& corners,
             const std::vector<uint32_t>& sources);
  uint32_t add_edge(uint32_t a, uint32_t b);

  std::vector<MeshVertex> vertices_;
  std::vector<MeshEdge> edges_;
  std::vector<MeshTriangle> triangles_;
  MeshCleanup cleanup_;
};

}  // namespace relight
