#include "analysis/albedo_atlas.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace relight {

namespace {

constexpr int kMaxSide = 1024;  // texels along a triangle's grid

// Barycentric coordinates (of the triangle's second and third corners) of a
// point on the triangle's plane.
Vec2 barycentric(const TriangleMesh& mesh, uint32_t triangle, const Vec3& p) {
  const auto& t = mesh.triangles[triangle];
  const Vec3 a = mesh.positions[t[0]], e1 = mesh.positions[t[1]] - a, e2 = mesh.positions[t[2]] - a, d = p - a;
  const float d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2), d1 = d.dot(e1), d2 = d.dot(e2);
  const float det = d11 * d22 - d12 * d12;
  if (!(det > 0.0f)) return Vec2::Zero();  // a degenerate triangle: one texel will do
  return Vec2((d22 * d1 - d12 * d2) / det, (d11 * d2 - d12 * d1) / det);
}

}  // namespace

AlbedoAtlas::AlbedoAtlas(const TriangleMesh& mesh) : mesh_(mesh), side_(mesh.triangles.size(), 0) {}

void AlbedoAtlas::size_for(const PixelSurfaces& view, const Camera& camera) {
  if (!sum_.empty()) throw std::logic_error("AlbedoAtlas: every view is sized for before the first frame is added");
  // The smallest patch of each triangle a pixel covers: its distance times
  // the pixel's angle, squared, over the cosine of the grazing (a slant
  // surface's pixel covers more of it; at most 5 times).
  const float pixel_angle = radians(camera.spec().vfov_deg) / float(std::max(1, camera.height()));
  std::vector<float> smallest(side_.size(), std::numeric_limits<float>::infinity());
  for (size_t i = 0; i < view.surface.size(); ++i) {
    const SurfacePoint& s = view.surface[i];
    if (!view.hit[i] || s.prim >= smallest.size()) continue;
    const Vec3 towards = (s.position - camera.spec().position).normalized();
    const float grazing = std::max(0.2f, std::abs(towards.dot(s.geometric_normal)));
    const float footprint = (s.distance * pixel_angle) * (s.distance * pixel_angle) / grazing;
    smallest[s.prim] = std::min(smallest[s.prim], footprint);
  }
  // The used half of a side x side grid holds side^2 / 2 texels over the
  // triangle's area: a texel no larger than the smallest pixel's patch.
  for (size_t t = 0; t < side_.size(); ++t) {
    if (!std::isfinite(smallest[t])) continue;
    const auto& corners = mesh_.triangles[t];
    const Vec3 a = mesh_.positions[corners[0]];
    const double area = 0.5 * (mesh_.positions[corners[1]] - a).cross(mesh_.positions[corners[2]] - a).norm();
    const double side = std::ceil(std::sqrt(2.0 * area / std::max(double(smallest[t]), 1e-12)));
    side_[t] = uint16_t(std::max<double>(side_[t], std::clamp(side, 1.0, double(kMaxSide))));
  }
}

int64_t AlbedoAtlas::texel_of(const SurfacePoint& point) const {
  if (point.prim >= side_.size() || side_[point.prim] == 0) return -1;
  const int side = side_[point.prim];
  const Vec2 b = barycentric(mesh_, point.prim, point.position);
  const auto cell = [&](float x) { return std::clamp(int(std::floor(x * float(side))), 0, side - 1); };
  return int64_t(first_[point.prim]) + int64_t(cell(b.x())) * side + cell(b.y());
}

void AlbedoAtlas::add(const PixelSurfaces& view, const Image& albedo, std::span<const float> weight) {
  if (albedo.size() != view.surface.size() || weight.size() != view.surface.size())
    throw std::invalid_argument("AlbedoAtlas::add: the albedo and the weights are not the view's size");
  if (sum_.empty()) {
    first_.resize(side_.size());
    size_t n = 0;
    for (size_t t = 0; t < side_.size(); ++t) {
      first_[t] = uint32_t(n);
      n += size_t(side_[t]) * side_[t];
    }
    sum_.assign(n, Vec3::Zero());
    weight_.assign(n, 0.0f);
  }
  for (size_t i = 0; i < view.surface.size(); ++i) {
    if (!view.hit[i] || !(weight[i] > 0.0f) || !albedo.pixels[i].allFinite()) continue;
    const int64_t texel = texel_of(view.surface[i]);
    if (texel < 0) continue;
    sum_[size_t(texel)] += weight[i] * albedo.pixels[i];
    weight_[size_t(texel)] += weight[i];
  }
}

Image AlbedoAtlas::albedo_for(const PixelSurfaces& view, const Image& own) const {
  Image out = own;
  for (size_t i = 0; i < view.surface.size() && !sum_.empty(); ++i) {
    if (!view.hit[i]) continue;
    const int64_t texel = texel_of(view.surface[i]);
    if (texel >= 0 && weight_[size_t(texel)] > 0.0f) out.pixels[i] = sum_[size_t(texel)] / weight_[size_t(texel)];
  }
  return out;
}

std::vector<std::pair<size_t, size_t>> shared_points(const PixelSurfaces& a, const Camera& a_camera,
                                                     const PixelSurfaces& b) {
  std::vector<std::pair<size_t, size_t>> pairs;
  for (size_t j = 0; j < b.surface.size(); ++j) {
    if (!b.hit[j]) continue;
    const auto at = a_camera.project(b.surface[j].position);
    if (!at || !(at->x() >= 0.0f && at->y() >= 0.0f && at->x() < float(a.width) && at->y() < float(a.height))) continue;
    const size_t i = size_t(at->y()) * size_t(a.width) + size_t(at->x());
    if (a.hit[i] && a.surface[i].prim == b.surface[j].prim &&
        (a.surface[i].position - b.surface[j].position).norm() < 0.01f)
      pairs.emplace_back(i, j);
  }
  return pairs;
}

double change_at_shared_points(const Image& a, const Image& b, const std::vector<std::pair<size_t, size_t>>& pairs) {
  double change = 0.0, level = 0.0;
  for (const auto& [i, j] : pairs) {
    change += (a.pixels[i] - b.pixels[j]).cwiseAbs().mean();
    level += a.pixels[i].mean();
  }
  return level > 0.0 ? change / level : 0.0;
}

std::vector<float> albedo_weights(const Analysis& analysis) {
  const Image& light = analysis.illumination.surface;
  std::vector<float> weight(light.size(), 0.0f);
  for (size_t i = 0; i < weight.size(); ++i) {
    const float l = luminance(light.pixels[i]);
    const float c = i < analysis.coverage.size() ? analysis.coverage[i] : 1.0f;
    const bool off = i < analysis.albedo.edge_mismatch.size() && analysis.albedo.edge_mismatch[i];
    weight[i] = off || !std::isfinite(l) ? 0.0f : l * l * c * c;
  }
  return weight;
}

}  // namespace relight
