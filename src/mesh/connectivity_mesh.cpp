#include "mesh/connectivity_mesh.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace relight {

namespace {

// Twice the signed area of triangle (a, b, p): > 0 when p is left of a->b.
double orient(const Vec2& a, const Vec2& b, const Vec2& p) {
  return (double(b.x()) - a.x()) * (double(p.y()) - a.y()) - (double(b.y()) - a.y()) * (double(p.x()) - a.x());
}

void replace_in(std::vector<uint32_t>& list, uint32_t from, uint32_t to) {
  std::replace(list.begin(), list.end(), from, to);
}

uint64_t edge_key(uint32_t a, uint32_t b) { return (uint64_t(std::min(a, b)) << 32) | std::max(a, b); }

// Maps each input vertex to the first vertex within `distance` of it (exact
// duplicates at 0), by hashing positions to a grid of that cell size.
std::vector<uint32_t> weld_map(const std::vector<Vec3>& positions, float distance) {
  struct CellHash {
    size_t operator()(const Eigen::Vector3i& c) const {
      return (size_t(uint32_t(c.x())) * 73856093u) ^ (size_t(uint32_t(c.y())) * 19349663u) ^
             (size_t(uint32_t(c.z())) * 83492791u);
    }
  };
  struct CellEq {
    bool operator()(const Eigen::Vector3i& a, const Eigen::Vector3i& b) const { return a == b; }
  };
  if (distance <= 0.0f) return same_position_ids(positions);
  std::vector<uint32_t> map(positions.size());
  std::unordered_map<Eigen::Vector3i, std::vector<uint32_t>, CellHash, CellEq> grid;
  for (size_t i = 0; i < positions.size(); ++i) {
    const Eigen::Vector3i cell = (positions[i] / distance).array().floor().cast<int>();
    map[i] = uint32_t(i);
    bool found = false;
    for (int dz = -1; dz <= 1 && !found; ++dz)
      for (int dy = -1; dy <= 1 && !found; ++dy)
        for (int dx = -1; dx <= 1 && !found; ++dx) {
          const auto it = grid.find(cell + Eigen::Vector3i(dx, dy, dz));
          if (it == grid.end()) continue;
          for (uint32_t j : it->second)
            if ((positions[j] - positions[i]).norm() <= distance) {
              map[i] = j;
              found = true;
              break;
            }
        }
    if (!found) grid[cell].push_back(uint32_t(i));
  }
  return map;
}

bool is_degenerate(const Vec3& a, const Vec3& b, const Vec3& c) {
  const float longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return (b - a).cross(c - a).norm() <= 1e-6f * longest;
}

}  // namespace

bool stays_on_side_of_edge(const Vec2& a, const Vec2& b, const Vec2& from, const Vec2& to) {
  const double before = orient(a, b, from), after = orient(a, b, to);
  return (before > 0 && after > 0) || (before < 0 && after < 0);
}

bool move_crosses_edge(const Vec2& a, const Vec2& b, const Vec2& from, const Vec2& to) {
  const double d1 = orient(a, b, from), d2 = orient(a, b, to);
  const double d3 = orient(from, to, a), d4 = orient(from, to, b);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  // Touching counts as crossing: a corner landing on the edge flattens the triangle.
  const auto on_segment = [](const Vec2& p, const Vec2& q, const Vec2& r) {
    return std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) && std::min(p.y(), q.y()) <= r.y() &&
           r.y() <= std::max(p.y(), q.y());
  };
  return (d1 == 0 && on_segment(a, b, from)) || (d2 == 0 && on_segment(a, b, to)) ||
         (d3 == 0 && on_segment(from, to, a)) || (d4 == 0 && on_segment(from, to, b));
}

ConnectivityMesh::ConnectivityMesh(const TriangleMesh& mesh, float weld_distance) {
  const std::vector<uint32_t> weld = weld_map(mesh.positions, weld_distance);
  std::vector<uint32_t> index(mesh.positions.size(), kNone);
  std::vector<Vec3> positions;
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    if (weld[i] == i) {
      index[i] = uint32_t(positions.size());
      positions.push_back(mesh.positions[i]);
    } else {
      ++cleanup_.welded_vertices;
    }
  std::vector<std::array<uint32_t, 3>> corners;
  std::vector<uint32_t> sources;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    std::array<uint32_t, 3> c;
    for (int k = 0; k < 3; ++k) c[k] = index[weld[mesh.triangles[t][k]]];
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0] ||
        is_degenerate(positions[c[0]], positions[c[1]], positions[c[2]])) {
      ++cleanup_.degenerate_triangles;
      continue;
    }
    corners.push_back(c);
    sources.push_back(uint32_t(t));
  }
  build(positions, corners, sources);
  for (const MeshEdge& e : edges_) cleanup_.non_manifold_edges += e.triangles.size() > 2;
}

void ConnectivityMesh::build(const std::vector<Vec3>& positions, const std::vector<std::array<uint32_t, 3>>& corners,
                             const std::vector<uint32_t>& sources) {
  vertices_.assign(positions.size(), {});
  for (size_t i = 0; i < positions.size(); ++i) vertices_[i].position = positions[i];
  edges_.clear();
  triangles_.clear();
  std::unordered_map<uint64_t, uint32_t> edge_of;
  for (size_t t = 0; t < corners.size(); ++t) {
    MeshTriangle tri{corners[t], {}, sources[t]};
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = corners[t][k], b = corners[t][(k + 1) % 3];
      auto [it, inserted] = edge_of.try_emplace(edge_key(a, b), uint32_t(edges_.size()));
      if (inserted) edges_.push_back({{a, b}, {}});
      tri.edges[k] = it->second;
      edges_[it->second].triangles.push_back(uint32_t(t));
      vertices_[a].triangles.push_back(uint32_t(t));
    }
    triangles_.push_back(tri);
  }
}

