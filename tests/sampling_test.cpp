// Sampling: the piecewise-constant distributions sample their own pdf, the
// random number generator is deterministic, the standard warps have the right
// moments; and the camera (FORMAT.md "Camera"): pixel-centre convention, and
// project() inverting ray_direction().
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <vector>

#include "core/progress.h"
#include "core/sampling.h"
#include "core/statistics.h"
#include "scene/camera.h"

namespace relight {
namespace {

constexpr double kPiD = std::numbers::pi;

// Pearson's chi-square statistic of observed counts against expected
// probabilities; bins of probability 0 must stay empty.
double chi_square(const std::vector<int>& observed, const std::vector<double>& probability, int n, int& dof) {
  double x2 = 0.0;
  dof = -1;  // k bins, k - 1 degrees of freedom
  for (size_t i = 0; i < observed.size(); ++i) {
    const double expected = probability[i] * n;
    if (expected <= 0.0) {
      EXPECT_EQ(observed[i], 0) << "bin " << i << " has probability 0 but was sampled";
      continue;
    }
    x2 += (observed[i] - expected) * (observed[i] - expected) / expected;
    ++dof;
  }
  return x2;
}

// Accept up to ~5 standard deviations above the mean of chi-square(dof).
void expect_chi_square_ok(double x2, int dof) {
  EXPECT_LT(x2, dof + 5.0 * std::sqrt(2.0 * dof)) << "chi-square " << x2 << " with " << dof << " dof";
}

// ------------------------------------------------------------- Rng

TEST(Percentile, IsTheValueThatShareOfTheValuesAreAtMost) {
  const std::vector<double> frame_ms = {9.0, 1.0, 7.0, 3.0, 5.0, 2.0, 8.0, 4.0, 6.0, 10.0};
  EXPECT_EQ(relight::percentile(frame_ms, 0.5), 5.0);
  EXPECT_EQ(relight::percentile(frame_ms, 0.95), 10.0);
  EXPECT_EQ(relight::percentile(frame_ms, 0.1), 1.0);
  EXPECT_EQ(relight::percentile({42.0}, 0.95), 42.0);
  EXPECT_THROW(relight::percentile({}, 0.5), std::invalid_argument);
}

// The progress line estimates the time left at the pace so far, once a
// twentieth is done and a second has passed.
TEST(ProgressLine, EstimatesTheTimeLeftFromThePaceSoFar) {
  EXPECT_NE(progress_line("analysis", 0.25, 10.0).find("~30s left"), std::string::npos)
      << progress_line("analysis", 0.25, 10.0);
  EXPECT_NE(progress_line("analysis", 0.1, 20.0).find("~3m00s left"), std::string::npos);
  EXPECT_NE(progress_line("analysis", 0.5, 4000.0).find("~1h06m left"), std::string::npos);
  EXPECT_EQ(progress_line("analysis", 0.01, 10.0).find("left"), std::string::npos);  // too early to tell
  EXPECT_EQ(progress_line("analysis", 0.5, 0.4).find("left"), std::string::npos);
  EXPECT_EQ(progress_line("analysis", 1.0, 12.0).find("left"), std::string::npos);  // done
  EXPECT_NE(progress_line("analysis", 0.5, 4.0).find(" 50%    4.0s"), std::string::npos);
}

// A job's time left: each stage to come at the pace its kind went at in
// this run; before one of its kind has finished, at the pace of the one
// running where that is of its kind, else of what has run.
TEST(JobEstimate, TimesTheStagesToComeAtThePaceTheirKindWent) {
  enum { direct, bounce };
  JobEstimate job({{"direct light", direct, 100.0},
                   {"illumination", bounce, 10.0},
                   {"interreflection 1", bounce, 10.0},
                   {"interreflection 2", bounce, 10.0},
                   {"rendered back", bounce, 20.0}});
  EXPECT_FALSE(job.seconds_left(0.5, 3.0));  // nothing begun
  job.begin("direct light", 1.0);
  EXPECT_FALSE(job.seconds_left(0.02, 3.0));  // too early to tell
  // Half the direct light in 2 s: 0.04 s per unit, for this stage and, with
  // no other pace known, for the 50 units to come.
  EXPECT_NEAR(*job.seconds_left(0.5, 3.0), 2.0 + 0.04 * 50.0, 1e-9);
  job.begin("denoising", 4.0);     // not planned: part of the direct light's time
  job.begin("illumination", 6.0);  // the direct light took 5 s: 0.05 s per unit
  EXPECT_NEAR(*job.seconds_left(0.0, 6.0), 0.05 * 50.0, 1e-9);
  // Half its bar in 5 s, 1 s per unit where the direct light's went 0.05:
  // it and the bounce light's renders to come at its own pace.
  EXPECT_NEAR(*job.seconds_left(0.5, 11.0), 5.0 + 40.0, 1e-9);
  job.begin("interreflection 1", 16.0);  // the bounce light: 1 s per unit
  // Its bar half done in 5 s, and at the pace of the illumination: 5 s
  // more; "interreflection 2" and "rendered back" at 1 s per unit.
  EXPECT_NEAR(*job.seconds_left(0.5, 21.0), 5.0 + 30.0, 1e-9);
  // Its bar slower than the illumination went: its own pace.
  EXPECT_NEAR(*job.seconds_left(0.25, 21.0), 15.0 + 30.0, 1e-9);
  EXPECT_NEAR(job.fraction_done(0.25, 21.0), 20.0 / (20.0 + 45.0), 1e-9);
  // Converged early: "interreflection 2" did not run, and only the render
  // back is to come.
  job.begin("rendered back", 28.0);  // the bounce light: 22 s for 20 units
  EXPECT_NEAR(*job.seconds_left(0.0, 28.0), 1.1 * 20.0, 1e-9);
}

TEST(Rng, SameSeedAndStreamGiveTheSameSequence) {
  Rng a(42, 7, 3), b(42, 7, 3);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(a.next_u32(), b.next_u32()) << i;
  Rng c(42, 7, 3), d(42, 7, 3);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(c.uniform(), d.uniform()) << i;
}

TEST(Rng, DifferentSeedOrStreamGiveDifferentSequences) {
  auto first = [](Rng r) {
    std::vector<uint32_t> v;
    for (int i = 0; i < 8; ++i) v.push_back(r.next_u32());
    return v;
  };
  const auto base = first(Rng(42, 7, 3));
  EXPECT_NE(first(Rng(43, 7, 3)), base);
  EXPECT_NE(first(Rng(42, 8, 3)), base);
  EXPECT_NE(first(Rng(42, 7, 4)), base);
  EXPECT_NE(first(Rng(42, 3, 7)), base);  // the stream arguments are not symmetric
}

TEST(Rng, NeighbouringPixelStreamsAreUncorrelated) {
  // The first values of streams (seed, i) for consecutive i: mean 1/2 and no
  // correlation between consecutive streams.
  const int n = 20000;
  std::vector<double> x(n);
  for (int i = 0; i < n; ++i) x[i] = Rng(1, uint64_t(i)).uniform();
  double mean = 0.0, corr = 0.0;
  for (int i = 0; i < n; ++i) mean += x[i];
  mean /= n;
  for (int i = 0; i + 1 < n; ++i) corr += (x[i] - 0.5) * (x[i + 1] - 0.5);
  corr /= (n - 1) / 12.0;  // normalised by the variance 1/12
  EXPECT_NEAR(mean, 0.5, 0.01);
  EXPECT_NEAR(corr, 0.0, 0.04);
}

TEST(Rng, UniformIsInUnitIntervalWithUniformHistogram) {
  Rng rng(5, 0);
  const int n = 200000, bins = 50;
  std::vector<int> hist(bins, 0);
  for (int i = 0; i < n; ++i) {
    const float u = rng.uniform();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    ++hist[std::min(int(u * bins), bins - 1)];
  }
  int dof = 0;
  const double x2 = chi_square(hist, std::vector<double>(bins, 1.0 / bins), n, dof);
  expect_chi_square_ok(x2, dof);
}

// ---------------------------------------------------- Hammersley points

TEST(Hammersley, ShiftedPointsFillEveryRowAndColumnOfTheGridOnce) {
  // 256 points, shifted anywhere, still put one point in each of 16 x 16
  // strata's rows of 1/256 in x, and 16 in each 1/16-wide column of y.
  const int n = 256;
  for (const Vec2& shift : {Vec2(0.0f, 0.0f), Vec2(0.37f, 0.91f), Vec2(0.999f, 0.5f)}) {
    std::vector<int> rows(n, 0), columns(16, 0);
    for (int i = 0; i < n; ++i) {
      const Vec2 p = shifted(hammersley(i, n), shift);
      ASSERT_GE(p.minCoeff(), 0.0f);
      ASSERT_LT(p.maxCoeff(), 1.0f);
      ++rows[int(p.x() * n)];
      ++columns[int(p.y() * 16)];
    }
    EXPECT_EQ(*std::min_element(rows.begin(), rows.end()), 1);
    EXPECT_EQ(*std::max_element(rows.begin(), rows.end()), 1);
    EXPECT_EQ(*std::min_element(columns.begin(), columns.end()), 16);
    EXPECT_EQ(*std::max_element(columns.begin(), columns.end()), 16);
  }
}

// ---------------------------------------------------- Distribution1D

TEST(Distribution1D, PdfIsWeightOverMean) {
  const Distribution1D dist({1, 0, 3, 6, 0, 2});
  EXPECT_FLOAT_EQ(dist.total(), 12.0f);
  EXPECT_EQ(dist.size(), 6);
  // Density on [0,1): bin width 1/6, so pdf = w * 6 / 12.
  const float expected[] = {0.5f, 0.0f, 1.5f, 3.0f, 0.0f, 1.0f};
  for (int i = 0; i < 6; ++i) EXPECT_FLOAT_EQ(dist.pdf(i), expected[i]) << i;
}

TEST(Distribution1D, SamplesFollowThePdf) {
  const std::vector<float> weights = {1, 0, 3, 6, 0, 2, 0.5f, 0, 0, 4};
  const Distribution1D dist(weights);
  double total = 0.0;
  for (float w : weights) total += w;
  std::vector<double> prob;
  for (float w : weights) prob.push_back(w / total);

  Rng rng(17, 0);
  const int n = 200000;
  std::vector<int> hist(weights.size(), 0);
  // The continuous position (bin + offset)/n must be uniform inside each
  // bin: histogram it on a 4x finer grid.
  std::vector<int> fine(weights.size() * 4, 0);
  for (int i = 0; i < n; ++i) {
    float offset = -1.0f, pdf = -1.0f;
    const int bin = dist.sample(rng.uniform(), offset, pdf);
    ASSERT_GE(bin, 0);
    ASSERT_LT(bin, int(weights.size()));
    ASSERT_GE(offset, 0.0f);
    ASSERT_LT(offset, 1.0f);
    ASSERT_FLOAT_EQ(pdf, dist.pdf(bin));
    ++hist[bin];
    ++fine[bin * 4 + std::min(int(offset * 4), 3)];
  }
  int dof = 0;
  const double x2 = chi_square(hist, prob, n, dof);
  expect_chi_square_ok(x2, dof);
  std::vector<double> fine_prob;
  for (double p : prob)
    for (int k = 0; k < 4; ++k) fine_prob.push_back(p / 4);
  const double x2_fine = chi_square(fine, fine_prob, n, dof);
  expect_chi_square_ok(x2_fine, dof);
}

TEST(Distribution1D, IsTheInverseCdf) {
  // With weights {1, 3}: cdf(0.5) = 0.25, so u = 0.125 lies half-way
  // through bin 0 and u = 0.625 half-way through bin 1.
  const Distribution1D dist({1, 3});
  float offset, pdf;
  EXPECT_EQ(dist.sample(0.125f, offset, pdf), 0);
  EXPECT_NEAR(offset, 0.5f, 1e-6f);
  EXPECT_FLOAT_EQ(pdf, 0.5f);
  EXPECT_EQ(dist.sample(0.625f, offset, pdf), 1);
  EXPECT_NEAR(offset, 0.5f, 1e-6f);
  EXPECT_FLOAT_EQ(pdf, 1.5f);
  EXPECT_EQ(dist.sample(0.0f, offset, pdf), 0);
  EXPECT_EQ(dist.sample(0x1.fffffep-1f, offset, pdf), 1);
}

// The guide table only shortens the search: every u, those on the guide's
// k / n boundaries included, lands in the bin the inverse cdf gives.
TEST(Distribution1D, TheGuideTableGivesTheInverseCdfsBin) {
  const int n = 1000;
  std::vector<float> weights(n);
  Rng init(5, 0);
  for (int i = 0; i < n; ++i) weights[i] = i % 5 == 0 ? 0.0f : std::pow(init.uniform(), 4.0f) * 100.0f;
  weights[n / 2] = 5e4f;  // one bin taking a third of the total
  const Distribution1D dist(weights);
  std::vector<double> cdf(n + 1, 0.0);
  for (int i = 0; i < n; ++i) cdf[i + 1] = cdf[i] + weights[i];
  Rng rng(9, 0);
  for (int t = 0; t < 20000; ++t) {
    const float u = t % 2 ? rng.uniform() : std::min(float(t / 2 % n) / n, 0x1.fffffep-1f);
    float offset, pdf;
    const int bin = dist.sample(u, offset, pdf);
    const double target = double(u) * cdf[n];
    ASSERT_GT(weights[bin], 0.0f) << u;
    // The bin's cdf range holds u, within float rounding of the cdf.
    EXPECT_LE(cdf[bin], target + 1e-4 * cdf[n]) << u;
    EXPECT_GE(cdf[bin + 1], target - 1e-4 * cdf[n]) << u;
  }
}

TEST(Distribution1D, NeverLandsInEmptyBinsEvenAtTheEnds) {
  const Distribution1D dist({0, 0, 2, 0, 0});
  float offset, pdf;
  for (float u : {0.0f, 1e-7f, 0.3f, 0.5f, 0.9999f, 0x1.fffffep-1f}) {
    EXPECT_EQ(dist.sample(u, offset, pdf), 2) << u;
    EXPECT_FLOAT_EQ(pdf, 5.0f);
  }
}

TEST(Distribution1D, NegativeWeightsCountAsZero) {
  const Distribution1D dist({-5, 1, 1});
  EXPECT_FLOAT_EQ(dist.total(), 2.0f);
  EXPECT_EQ(dist.pdf(0), 0.0f);
  float offset, pdf;
  EXPECT_NE(dist.sample(0.0f, offset, pdf), 0);
}

TEST(Distribution1D, AllZeroWeightsSampleUniformly) {
  const Distribution1D dist({0, 0, 0, 0});
  float offset, pdf;
  EXPECT_EQ(dist.sample(0.6f, offset, pdf), 2);
  EXPECT_NEAR(offset, 0.4f, 1e-5f);
  EXPECT_FLOAT_EQ(pdf, 1.0f);
}

// ---------------------------------------------------- Distribution2D

TEST(Distribution2D, SamplesFollowThePdfAndPdfIntegratesToOne) {
  const int w = 8, h = 5;
  std::vector<float> weights(w * h);
  Rng init(3, 0);
  for (int i = 0; i < w * h; ++i) weights[i] = (i % 7 == 3) ? 0.0f : 0.1f + 5.0f * init.uniform();
  weights[2 * w + 6] = 40.0f;  // one bright cell
  for (int x = 0; x < w; ++x) weights[4 * w + x] = 0.0f;  // an empty row
  const Distribution2D dist(weights, w, h);
  ASSERT_FALSE(dist.empty());

  double total = 0.0;
  for (float v : weights) total += v;
  std::vector<double> prob;
  for (float v : weights) prob.push_back(v / total);

  // The pdf on the unit square integrates to 1 and is weight / mean weight.
  double integral = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float pdf = dist.pdf(Vec2((x + 0.5f) / w, (y + 0.5f) / h));
      EXPECT_NEAR(pdf, weights[y * w + x] / (total / (w * h)), 1e-4 * (1 + pdf)) << x << "," << y;
      integral += pdf / (w * h);
    }
  EXPECT_NEAR(integral, 1.0, 1e-5);

