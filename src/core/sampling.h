// Random numbers and sampling: a counter-based generator (so every pixel's
// stream depends only on the seed and the pixel, whatever the thread count),
// the standard warps, and piecewise-constant 1D/2D distributions for
// importance-sampling images.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec.h"

namespace relight {

// PCG32 (O'Neill 2014): small, fast, statistically good.
class Rng {
 public:
  // A stream fixed by (seed, a, b): e.g. (seed, pixel index, pass).
  Rng(uint64_t seed, uint64_t a, uint64_t b = 0);
  uint32_t next_u32();
  // Uniform in [0, 1).
  float uniform();
  Vec2 uniform2() { return {uniform(), uniform()}; }

 private:
  uint64_t state_, inc_;
};

// Hammersley point i of n in [0,1)^2: n well-spread points (each of n
// equal rows holds one, and so does each of the radical inverse's cells).
Vec2 hammersley(int i, int n);
// The point shifted by `shift` modulo 1 (Cranley-Patterson rotation): a
// random shift per use keeps the spread and removes the bias of fixed points.
Vec2 shifted(const Vec2& point, const Vec2& shift);

// Cosine-weighted direction about +z; pdf = cos(theta)/pi.
Vec3 sample_cosine_hemisphere(const Vec2& u);
// Uniform point on the unit disc (concentric map).
Vec2 sample_concentric_disc(const Vec2& u);
// Uniform direction on the unit sphere; pdf = 1/(4 pi).
Vec3 sample_uniform_sphere(const Vec2& u);
// Uniform direction in the cone of half-angle acos(cos_max) about +z.
Vec3 sample_uniform_cone(const Vec2& u, float cos_max);

inline float power_heuristic(float pdf_a, float pdf_b) {
  const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

// Piecewise-constant distribution over n equal bins of [0, 1).
class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(std::vector<float> weights);
  // Returns the bin; `offset` in [0,1) is the position inside it, `pdf` the
  // density on [0,1).
  int sample(float u, float& offset, float& pdf) const;
  float pdf(int bin) const { return total_ > 0 ? weights_[bin] * float(weights_.size()) / total_ : 0.0f; }
  float total() const { return total_; }
  int size() const { return int(weights_.size()); }

 private:
  std::vector<float> weights_, cdf_;
  // guide_[k]: the bin holding u = k / size(), where the search for any u in
  // [k, k + 1) / size() starts (Chen and Asau's guide table): a short forward
  // scan instead of a binary search's cache misses over a probe-sized cdf.
  std::vector<int> guide_;
  float total_ = 0.0f;
};

// Piecewise-constant distribution over a width x height grid on [0,1)^2.
class Distribution2D {
 public:
  Distribution2D() = default;
  Distribution2D(const std::vector<float>& weights, int width, int height);
  // Sample (u, v) in [0,1)^2 with density `pdf` on the unit square.
  Vec2 sample(const Vec2& u, float& pdf) const;
  float pdf(const Vec2& uv) const;
  bool empty() const { return rows_.empty(); }

 private:
  int width_ = 0, height_ = 0;
  std::vector<Distribution1D> rows_;
  Distribution1D marginal_;
};

}  // namespace relight
