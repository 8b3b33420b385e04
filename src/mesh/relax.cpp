#include "mesh/relax.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace relight {

namespace {

// The plane of the vertex's triangles (normal, offset), if they all lie in one.
std::optional<std::pair<Vec3, float>> common_plane(const ConnectivityMesh& mesh, uint32_t v) {
  const Vec3 p = mesh.vertices()[v].position;
  std::optional<Vec3> normal;
  for (uint32_t t : mesh.vertices()[v].triangles) {
    const auto& c = mesh.triangles()[t].vertices;
    const Vec3 a = mesh.vertices()[c[0]].position, b = mesh.vertices()[c[1]].position,
               d = mesh.vertices()[c[2]].position;
    const Vec3 n = (b - a).cross(d - a).normalized();
    if (!normal)
      normal = n;
    else if (std::abs(normal->dot(n)) < 0.9999f)
      return std::nullopt;
  }
  return std::make_pair(*normal, normal->dot(p));
}

bool sees_vertex_surface(const ConnectivityMesh& mesh, uint32_t v, uint32_t seen) {
  for (uint32_t t : mesh.vertices()[v].triangles)
    if (mesh.triangles()[t].source == seen) return true;
  return false;
}

// Whether the vertex at `to` would stay at least half a pixel from the line
// of each opposite edge: a move the flip test allows could otherwise leave a
// triangle all but flat.
bool keeps_triangles_open(const ConnectivityMesh& mesh, uint32_t v, const Vec2& to, const ToImage& to_image) {
  for (uint32_t t : mesh.vertices()[v].triangles) {
    const auto& c = mesh.triangles()[t].vertices;
    const int k = c[0] == v ? 0 : c[1] == v ? 1 : 2;
    const Vec2 a = to_image(mesh.vertices()[c[(k + 1) % 3]].position);
    const Vec2 b = to_image(mesh.vertices()[c[(k + 2) % 3]].position);
    const Vec2 ab = b - a, at = to - a;
    if (std::abs(ab.x() * at.y() - ab.y() * at.x()) < 0.5f * ab.norm()) return false;
  }
  return true;
}

}  // namespace

std::vector<float> log_gradient_magnitude(const PhotoSamples& photo) {
  const int w = photo.width, h = photo.height;
  std::vector<float> log_i(photo.intensity.size());
  for (size_t i = 0; i < log_i.size(); ++i) log_i[i] = std::log(std::max(photo.intensity[i], 1e-6f));
  const auto at = [&](int x, int y) { return log_i[size_t(std::clamp(y, 0, h - 1)) * w + std::clamp(x, 0, w - 1)]; };
  std::vector<float> magnitude(log_i.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float gx = (at(x + 1, y - 1) + 2 * at(x + 1, y) + at(x + 1, y + 1)) -
                       (at(x - 1, y - 1) + 2 * at(x - 1, y) + at(x - 1, y + 1));
      const float gy = (at(x - 1, y + 1) + 2 * at(x, y + 1) + at(x + 1, y + 1)) -
                       (at(x - 1, y - 1) + 2 * at(x, y - 1) + at(x + 1, y - 1));
      magnitude[size_t(y) * w + x] = 0.125f * std::hypot(gx, gy);
    }
  return magnitude;
}

Eigen::Vector2i climb(const std::vector<float>& height, int width, int height_px, int x, int y, int max_steps) {
  for (int step = 0; step < max_steps; ++step) {
    int best_x = x, best_y = y;
    float best = height[size_t(y) * width + x];
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= width || ny >= height_px) continue;
        if (height[size_t(ny) * width + nx] > best) {
          best = height[size_t(ny) * width + nx];
          best_x = nx;
          best_y = ny;
        }
      }
    if (best_x == x && best_y == y) break;
    x = best_x;
    y = best_y;
  }
  return {x, y};
}

RelaxStats relax_towards_shadow_edges(ConnectivityMesh& mesh, const Camera& camera, const PhotoSamples& photo,
                                      const RelaxOptions& options) {
  RelaxStats stats;
  const std::vector<float> gradient = log_gradient_magnitude(photo);
  const ToImage to_image = [&](const Vec3& p) { return camera.project(p).value_or(Vec2(-1e9f, -1e9f)); };
  for (int pass = 0; pass < options.iterations; ++pass)
    for (uint32_t v = 0; v < mesh.vertices().size(); ++v) {
      if (!mesh.is_interior_vertex(v)) continue;
      const auto plane = common_plane(mesh, v);
      if (!plane) continue;  // a crease or corner of the geometry stays where it is
      const Vec2 at = to_image(mesh.vertices()[v].position);
      const int x = int(std::floor(at.x())), y = int(std::floor(at.y()));
      if (!photo.inside(x, y) || !sees_vertex_surface(mesh, v, photo.triangle_at(x, y))) continue;
      const Eigen::Vector2i top = climb(gradient, photo.width, photo.height, x, y, options.max_steps_px);
      if (top == Eigen::Vector2i(x, y) || !sees_vertex_surface(mesh, v, photo.triangle_at(top.x(), top.y()))) continue;
      // The point of the vertex's plane seen at the centre of the top pixel.
      const Vec3 dir = camera.ray_direction(top.x() + 0.5f, top.y() + 0.5f);
      const float along = dir.dot(plane->first);
      if (std::abs(along) < 1e-6f) continue;
      const float distance = (plane->second - plane->first.dot(camera.position())) / along;
      if (!(distance > 0)) continue;
      const Vec3 target = camera.position() + distance * dir;
      if (keeps_triangles_open(mesh, v, to_image(target), to_image) &&
          mesh.move_vertex(v, target, to_image, options.flip_test))
        ++stats.vertices_moved;
      else
        ++stats.moves_refused;
    }
  return stats;
}

}  // namespace relight