  Rng rng(4, 0);
  const int n = 200000;
  std::vector<int> hist(w * h, 0);
  int pdf_mismatches = 0;
  for (int i = 0; i < n; ++i) {
    float pdf = -1.0f;
    const Vec2 uv = dist.sample(rng.uniform2(), pdf);
    ASSERT_GE(uv.x(), 0.0f);
    ASSERT_LT(uv.x(), 1.0f);
    ASSERT_GE(uv.y(), 0.0f);
    ASSERT_LT(uv.y(), 1.0f);
    if (std::abs(pdf - dist.pdf(uv)) > 1e-4f * pdf) {
      ++pdf_mismatches;
      ADD_FAILURE() << "sample " << i << ": returned pdf " << pdf << " but pdf(uv) = " << dist.pdf(uv)
                    << " at uv = " << uv.transpose();
    }
    ++hist[int(uv.y() * h) * w + int(uv.x() * w)];
  }
  // KNOWN BUG in src/core/sampling.cpp Distribution2D::sample (see
  // SampleStaysInsideTheSampledCell): with this seed sample 95965 draws the
  // end of cell (6, 2) with offset 0.99999994, (6 + offset) rounds to 7 in
  // float, and uv lands in cell (7, 2) while the pdf of cell (6, 2) is
  // returned. Do not relax this: fix the source.
  EXPECT_EQ(pdf_mismatches, 0);
  int dof = 0;
  const double x2 = chi_square(hist, prob, n, dof);
  expect_chi_square_ok(x2, dof);
}

TEST(Distribution2D, SampleStaysInsideTheSampledCell) {
  // KNOWN BUG (src/core/sampling.cpp, Distribution2D::sample): it returns
  // (x + ox) / width with ox <= 0x1.fffffep-1; for x >= 2 the float sum
  // x + ox rounds up to x + 1, so uv falls in the next cell, whose pdf can
  // differ arbitrarily (here: 0) from the pdf returned. Deterministic case:
  // a single non-empty cell x = 3 of 8, u.x at the top of [0, 1).
  std::vector<float> weights(8, 0.0f);
  weights[3] = 1.0f;
  const Distribution2D dist(weights, 8, 1);
  for (float ux : {0.5f, 0.999f, 0.9999999f, 0x1.fffffep-1f}) {
    float pdf = -1.0f;
    const Vec2 uv = dist.sample(Vec2(ux, 0.5f), pdf);
    EXPECT_FLOAT_EQ(pdf, 8.0f);
    EXPECT_EQ(int(uv.x() * 8), 3) << "u.x = " << ux << " gave uv.x = " << uv.x();
    EXPECT_FLOAT_EQ(dist.pdf(uv), pdf) << "u.x = " << ux;
  }
  // The same in y: one non-empty row y = 3 of 8.
  std::vector<float> column(8, 0.0f);
  column[3] = 1.0f;
  const Distribution2D tall(column, 1, 8);
  float pdf = -1.0f;
  const Vec2 uv = tall.sample(Vec2(0.5f, 0x1.fffffep-1f), pdf);
  EXPECT_EQ(int(uv.y() * 8), 3) << "uv.y = " << uv.y();
  EXPECT_FLOAT_EQ(tall.pdf(uv), pdf);
}

// -------------------------------------------------------------- warps

TEST(Warps, UniformSphereIsUnitAndUnbiased) {
  Rng rng(8, 0);
  const int n = 100000;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double zz = 0.0;
  for (int i = 0; i < n; ++i) {
    const Vec3 d = sample_uniform_sphere(rng.uniform2());
    ASSERT_NEAR(d.norm(), 1.0f, 1e-5f);
    mean += d.cast<double>();
    zz += d.z() * d.z();
  }
  mean /= n;
  EXPECT_LT(mean.norm(), 0.01);
  EXPECT_NEAR(zz / n, 1.0 / 3.0, 0.005);  // E[z^2] = 1/3 on the sphere
}

TEST(Warps, CosineHemisphereHasCosineDensity) {
  Rng rng(9, 0);
  const int n = 100000;
  double z_mean = 0.0;
  for (int i = 0; i < n; ++i) {
    const Vec3 d = sample_cosine_hemisphere(rng.uniform2());
    ASSERT_NEAR(d.norm(), 1.0f, 1e-5f);
    ASSERT_GE(d.z(), 0.0f);
    z_mean += d.z();
  }
  EXPECT_NEAR(z_mean / n, 2.0 / 3.0, 0.005);  // E[cos] under cos/pi = 2/3
}

TEST(Warps, ConcentricDiscIsUniform) {
  Rng rng(10, 0);
  const int n = 100000;
  double r2 = 0.0;
  int first_quadrant = 0;
  for (int i = 0; i < n; ++i) {
    const Vec2 p = sample_concentric_disc(rng.uniform2());
    ASSERT_LE(p.squaredNorm(), 1.0f + 1e-6f);
    r2 += p.squaredNorm();
    if (p.x() > 0 && p.y() > 0) ++first_quadrant;
  }
  EXPECT_NEAR(r2 / n, 0.5, 0.005);  // E[r^2] = 1/2 for a uniform disc
  EXPECT_NEAR(double(first_quadrant) / n, 0.25, 0.005);
}

TEST(Warps, UniformConeStaysInsideAndIsUniform) {
  Rng rng(11, 0);
  const float cos_max = std::cos(radians(20.0f));
  const int n = 100000;
  double z_mean = 0.0;
  for (int i = 0; i < n; ++i) {
    const Vec3 d = sample_uniform_cone(rng.uniform2(), cos_max);
    ASSERT_NEAR(d.norm(), 1.0f, 1e-5f);
    ASSERT_GE(d.z(), cos_max - 1e-6f);
    z_mean += d.z();
  }
  EXPECT_NEAR(z_mean / n, (1.0 + cos_max) / 2.0, 1e-4);
}

TEST(Warps, PowerHeuristic) {
  EXPECT_FLOAT_EQ(power_heuristic(1.0f, 1.0f), 0.5f);
  EXPECT_FLOAT_EQ(power_heuristic(3.0f, 1.0f), 0.9f);
  EXPECT_FLOAT_EQ(power_heuristic(0.0f, 0.0f), 0.0f);
  EXPECT_FLOAT_EQ(power_heuristic(2.0f, 0.5f) + power_heuristic(0.5f, 2.0f), 1.0f);
}

TEST(Warps, OrthonormalBasisIsRightHanded) {
  Rng rng(12, 0);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 n = sample_uniform_sphere(rng.uniform2());
    Vec3 t, b;
    orthonormal_basis(n, t, b);
    ASSERT_NEAR(t.norm(), 1.0f, 1e-5f);
    ASSERT_NEAR(b.norm(), 1.0f, 1e-5f);
    ASSERT_NEAR(t.dot(n), 0.0f, 1e-5f);
    ASSERT_NEAR(b.dot(n), 0.0f, 1e-5f);
    ASSERT_NEAR(t.dot(b), 0.0f, 1e-5f);
    ASSERT_LT((t.cross(b) - n).norm(), 1e-5f);
    ASSERT_LT((to_world(Vec3(0, 0, 1), n) - n).norm(), 1e-6f);
  }
}

