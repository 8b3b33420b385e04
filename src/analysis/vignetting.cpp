#include "analysis/vignetting.h"

#include <spdlog/spdlog.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/statistics.h"

namespace relight {

namespace {

// r^2 of pixel (x, y)'s centre: its distance from the photo's centre over
// the half diagonal, squared.
double radius_squared(double x, double y, int w, int h) {
  const double dx = x + 0.5 - 0.5 * w, dy = y + 0.5 - 0.5 * h;
  return (dx * dx + dy * dy) / (0.25 * (double(w) * w + double(h) * h));
}

// One point of the fit: log(photo / probe) at r^2, in the photo's
// jackknife block `block`.
struct Sample {
  double r2, log_ratio;
  uint32_t block;
};

// The normal equations of the weighted least squares over some samples:
// unknowns a, b and the probe's log exposure.
struct Normal {
  Eigen::Matrix3d xtx = Eigen::Matrix3d::Zero();
  Eigen::Vector3d xty = Eigen::Vector3d::Zero();
  void add(const Sample& s, double weight) {
    const Eigen::Vector3d x(s.r2, s.r2 * s.r2, 1.0);
    xtx += weight * x * x.transpose();
    xty += weight * s.log_ratio * x;
  }
  Eigen::Vector3d solve() const { return xtx.ldlt().solve(xty); }
};

double residual(const Sample& s, const Eigen::Vector3d& p) {
  return s.log_ratio - (p(0) * s.r2 + p(1) * s.r2 * s.r2 + p(2));
}

// Huber weights for residuals at `scale` (1.4826 x their median absolute
// value): a surface the views see differently (a sheen, a misplaced edge)
// pulls no harder than any point a little off.
std::vector<double> huber_weights(const std::vector<Sample>& samples, const Eigen::Vector3d& p) {
  std::vector<double> r(samples.size());
  for (size_t i = 0; i < samples.size(); ++i) r[i] = std::abs(residual(samples[i], p));
  const double scale = std::max(1e-6, 1.4826 * percentile(r, 0.5)), k = 1.345 * scale;
  std::vector<double> w(samples.size());
  for (size_t i = 0; i < samples.size(); ++i) w[i] = r[i] <= k ? 1.0 : k / r[i];
  return w;
}

}  // namespace

float Vignetting::at(int x, int y, int w, int h) const {
  const double r2_here = radius_squared(x, y, w, h);
  const double falloff = std::exp(r2 * r2_here + r4 * r2_here * r2_here);
  return float(std::clamp(falloff, double(kMaxVignetting), 1.0));
}

float Vignetting::corner() const { return std::exp(r2 + r4); }

std::optional<VignettingFit> fit_vignetting(const std::vector<SharedPoint>& shared, const Image& photo) {
  const int w = photo.width, h = photo.height;
  std::vector<Sample> samples;
  std::set<uint32_t> outer;
  for (const SharedPoint& s : shared) {
    const float shown = luminance(photo.pixels[s.pixel]), probe = luminance(s.probe);
    if (!(shown > 0.0f) || !(probe > 0.0f)) continue;
    const int x = int(s.pixel % size_t(w)), y = int(s.pixel / size_t(w));
    const double r2 = radius_squared(x, y, w, h);
    const uint32_t block = jackknife_block(x, y, w);
    samples.push_back({r2, std::log(double(shown) / double(probe)), block});
    if (r2 >= double(kMinVignettingReach) * kMinVignettingReach) outer.insert(block);
  }
  if (samples.size() < kMinExposurePoints) return std::nullopt;
  // Iteratively reweighted least squares from the plain fit.
  std::vector<double> weight(samples.size(), 1.0);
  Eigen::Vector3d p;
  for (int round = 0; round < 8; ++round) {
    Normal all;
    for (size_t i = 0; i < samples.size(); ++i) all.add(samples[i], weight[i]);
    p = all.solve();
    weight = huber_weights(samples, p);
  }
  // The jackknife over the photo's blocks, at the last weights: each block's
  // share of the normal equations taken out in turn.
  Normal all;
  std::map<uint32_t, Normal> per_block;
  for (size_t i = 0; i < samples.size(); ++i) {
    all.add(samples[i], weight[i]);
    per_block[samples[i].block].add(samples[i], weight[i]);
  }
  std::vector<double> corner;
  for (const auto& [block, part] : per_block) {
    Normal without = all;
    without.xtx -= part.xtx, without.xty -= part.xty;
    const Eigen::Vector3d q = without.solve();
    if (q.allFinite()) corner.push_back(q(0) + q(1));
  }
  double mean = 0.0, spread = 0.0;
  for (const double c : corner) mean += c;
  mean /= double(std::max<size_t>(1, corner.size()));
  for (const double c : corner) spread += (c - mean) * (c - mean);
  const double n = double(corner.size()), error = n > 1.0 ? std::sqrt((n - 1.0) / n * spread) : 0.0;
  VignettingFit fit;
  fit.falloff = {float(p(0)), float(p(1))};
  fit.significance = error > 0.0 ? float(std::abs(p(0) + p(1)) / error) : 0.0f;
  fit.points = samples.size();
  fit.outer_blocks = outer.size();
  return fit;
}

bool is_lens_vignetting(const VignettingFit& fit) {
  const float corner = fit.falloff.corner();
  return fit.outer_blocks >= kMinVignettingBlocks && fit.significance >= kMinVignettingSignificance &&
         corner <= 1.0f - kExposureTolerance && corner >= kMaxVignetting;
}

std::optional<Vignetting> photo_vignetting(const VignettingFit& fit, const std::string& scene_path) {
  const float corner = fit.falloff.corner();
  spdlog::info(
      "vignetting: the photo's corners {:.3f} times as bright as its centre against a probe ({} points, "
      "{:.1f} standard errors clear of none, {} blocks {:.0f} % or more of the way to the corners)",
      corner, fit.points, fit.significance, fit.outer_blocks, 100.0f * kMinVignettingReach);
  if (is_lens_vignetting(fit)) {
    spdlog::warn(
        "{}: the photo is {:.0f} % darker at its corners than at its centre against what a probe shows (a lens's "
        "vignetting): divided out (--keep-vignetting leaves it in)",
        scene_path, 100.0f * (1.0f - corner));
    return fit.falloff;
  }
  if (corner < kMaxVignetting && fit.significance >= kMinVignettingSignificance)
    spdlog::warn(
        "{}: the photo is {:.0f} % darker at its corners than at its centre against what a probe shows: more than a "
        "lens vignettes, so it is left as it is (is the camera or the geometry off?)",
        scene_path, 100.0f * (1.0f - corner));
  return std::nullopt;
}

void remove_vignetting(Image& photo, const Vignetting& v) {
  for (int y = 0; y < photo.height; ++y)
    for (int x = 0; x < photo.width; ++x) photo.at(x, y) /= v.at(x, y, photo.width, photo.height);
}

}  // namespace relight