uint32_t ConnectivityMesh::add_edge(uint32_t a, uint32_t b) {
  edges_.push_back({{a, b}, {}});
  return uint32_t(edges_.size() - 1);
}

uint32_t ConnectivityMesh::find_edge(uint32_t a, uint32_t b) const {
  for (uint32_t t : vertices_[a].triangles)
    for (uint32_t e : triangles_[t].edges) {
      const auto& v = edges_[e].vertices;
      if ((v[0] == a && v[1] == b) || (v[0] == b && v[1] == a)) return e;
    }
  return kNone;
}

void ConnectivityMesh::edge_sources(uint32_t e, std::vector<uint32_t>& out) const {
  out.clear();
  for (uint32_t t : edges_[e].triangles) out.push_back(triangles_[t].source);
}

bool ConnectivityMesh::is_interior_vertex(uint32_t v) const {
  if (vertices_[v].triangles.empty()) return false;
  for (uint32_t t : vertices_[v].triangles)
    for (uint32_t e : triangles_[t].edges) {
      const auto& ends = edges_[e].vertices;
      if ((ends[0] == v || ends[1] == v) && edges_[e].triangles.size() != 2) return false;
    }
  return true;
}

uint32_t ConnectivityMesh::split_edge(uint32_t e, const Vec3& position) {
  const uint32_t a = edges_[e].vertices[0], b = edges_[e].vertices[1];
  const uint32_t m = uint32_t(vertices_.size());
  vertices_.push_back({position, {}});
  const uint32_t e2 = add_edge(m, b);
  edges_[e].vertices = {a, m};
  const std::vector<uint32_t> split = std::move(edges_[e].triangles);
  edges_[e].triangles.clear();
  for (uint32_t t : split) {
    // t = (p, q, c) with p-q the edge; it keeps (p, m, c), t2 gets (m, q, c).
    const MeshTriangle old = triangles_[t];
    int i = 0;
    while (old.edges[i] != e) ++i;
    const uint32_t p = old.vertices[i], q = old.vertices[(i + 1) % 3], c = old.vertices[(i + 2) % 3];
    const uint32_t qc = old.edges[(i + 1) % 3], cp = old.edges[(i + 2) % 3];
    const uint32_t t2 = uint32_t(triangles_.size());
    const uint32_t mc = add_edge(m, c);
    const uint32_t pm = p == a ? e : e2, mq = p == a ? e2 : e;
    triangles_[t] = {{p, m, c}, {pm, mc, cp}, old.source};
    triangles_.push_back({{m, q, c}, {mq, qc, mc}, old.source});
    edges_[pm].triangles.push_back(t);
    edges_[mq].triangles.push_back(t2);
    edges_[mc].triangles = {t, t2};
    replace_in(edges_[qc].triangles, t, t2);
    replace_in(vertices_[q].triangles, t, t2);
    vertices_[c].triangles.push_back(t2);
    vertices_[m].triangles.insert(vertices_[m].triangles.end(), {t, t2});
  }
  return m;
}

bool ConnectivityMesh::move_vertex(uint32_t v, const Vec3& position, const ToImage& to_image, FlipTest test) {
  const Vec2 from = to_image(vertices_[v].position), to = to_image(position);
  for (uint32_t t : vertices_[v].triangles) {
    const auto& c = triangles_[t].vertices;
    const int k = c[0] == v ? 0 : c[1] == v ? 1 : 2;
    const Vec2 a = to_image(vertices_[c[(k + 1) % 3]].position), b = to_image(vertices_[c[(k + 2) % 3]].position);
    const bool flips =
        test == FlipTest::side_of_edge ? !stays_on_side_of_edge(a, b, from, to) : move_crosses_edge(a, b, from, to);
    if (flips) return false;
  }
  vertices_[v].position = position;
  return true;
}

ConnectivityMesh::Parts ConnectivityMesh::compact(const std::function<bool(const MeshTriangle&)>& keep) const {
  Parts parts;
  std::vector<uint32_t> index(vertices_.size(), kNone);
  for (const MeshTriangle& t : triangles_) {
    if (!keep(t)) continue;
    std::array<uint32_t, 3> c;
    for (int k = 0; k < 3; ++k) {
      uint32_t& i = index[t.vertices[k]];
      if (i == kNone) {
        i = uint32_t(parts.positions.size());
        parts.positions.push_back(vertices_[t.vertices[k]].position);
      }
      c[k] = i;
    }
    parts.corners.push_back(c);
    parts.sources.push_back(t.source);
  }
  return parts;
}

void ConnectivityMesh::keep_triangles(const std::function<bool(const MeshTriangle&)>& keep) {
  const Parts parts = compact(keep);
  build(parts.positions, parts.corners, parts.sources);
}

TriangleMesh ConnectivityMesh::to_triangle_mesh(std::vector<uint32_t>* sources) const {
  Parts parts = compact([](const MeshTriangle&) { return true; });
  TriangleMesh mesh;
  mesh.positions = std::move(parts.positions);
  mesh.triangles = std::move(parts.corners);
  if (sources) *sources = std::move(parts.sources);
  return mesh;
}

}  // namespace relight