// -------------------------------------------------------------- camera

struct CameraCase {
  CameraSpec spec;
  int width, height;
};

std::vector<CameraCase> camera_cases() {
  CameraCase a;  // the FORMAT.md example: up not orthogonal to the view
  a.spec.position = Vec3(7.0f, -6.5f, 4.0f);
  a.spec.look_at = Vec3(0.0f, 0.0f, 0.8f);
  a.spec.up = Vec3(0, 0, 1);
  a.spec.vfov_deg = 35.0f;
  a.width = 64;
  a.height = 48;
  CameraCase b;  // portrait, wide angle, tilted up vector
  b.spec.position = Vec3(-1, 2, 0.5f);
  b.spec.look_at = Vec3(3, 1, -0.5f);
  b.spec.up = Vec3(0.2f, 0.1f, 1.0f);
  b.spec.vfov_deg = 80.0f;
  b.width = 30;
  b.height = 50;
  return {a, b};
}

// Cameras whose principal point is off the image centre (docs/formats.md).
std::vector<CameraCase> off_centre_cases() {
  std::vector<CameraCase> cases = camera_cases();
  cases[0].spec.principal_point = Vec2(0.3f, 0.65f);   // shifted left and down
  cases[1].spec.principal_point = Vec2(0.9f, -0.2f);  // far off, above the image
  return cases;
}

