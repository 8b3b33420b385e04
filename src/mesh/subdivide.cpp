#include "mesh/subdivide.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <deque>
#include <queue>

namespace relight {

namespace {

double mean_intensity(std::span<const LineSample> samples) {
  double sum = 0;
  for (const LineSample& s : samples) sum += s.intensity;
  return sum / double(samples.size());
}

// The candidate with the largest residual from the fitted line, if that
// residual (relative to the mean) is over the threshold.
std::optional<float> largest_fit_error(std::span<const LineSample> samples, float lo, float hi, double mean,
                                       const SubdivisionOptions& options) {
  const LineFit fit = fit_line(samples);
  double worst = -1;
  float at = 0;
  for (const LineSample& s : samples) {
    if (s.distance < lo || s.distance > hi) continue;
    const double error = std::abs(s.intensity - fit.a - fit.b * s.distance);
    if (error > worst) {
      worst = error;
      at = s.distance;
    }
  }
  if (worst > options.threshold * mean) return at;
  return std::nullopt;
}

double standard_deviation(std::span<const LineSample> samples) {
  // Eq. 4.1: sigma^2 = (N sum x^2 - (sum x)^2) / N^2.
  double sum = 0, sum2 = 0;
  for (const LineSample& s : samples) {
    sum += s.intensity;
    sum2 += double(s.intensity) * s.intensity;
  }
  const double n = double(samples.size());
  return std::sqrt(std::max(0.0, n * sum2 - sum * sum) / (n * n));
}

// Whether splitting edge e at the image fraction s leaves every half of its
// triangles at least min_edge_px^2 / 2 in image area. Without this bound the
// edges a split adds inside a thin triangle (a column's facet one pixel
// wide) would be split again and again, each time thinner.
bool halves_large_enough(const ConnectivityMesh& mesh, const std::vector<Vec2>& image, uint32_t e, float s,
                         float min_edge_px) {
  const float min_area = 0.5f * min_edge_px * min_edge_px;
  for (uint32_t t : mesh.edges()[e].triangles) {
    const auto& c = mesh.triangles()[t].vertices;
    const Vec2 u = image[c[1]] - image[c[0]], v = image[c[2]] - image[c[0]];
    const float area = 0.5f * std::abs(u.x() * v.y() - u.y() * v.x());
    if (std::min(s, 1.0f - s) * area < min_area) return false;
  }
  return true;
}

}  // namespace

LineFit fit_line(std::span<const LineSample> samples) {
  // The normal equations 4.3-4.4: [n, sum x; sum x, sum x^2] [a; b] = [sum y; sum xy].
  double sx = 0, sxx = 0, sy = 0, sxy = 0;
  for (const LineSample& s : samples) {
    sx += s.distance;
    sxx += double(s.distance) * s.distance;
    sy += s.intensity;
    sxy += double(s.distance) * s.intensity;
  }
  const Eigen::Matrix2d m{{double(samples.size()), sx}, {sx, sxx}};
  const Eigen::Vector2d ab = m.ldlt().solve(Eigen::Vector2d(sy, sxy));
  return {ab.x(), ab.y()};
}

std::optional<float> find_split(std::span<const LineSample> samples, float length_px,
                                const SubdivisionOptions& options) {
  const float margin = std::max(2.0f, options.min_edge_px);
  if (length_px < 2.0f * margin || samples.size() < 3) return std::nullopt;
  const double mean = mean_intensity(samples);
  if (!(mean > 0)) return std::nullopt;
  switch (options.criterion) {
    case SplitCriterion::line_fit:
      return largest_fit_error(samples, margin, length_px - margin, mean, options);
    case SplitCriterion::compare_end_points:
      if (std::abs(samples.front().intensity - samples.back().intensity) > options.threshold * mean)
        return 0.5f * length_px;
      return std::nullopt;
    case SplitCriterion::standard_deviation:
      if (standard_deviation(samples) > options.threshold * mean) return 0.5f * length_px;
      return std::nullopt;
  }
  return std::nullopt;
}

void read_line(const PhotoSamples& photo, const Vec2& from, const Vec2& to, std::span<const uint32_t> visible,
               std::vector<LineSample>& out) {
  out.clear();
  const Vec2 d = to - from;
  const float length = d.norm();
  if (!(length > 0)) return;
  const Vec2 dir = d / length;
  walk_visible_pixels(photo, from, to, visible, [&](int x, int y) {
    const float along = (Vec2(x + 0.5f, y + 0.5f) - from).dot(dir);
    out.push_back({std::clamp(along, 0.0f, length), photo.intensity_at(x, y)});
  });
}

Vec3 point_at_image_fraction(const Camera& camera, const Vec3& a, const Vec3& b, float s) {
  // Image positions interpolate linearly in 1/depth: the image fraction s is
  // the 3D fraction t = s za / ((1 - s) zb + s za).
  const float za = camera.forward().dot(a - camera.position()), zb = camera.forward().dot(b - camera.position());
  const float t = s * za / ((1.0f - s) * zb + s * za);
  return a + t * (b - a);
}

SubdivisionStats subdivide_along_shadows(ConnectivityMesh& mesh, const Camera& camera, const PhotoSamples& photo,
                                         const SubdivisionOptions& options) {
  SubdivisionStats stats;
  std::vector<Vec2> image;  // each vertex's image position
  const auto project = [&](uint32_t v) {
    image.push_back(camera.project(mesh.vertices()[v].position).value_or(Vec2(-1e9f, -1e9f)));
  };
  for (uint32_t v = 0; v < mesh.vertices().size(); ++v) project(v);

  std::deque<uint32_t> queue;
  for (uint32_t e = 0; e < mesh.edges().size(); ++e) queue.push_back(e);
  std::vector<LineSample> samples;
  std::vector<uint32_t> visible;
  while (!queue.empty() && mesh.triangles().size() < options.max_triangles) {
    const uint32_t e = queue.front();
    queue.pop_front();
    const MeshEdge& edge = mesh.edges()[e];
    const Vec2 p0 = image[edge.vertices[0]], p1 = image[edge.vertices[1]];
    const float length = (p1 - p0).norm();
    if (length < 2.0f * std::max(2.0f, options.min_edge_px)) continue;
    mesh.edge_sources(e, visible);
    read_line(photo, p0, p1, visible, samples);
    ++stats.edges_tested;
    const std::optional<float> at = find_split(samples, length, options);
    if (!at) continue;
    if (!halves_large_enough(mesh, image, e, *at / length, options.min_edge_px)) continue;
    const Vec3 a = mesh.vertices()[edge.vertices[0]].position, b = mesh.vertices()[edge.vertices[1]].position;
    const size_t first_new_edge = mesh.edges().size();
    project(mesh.split_edge(e, point_at_image_fraction(camera, a, b, *at / length)));
    ++stats.edges_split;
    queue.push_back(e);
    for (size_t n = first_new_edge; n < mesh.edges().size(); ++n) queue.push_back(uint32_t(n));
  }
  return stats;
}

size_t split_long_edges(ConnectivityMesh& mesh, const EdgeExcess& excess, size_t max_triangles) {
  const auto excess_of = [&](uint32_t e) {
    const auto& ends = mesh.edges()[e].vertices;
    return excess(mesh.vertices()[ends[0]].position, mesh.vertices()[ends[1]].position);
  };
  // Longest first: a split then adds edges (to the opposite corners) shorter
  // than the triangles' other sides, so it ends; in any order, splitting
  // short sides of thin triangles makes more long edges without end.
  std::priority_queue<std::pair<float, uint32_t>> queue;
  for (uint32_t e = 0; e < mesh.edges().size(); ++e) queue.emplace(excess_of(e), e);
  size_t splits = 0;
  while (!queue.empty() && queue.top().first > 1.0f && mesh.triangles().size() < max_triangles) {
    const uint32_t e = queue.top().second;
    queue.pop();
    const auto& ends = mesh.edges()[e].vertices;
    const size_t first_new_edge = mesh.edges().size();
    mesh.split_edge(e, 0.5f * (mesh.vertices()[ends[0]].position + mesh.vertices()[ends[1]].position));
    ++splits;
    queue.emplace(excess_of(e), e);
    for (size_t n = first_new_edge; n < mesh.edges().size(); ++n) queue.emplace(excess_of(uint32_t(n)), uint32_t(n));
  }
  return splits;
}

}  // namespace relight
