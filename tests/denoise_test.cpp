// The G-buffer-guided denoiser of the smooth illumination: it takes Monte
// Carlo noise out of a flat surface while keeping its mean, never mixes two
// surfaces, leaves the background alone, gives the same in bands of rows as
// at once, and can be cancelled.
#include "render/denoise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.h"
#include "flat_walls.h"

using namespace relight;

namespace {

constexpr int kW = 64, kH = 48;
constexpr float kSigma = 0.2f;  // the noise's standard deviation (luminance) per pixel

struct Noisy {
  TriangleMesh mesh;  // before rays, which refer to it
  RayScene rays;
  GBuffer gbuffer;
  Image truth, noisy;
  std::vector<float> variance;

  // levels(x, y): the noise-free illumination; Gaussian noise on top (grey, so
  // its luminance has the same deviation) where a pixel sees a surface.
  template <class Levels>
  Noisy(const std::vector<test::Wall>& walls, Levels levels)
      : mesh(test::walls_mesh(walls)),
        rays(mesh),
        gbuffer(test::walls_camera(kW, kH), rays, 1, 1, "walls"),
        truth(kW, kH),
        noisy(kW, kH),
        variance(size_t(kW) * kH, kSigma * kSigma) {
    std::mt19937 rng(7);
    std::normal_distribution<float> noise(0.0f, kSigma);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        truth.at(x, y) = levels(x, y);
        noisy.at(x, y) = truth.at(x, y) + (gbuffer.central(x, y).hit ? Vec3::Constant(noise(rng)) : Vec3::Zero());
      }
  }
};

double rms_error(const Image& a, const Image& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) sum += double((a.pixels[i] - b.pixels[i]).squaredNorm()) / 3.0;
  return std::sqrt(sum / double(a.size()));
}

TEST(Denoise, TakesNoiseOutOfAFlatSurfaceAndKeepsItsMean) {
  const Noisy n({{2.0f, -10.0f, 10.0f}}, [](int, int) { return Vec3(1.0f, 0.8f, 0.6f); });
  const Image out = denoise_illumination(n.noisy, n.variance, n.gbuffer);
  const double before = rms_error(n.noisy, n.truth), after = rms_error(out, n.truth);
  EXPECT_NEAR(before, kSigma, 0.02);
  EXPECT_LT(after, 0.25 * before) << "before " << before << ", after " << after;
  Vec3 mean_in = Vec3::Zero(), mean_out = Vec3::Zero();
  for (size_t i = 0; i < out.size(); ++i) {
    mean_in += n.noisy.pixels[i];
    mean_out += out.pixels[i];
  }
  EXPECT_LT((mean_out - mean_in).cwiseAbs().maxCoeff() / float(out.size()), 0.01f);
}

// Two walls a metre apart in depth, the far one brighter by less than the
// noise's luminance weight tells apart: the plane test keeps each pixel's
// average on its own wall, right up to the line where they meet in the image.
TEST(Denoise, NeverMixesTwoSurfaces) {
  const Noisy n({{2.0f, -10.0f, 0.0f}, {3.0f, -10.0f, 10.0f}},
                [](int x, int) { return Vec3::Constant(x < kW / 2 ? 1.0f : 1.6f); });
  const Image out = denoise_illumination(n.noisy, n.variance, n.gbuffer);
  // The columns either side of the meeting line (x = 0 is the image's centre).
  double near_side = 0.0, far_side = 0.0;
  for (int y = 0; y < kH; ++y) {
    near_side += luminance(out.at(kW / 2 - 1, y));
    far_side += luminance(out.at(kW / 2, y));
  }
  EXPECT_NEAR(near_side / kH, 1.0, 0.05);
  EXPECT_NEAR(far_side / kH, 1.6, 0.05);
  EXPECT_LT(rms_error(out, n.truth), 0.35 * rms_error(n.noisy, n.truth));
}

TEST(Denoise, LeavesTheBackgroundAlone) {
  // A wall on the right half only; the left half sees nothing.
  Noisy n({{2.0f, 0.0f, 10.0f}}, [](int, int) { return Vec3::Constant(1.0f); });
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if (!n.gbuffer.central(x, y).hit) n.noisy.at(x, y) = Vec3(float(x), float(y), 5.0f);
  const Image out = denoise_illumination(n.noisy, n.variance, n.gbuffer);
  int background = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if (!n.gbuffer.central(x, y).hit) {
        ++background;
        EXPECT_EQ(out.at(x, y), n.noisy.at(x, y));
      } else {
        EXPECT_LT(std::abs(luminance(out.at(x, y)) - 1.0f), 0.3f);  // no background leaked in
      }
  EXPECT_GT(background, kW * kH / 3);
}

// A large view is filtered a band of rows at a time, each with the rows the
// filter reaches beyond it: the result is the whole view's, bit for bit.
TEST(Denoise, FiltersInBandsAsAtOnce) {
  const Noisy n({{2.0f, -10.0f, 0.0f}, {3.0f, -10.0f, 10.0f}},
                [](int x, int y) { return Vec3::Constant(x < kW / 2 ? 1.0f : 1.6f + 0.01f * float(y)); });
  for (const int passes : {3, 5}) {
    DenoiseOptions whole;
    whole.passes = passes;
    whole.band_rows = kH;
    const Image at_once = denoise_illumination(n.noisy, n.variance, n.gbuffer, whole);
    EXPECT_GT(rms_error(at_once, n.noisy), 0.5 * kSigma);  // it filtered
    for (const int rows : {1, 5, 13, 30}) {
      DenoiseOptions banded = whole;
      banded.band_rows = rows;
      const Image out = denoise_illumination(n.noisy, n.variance, n.gbuffer, banded);
      size_t differ = 0;
      for (size_t i = 0; i < out.size(); ++i) differ += out.pixels[i] != at_once.pixels[i];
      EXPECT_EQ(differ, 0u) << passes << " passes, bands of " << rows << " rows";
    }
  }
}

TEST(Denoise, StopsWhenCancelled) {
  const Noisy n({{2.0f, -10.0f, 10.0f}}, [](int, int) { return Vec3::Constant(1.0f); });
  Progress progress(false);
  progress.cancel();
  DenoiseOptions options;
  options.progress = &progress;
  EXPECT_THROW(denoise_illumination(n.noisy, n.variance, n.gbuffer, options), Cancelled);
}

}  // namespace