// FORMAT.md's ray for pixel (col, row), computed in double from the text,
// with docs/formats.md's principal point (u, v): x = 2(col+0.5)/W - 2u,
// y = 2v - 2(row+0.5)/H (FORMAT.md's formula where u = v = 0.5).
Eigen::Vector3d format_ray(const CameraSpec& s, int w, int h, int col, int row) {
  const Eigen::Vector3d pos = s.position.cast<double>(), at = s.look_at.cast<double>(), up = s.up.cast<double>();
  const Eigen::Vector3d forward = (at - pos).normalized();
  const Eigen::Vector3d right = forward.cross(up).normalized();
  const Eigen::Vector3d up2 = right.cross(forward);
  const double u = s.principal_point.x(), v = s.principal_point.y();
  const double x = 2.0 * (col + 0.5) / w - 2.0 * u, y = 2.0 * v - 2.0 * (row + 0.5) / h;
  const double t = std::tan(s.vfov_deg * kPiD / 360.0);
  return (forward + x * t * (double(w) / h) * right + y * t * up2).normalized();
}

TEST(Camera, PixelCentreRayIsFormatsFormula) {
  for (const auto& c : camera_cases()) {
    const Camera cam(c.spec, c.width, c.height);
    for (int row = 0; row < c.height; row += 7)
      for (int col = 0; col < c.width; col += 5) {
        const Vec3 d = cam.ray_direction(col + 0.5f, row + 0.5f);
        EXPECT_NEAR(d.norm(), 1.0f, 1e-5f);
        EXPECT_LT((d.cast<double>() - format_ray(c.spec, c.width, c.height, col, row)).norm(), 2e-6)
            << "pixel " << col << "," << row;
      }
  }
}

