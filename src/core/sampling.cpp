#include "core/sampling.h"

#include <algorithm>
#include <cmath>

namespace relight {

namespace {
// SplitMix64: turns structured seeds into well-mixed ones.
uint64_t mix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
}  // namespace

Rng::Rng(uint64_t seed, uint64_t a, uint64_t b) {
  state_ = mix64(seed ^ mix64(a ^ mix64(b)));
  inc_ = (mix64(a + 0x632be59bd9b4e019ULL) << 1u) | 1u;
  next_u32();
}

Vec2 hammersley(int i, int n) {
  uint32_t bits = uint32_t(i);
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return {(float(i) + 0.5f) / float(n), float(bits) * 2.3283064365386963e-10f};
}

Vec2 shifted(const Vec2& point, const Vec2& shift) {
  Vec2 p = point + shift;
  for (int k = 0; k < 2; ++k)
    if (p[k] >= 1.0f) p[k] -= 1.0f;
  return p.cwiseMin(0x1.fffffep-1f);  // float rounding must not reach 1
}

uint32_t Rng::next_u32() {
  const uint64_t old = state_;
  state_ = old * 6364136223846793005ULL + inc_;
  const uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
  const uint32_t rot = uint32_t(old >> 59u);
  return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
}

float Rng::uniform() { return std::min(float(next_u32()) * 0x1p-32f, 0x1.fffffep-1f); }

Vec2 sample_concentric_disc(const Vec2& u) {
  const Vec2 o = 2.0f * u - Vec2(1.0f, 1.0f);
  if (o.x() == 0.0f && o.y() == 0.0f) return Vec2::Zero();
  float r, theta;
  if (std::abs(o.x()) > std::abs(o.y())) {
    r = o.x();
    theta = (kPi / 4.0f) * (o.y() / o.x());
  } else {
    r = o.y();
    theta = kPi / 2.0f - (kPi / 4.0f) * (o.x() / o.y());
  }
  return r * Vec2(std::cos(theta), std::sin(theta));
}

Vec3 sample_cosine_hemisphere(const Vec2& u) {
  const Vec2 d = sample_concentric_disc(u);
  const float z = std::sqrt(std::max(0.0f, 1.0f - d.squaredNorm()));
  return {d.x(), d.y(), z};
}

Vec3 sample_uniform_sphere(const Vec2& u) {
  const float z = 1.0f - 2.0f * u.x();
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y();
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec3 sample_uniform_cone(const Vec2& u, float cos_max) {
  const float z = 1.0f - u.x() * (1.0f - cos_max);
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y();
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Distribution1D::Distribution1D(std::vector<float> weights) : weights_(std::move(weights)) {
  cdf_.resize(weights_.size() + 1);
  cdf_[0] = 0.0f;
  double acc = 0.0;
  for (size_t i = 0; i < weights_.size(); ++i) {
    weights_[i] = std::max(0.0f, weights_[i]);
    acc += weights_[i];
    cdf_[i + 1] = float(acc);
  }
  total_ = float(acc);
  const int n = int(weights_.size());
  guide_.resize(weights_.size());
  int bin = 0;
  for (int k = 0; k < n; ++k) {
    const float target = float(k) / float(n) * total_;
    while (bin + 1 < n && cdf_[size_t(bin) + 1] <= target) ++bin;
    guide_[size_t(k)] = bin;
  }
}

int Distribution1D::sample(float u, float& offset, float& pdf_out) const {
  const int n = int(weights_.size());
  if (total_ <= 0.0f) {  // degenerate: uniform
    const int bin = std::min(int(u * n), n - 1);
    offset = u * n - bin;
    pdf_out = 1.0f;
    return bin;
  }
  const float target = u * total_;
  // The first bin whose cdf passes target (upper_bound), from the guide on.
  int bin = guide_[size_t(std::clamp(int(u * float(n)), 0, n - 1))];
  while (bin > 0 && cdf_[size_t(bin)] > target) --bin;  // u * n and the guide's k / n round apart
  while (bin + 1 < n && cdf_[size_t(bin) + 1] <= target) ++bin;
  while (bin > 0 && weights_[bin] == 0.0f) --bin;  // never land in an empty bin
  const float w = weights_[bin];
  offset = w > 0.0f ? std::clamp((target - cdf_[bin]) / w, 0.0f, 0x1.fffffep-1f) : 0.5f;
  pdf_out = pdf(bin);
  return bin;
}

Distribution2D::Distribution2D(const std::vector<float>& weights, int width, int height)
    : width_(width), height_(height) {
  std::vector<float> row_totals(height);
  rows_.reserve(height);
  for (int y = 0; y < height; ++y) {
    rows_.emplace_back(std::vector<float>(weights.begin() + size_t(y) * width, weights.begin() + size_t(y + 1) * width));
    row_totals[y] = rows_.back().total();
  }
  marginal_ = Distribution1D(std::move(row_totals));
}

Vec2 Distribution2D::sample(const Vec2& u, float& pdf_out) const {
  float oy, py, ox, px;
  const int y = marginal_.sample(u.y(), oy, py);
  const int x = rows_[y].sample(u.x(), ox, px);
  pdf_out = py * px;
  // (cell + offset)/n can round up into the next cell in float: step back so
  // that pdf() reads back the sampled cell.
  const auto inside = [](int cell, float offset, int n) {
    float t = (cell + offset) / n;
    while (t > 0.0f && int(t * n) > cell) t = std::nextafter(t, 0.0f);
    return t;
  };
  return {inside(x, ox, width_), inside(y, oy, height_)};
}

float Distribution2D::pdf(const Vec2& uv) const {
  const int x = std::clamp(int(uv.x() * width_), 0, width_ - 1);
  const int y = std::clamp(int(uv.y() * height_), 0, height_ - 1);
  return marginal_.pdf(y) * rows_[y].pdf(x);
}

}  // namespace relight