TEST(Camera, ImageCentreLooksAtLookAtAndRowZeroIsTop) {
  const CameraCase c = camera_cases()[0];
  const Camera cam(c.spec, c.width, c.height);
  const Vec3 forward = (c.spec.look_at - c.spec.position).normalized();
  EXPECT_LT((cam.ray_direction(c.width / 2.0f, c.height / 2.0f) - forward).norm(), 1e-6f);
  EXPECT_LT((cam.forward() - forward).norm(), 1e-6f);
  // Row 0 is the top: its rays point more along world up than the last row's.
  EXPECT_GT(cam.ray_direction(c.width / 2.0f, 0.5f).z(), cam.ray_direction(c.width / 2.0f, c.height - 0.5f).z());
  // Column 0 is on the left: right = forward x up.
  const Vec3 right = forward.cross(c.spec.up).normalized();
  EXPECT_LT(cam.ray_direction(0.5f, c.height / 2.0f).dot(right), 0.0f);
  EXPECT_GT(cam.ray_direction(c.width - 0.5f, c.height / 2.0f).dot(right), 0.0f);
}

TEST(Camera, VerticalFieldOfViewSpansTheImageHeight) {
  for (const auto& c : camera_cases()) {
    const Camera cam(c.spec, c.width, c.height);
    const Vec3 top = cam.ray_direction(c.width / 2.0f, 0.0f);
    const Vec3 bottom = cam.ray_direction(c.width / 2.0f, float(c.height));
    EXPECT_NEAR(std::acos(double(top.dot(bottom))) * 180.0 / kPiD, c.spec.vfov_deg, 1e-3);
    // Square pixels: a pixel step is the same angle horizontally and vertically at the centre.
    const Vec3 centre = cam.ray_direction(c.width / 2.0f, c.height / 2.0f);
    const double dx = std::acos(double(centre.dot(cam.ray_direction(c.width / 2.0f + 1, c.height / 2.0f))));
    const double dy = std::acos(double(centre.dot(cam.ray_direction(c.width / 2.0f, c.height / 2.0f + 1))));
    EXPECT_NEAR(dx, dy, 1e-3 * dy);
  }
}

TEST(Camera, ProjectInvertsRayDirection) {
  Rng rng(21, 0);
  for (const auto& c : camera_cases()) {
    const Camera cam(c.spec, c.width, c.height);
    for (int i = 0; i < 2000; ++i) {
      const Vec2 pixel(rng.uniform() * c.width, rng.uniform() * c.height);
      const float depth = 0.5f + 20.0f * rng.uniform();
      const Vec3 p = c.spec.position + depth * cam.ray_direction(pixel.x(), pixel.y());
      const auto back = cam.project(p);
      ASSERT_TRUE(back.has_value());
      ASSERT_LT((*back - pixel).norm(), 2e-3f) << "pixel " << pixel.transpose() << " depth " << depth;
    }
  }
}

TEST(Camera, RayDirectionInvertsProject) {
  Rng rng(22, 0);
  const CameraCase c = camera_cases()[1];
  const Camera cam(c.spec, c.width, c.height);
  int in_front = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p = c.spec.position + 10.0f * sample_uniform_sphere(rng.uniform2());
    const auto pixel = cam.project(p);
    const bool behind = (p - c.spec.position).dot(cam.forward()) <= 0.0f;
    if (behind) {
      EXPECT_FALSE(pixel.has_value());
      continue;
    }
    ASSERT_TRUE(pixel.has_value());
    ++in_front;
    // Skip points nearly sideways, where the image position is huge.
    if ((p - c.spec.position).normalized().dot(cam.forward()) < 0.2f) continue;
    const Vec3 d = cam.ray_direction(pixel->x(), pixel->y());
    ASSERT_LT((d - (p - c.spec.position).normalized()).norm(), 1e-4f);
  }
  EXPECT_GT(in_front, 900);
}

TEST(Camera, ProjectsPixelCentresAndCorners) {
  const CameraCase c = camera_cases()[0];
  const Camera cam(c.spec, c.width, c.height);
  EXPECT_LT((*cam.project(c.spec.look_at) - Vec2(c.width / 2.0f, c.height / 2.0f)).norm(), 1e-3f);
  // A point on FORMAT's ray of pixel (3, 5) projects to that pixel's centre.
  const Vec3 p = c.spec.position + 4.0f * format_ray(c.spec, c.width, c.height, 3, 5).cast<float>();
  EXPECT_LT((*cam.project(p) - Vec2(3.5f, 5.5f)).norm(), 1e-3f);
  EXPECT_FALSE(cam.project(c.spec.position - cam.forward()).has_value());
  EXPECT_FALSE(cam.project(c.spec.position).has_value());
}

TEST(Camera, OffCentrePrincipalPointRaysAreTheFormula) {
  for (const auto& c : off_centre_cases()) {
    const Camera cam(c.spec, c.width, c.height);
    for (int row = 0; row < c.height; row += 7)
      for (int col = 0; col < c.width; col += 5)
        EXPECT_LT((cam.ray_direction(col + 0.5f, row + 0.5f).cast<double>() -
                   format_ray(c.spec, c.width, c.height, col, row))
                      .norm(),
                  2e-6)
            << "pixel " << col << "," << row;
  }
}

// A lens's radial distortion (docs/formats.md): a point whose pinhole image
// lies at u focal lengths from the principal point shows at
// u (1 + k1 |u|^2 + k2 |u|^4), computed here in double from the text; and
// ray_direction and project stay each other's inverse.
TEST(Camera, ADistortedLensShowsAPointWhereThePolynomialSays) {
  for (CameraCase c : off_centre_cases()) {
    c.spec.distortion = Vec2(-0.08f, 0.01f);
    const Camera pinhole(
        CameraSpec{c.spec.position, c.spec.look_at, c.spec.up, c.spec.vfov_deg, c.spec.principal_point}, c.width,
        c.height);
    const Camera lens(c.spec, c.width, c.height);
    ASSERT_FALSE(lens.distortion_folds());
    const double f = 0.5 * c.height / std::tan(c.spec.vfov_deg * kPiD / 360.0);
    const Eigen::Vector2d centre(c.spec.principal_point.x() * c.width, c.spec.principal_point.y() * c.height);
    Rng rng(23, 0);
    for (int i = 0; i < 500; ++i) {
      const Vec2 pixel(rng.uniform() * c.width, rng.uniform() * c.height);
      const Vec3 p = c.spec.position + 3.0f * pinhole.ray_direction(pixel.x(), pixel.y());
      const Eigen::Vector2d u = (pixel.cast<double>() - centre) / f;
      const double r2 = u.squaredNorm();
      const Eigen::Vector2d shown = centre + f * u * (1.0 + r2 * (-0.08 + r2 * 0.01));
      const auto projected = lens.project(p);
      ASSERT_TRUE(projected.has_value());
      ASSERT_LT((projected->cast<double>() - shown).norm(), 2e-3) << "pixel " << pixel.transpose();
      ASSERT_LT((lens.ray_direction(projected->x(), projected->y()) - (p - c.spec.position).normalized()).norm(),
                1e-5f);
    }
  }
}

// Radius r shows at r (1 + k1 r^2), at most 2 / (3 sqrt(-3 k1)) where k1 < 0.
TEST(Camera, ADistortionThatBendsBackWithinThePhotoFolds) {
  CameraCase c = camera_cases()[1];       // 80 degrees: the corners 0.98 focal lengths out
  c.spec.distortion = Vec2(-0.1f, 0.0f);  // reaches 1.22
  EXPECT_FALSE(Camera(c.spec, c.width, c.height).distortion_folds());
  c.spec.distortion = Vec2(-0.3f, 0.0f);  // turns back at 0.70, short of the corners
  EXPECT_TRUE(Camera(c.spec, c.width, c.height).distortion_folds());
  c.spec.distortion = Vec2(0.5f, 0.0f);  // pincushion never turns back
  EXPECT_FALSE(Camera(c.spec, c.width, c.height).distortion_folds());
}

TEST(Camera, OffCentrePrincipalPointLooksAtLookAtWithTheSameFocalLength) {
  for (const auto& c : off_centre_cases()) {
    const Camera cam(c.spec, c.width, c.height);
    const Vec2 pp(c.spec.principal_point.x() * c.width, c.spec.principal_point.y() * c.height);
    EXPECT_LT((cam.ray_direction(pp.x(), pp.y()) - cam.forward()).norm(), 1e-6f);
    EXPECT_LT((*cam.project(c.spec.look_at) - pp).norm(), 1e-3f);
    // Half the image height above the principal point is vfov/2 off the axis, as in a centred camera.
    const double half = std::acos(double(cam.ray_direction(pp.x(), pp.y() - c.height / 2.0f).dot(cam.forward())));
    EXPECT_NEAR(half * 360.0 / kPiD, c.spec.vfov_deg, 1e-3);
    // Moving the principal point right moves the image of a point right by the same amount.
    CameraSpec centred = c.spec;
    centred.principal_point = Vec2(0.5f, 0.5f);
    const Camera centre_cam(centred, c.width, c.height);
    const Vec3 p = c.spec.position + 5.0f * cam.forward() + 0.7f * c.spec.up.normalized();
    const Vec2 shift = *cam.project(p) - *centre_cam.project(p);
    EXPECT_LT((shift - (pp - Vec2(c.width / 2.0f, c.height / 2.0f))).norm(), 1e-3f);
  }
}

TEST(Camera, OffCentreProjectInvertsRayDirection) {
  Rng rng(23, 0);
  for (const auto& c : off_centre_cases()) {
    const Camera cam(c.spec, c.width, c.height);
    for (int i = 0; i < 2000; ++i) {
      const Vec2 pixel(rng.uniform() * c.width, rng.uniform() * c.height);
      const Vec3 p = c.spec.position + (0.5f + 20.0f * rng.uniform()) * cam.ray_direction(pixel.x(), pixel.y());
      const auto back = cam.project(p);
      ASSERT_TRUE(back.has_value());
      ASSERT_LT((*back - pixel).norm(), 2e-3f) << "pixel " << pixel.transpose();
    }
  }
}

}  // namespace
}  // namespace relight
