// recover_albedo on a synthetic photo made by its own model: a pixel that
// covers a surface by a fraction c shows c a L + (1 - c) B (albedo a,
// illumination L, background B). Where c and L are large enough the albedo
// comes back exactly; elsewhere it is filled from the same surface. The
// pixels where the illumination's edges lie off the photo's are marked, and
// a soft photo's blur is undone in the albedo.
#include "analysis/albedo.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "analysis/illumination_alignment.h"
#include "analysis/photo_blur.h"
#include "flat_walls.h"

using namespace relight;

namespace {

constexpr int kW = 48, kH = 36;

// Smooth, known fields over the image.
Vec3 true_albedo(int x, int y) { return Vec3(0.2f + 0.6f * float(x) / kW, 0.5f, 0.7f - 0.4f * float(y) / kH); }
Vec3 light_at(int x, int y) { return Vec3(1.0f + 0.5f * float(x) / kW, 0.8f, 0.6f + float(y) / kH); }
const Vec3 kBackground(0.3f, 0.4f, 0.5f);

struct Synthetic {
  TriangleMesh mesh;  // before rays, which refer to it
  RayScene rays;
  GBuffer gbuffer;
  IlluminationImages illumination;
  Image photo;

  // One wall whose left edge, x = -0.2 m at 2 m, runs down the image: the
  // pixels on the edge see it in part; those left of it see the background.
  Synthetic()
      : mesh(test::walls_mesh({{2.0f, -0.2f, 10.0f}})),
        rays(mesh),
        gbuffer(test::walls_camera(kW, kH), rays, 16, 1, "walls"),
        illumination{Image(kW, kH), Image(kW, kH)},
        photo(kW, kH) {
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        illumination.surface.at(x, y) = light_at(x, y);
        illumination.background.at(x, y) = kBackground;
      }
  }
  void make_photo() {
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const float c = gbuffer.coverage(x, y);
        photo.at(x, y) = c * true_albedo(x, y).cwiseProduct(illumination.surface.at(x, y)) + (1 - c) * kBackground;
      }
  }
};

float max_error(const Vec3& a, const Vec3& b) { return (a - b).cwiseAbs().maxCoeff(); }

TEST(RecoverAlbedo, UndoesTheMixOfSurfaceAndBackground) {
  Synthetic s;
  s.make_photo();
  const AlbedoImages a = recover_albedo(s.photo, {}, s.illumination, s.gbuffer);
  int exact = 0, partial = 0, background = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float c = s.gbuffer.coverage(x, y);
      if (c == 0.0f) {
        ++background;
        EXPECT_EQ(a.albedo_coverage.at(x, y), Vec3::Zero());
        continue;
      }
      EXPECT_LT(max_error(a.albedo_coverage.at(x, y), c * a.albedo.at(x, y)), 1e-6f);
      if (c >= 0.5f) {
        ++exact;
        if (c < 1.0f) ++partial;
        EXPECT_LT(max_error(a.albedo.at(x, y), true_albedo(x, y)), 1e-5f) << x << "," << y << " coverage " << c;
      } else {
        // Too little of the surface to divide by: its neighbour's albedo, a
        // pixel or so away on a smooth field.
        EXPECT_LT(max_error(a.albedo.at(x, y), true_albedo(x, y)), 0.03f) << x << "," << y;
      }
    }
  EXPECT_GT(background, 0);
  EXPECT_GT(partial, 0);  // the edge is there and divided exactly
  EXPECT_EQ(a.filled, size_t(kW * kH - background - exact));
}

TEST(RecoverAlbedo, FillsDeepShadowFromTheSameSurfaceNotByDividing) {
  Synthetic s;
  // A block in deep shadow: under 1 % of the median illumination.
  for (int y = 10; y < 20; ++y)
    for (int x = 25; x < 35; ++x) s.illumination.surface.at(x, y) = Vec3::Constant(1e-4f);
  s.make_photo();
  // Noise in the photo there would blow up by 10^4 if divided.
  for (int y = 10; y < 20; ++y)
    for (int x = 25; x < 35; ++x) s.photo.at(x, y) += Vec3::Constant(0.01f);
  const AlbedoImages a = recover_albedo(s.photo, {}, s.illumination, s.gbuffer);
  EXPECT_GE(a.filled, size_t(100));
  for (int y = 10; y < 20; ++y)
    for (int x = 25; x < 35; ++x)
      // Grown in from the block's rim, at most 5 pixels away on a gentle slope.
      EXPECT_LT(max_error(a.albedo.at(x, y), true_albedo(x, y)), 0.08f) << x << "," << y;
  // The mean is that of the pixels that could be divided.
  EXPECT_NEAR(a.mean.y(), 0.5f, 1e-4f);
}

// A pixel 1000 times brighter than its light allows (an unmodelled highlight,
// or an illumination wrong there) is not divided but filled from its
// surface, and marked.
TEST(RecoverAlbedo, FillsWhatNoSurfaceCouldReflect) {
  Synthetic s;
  s.make_photo();
  s.photo.at(40, 18) *= 1000.0f;
  const AlbedoImages a = recover_albedo(s.photo, {}, s.illumination, s.gbuffer);
  EXPECT_FLOAT_EQ(a.bright_bound, 1.0f);  // the albedo's 99th percentile is 0.8
  ASSERT_EQ(a.as_divided.size(), size_t(1));
  EXPECT_EQ(a.as_divided[0].first, uint32_t(18 * kW + 40));
  EXPECT_LT(max_error(a.albedo.at(40, 18), true_albedo(40, 18)), 0.02f);
}

// Where the albedo's scale is off (lights brighter than the scene says),
// the brightest surfaces are not taken for impossible ones: the bound
// follows the albedo's 99th percentile.
TEST(RecoverAlbedo, ABrightScaleIsNotTakenForImpossibleAlbedo) {
  Synthetic s;
  s.make_photo();
  for (Vec3& p : s.photo.pixels) p *= 2.0f;  // albedos 0.4-1.6
  const AlbedoImages a = recover_albedo(s.photo, {}, s.illumination, s.gbuffer);
  EXPECT_GT(a.bright_bound, 1.25f * 1.5f);
  EXPECT_TRUE(a.as_divided.empty());
  EXPECT_LT(max_error(a.albedo.at(40, 18), 2.0f * true_albedo(40, 18)), 1e-5f);
}

// The analysis marks where the illumination's edges lie off the photo's
// (unreliable.exr) without moving them unless asked: the pixels marked are
// those align() would move, and the motion is the same.
TEST(EdgeMismatch, MarksThePixelsAlignMoves) {
  constexpr int w = 320, h = 240;  // matches are looked for up to w / 80 = 4 px away
  const auto corner = [&](int edge_x, int edge_y) {
    Image image(w, h, Vec3::Constant(0.2f));
    for (int y = edge_y; y < h; ++y)
      for (int x = edge_x; x < w; ++x) image.at(x, y) = Vec3::Constant(1.0f);
    return image;
  };
  const IlluminationAlignment alignment(corner(150, 100));
  const Image illumination = corner(153, 103);  // 3 px right and down
  const IlluminationAlignment::Mismatch mismatch = alignment.mismatch(illumination);
  const IlluminationAlignment::Aligned aligned = alignment.align(illumination);
  EXPECT_EQ(mismatch.moved, aligned.mismatch.moved);
  EXPECT_EQ(mismatch.motion_px, aligned.mismatch.motion_px);
  EXPECT_GT(mismatch.motion_px, 2.0f);
  EXPECT_GT(std::count(mismatch.moved.begin(), mismatch.moved.end(), 1), w);
  EXPECT_NE(aligned.illumination.pixels, illumination.pixels);  // align() moved them
}

// A photo blurred by a Gaussian of a pixel (a lens, a sensor), of a wall
// painted in a checker of 6 x 4 pixel squares: divided by the illumination
// blurred alike, its albedo is the checker blurred; sharpened, it comes
// back nearer the truth (by 1.4 dB; 0.4-1.8 dB on the blurred
// public scenes: docs/benchmarks.md, "A photo softer than the render"), the
// wall's silhouette against the background included, and within the bounds
// a surface can have; in bands of rows as at once.
TEST(SharpenAlbedo, UndoesThePhotosBlurOnATexturedWall) {
  constexpr float kSigma = 1.0f;
  Synthetic s;
  const auto checker = [](int x, int y) {
    return ((x / 6 + y / 4) % 2) ? Vec3(0.7f, 0.6f, 0.5f) : Vec3(0.2f, 0.3f, 0.4f);
  };
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float c = s.gbuffer.coverage(x, y);
      s.photo.at(x, y) = c * checker(x, y).cwiseProduct(s.illumination.surface.at(x, y)) + (1 - c) * kBackground;
    }
  s.photo = gaussian_blur(s.photo, kSigma);
  AlbedoImages a = recover_albedo(s.photo, {}, blur_illumination(s.illumination, s.gbuffer, kSigma), s.gbuffer);
  const auto rms_error = [&] {
    double sum = 0.0;
    int n = 0;
    // Clear of the image's border, beyond which the photo's blur saw nothing.
    for (int y = 3; y < kH - 3; ++y)
      for (int x = 3; x < kW - 3; ++x)
        if (s.gbuffer.coverage(x, y) >= 0.5f) sum += (a.albedo.at(x, y) - checker(x, y)).squaredNorm() / 3.0, ++n;
    return std::sqrt(sum / n);
  };
  const double blurred = rms_error();
  AlbedoImages in_bands = a;
  sharpen_albedo(a, s.gbuffer, kSigma);
  const double sharpened = rms_error();
  // Sharpened five rows at a time, each band with its reach beyond it: the same.
  sharpen_albedo(in_bands, s.gbuffer, kSigma, 5);
  for (size_t i = 0; i < a.albedo.size(); ++i)
    EXPECT_LT(max_error(in_bands.albedo.pixels[i], a.albedo.pixels[i]), 1e-3f);
  std::printf("[ figures  ] checker blurred by 1 px: albedo rms error %.4f as divided, %.4f sharpened\n", blurred,
              sharpened);
  EXPECT_GT(blurred, 0.1);
  EXPECT_LT(sharpened, 0.9 * blurred);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float c = s.gbuffer.coverage(x, y);
      EXPECT_LT(max_error(a.albedo_coverage.at(x, y), c * a.albedo.at(x, y)), 1e-6f);
      EXPECT_GE(a.albedo.at(x, y).minCoeff(), 0.0f);
      EXPECT_LE(a.albedo.at(x, y).maxCoeff(), a.bright_bound);
    }
}

// The deconvolution leaves an even image even (its filter passes a uniform
// colour whole), and a blur of no width undone is the image itself.
TEST(SharpenAlbedo, AnEvenImageAndNoBlurAreLeftAsTheyAre) {
  const Image even(40, 30, Vec3(0.25f, 0.5f, 0.75f));
  const Image deblurred = deblur(even, 1.5f);
  for (const Vec3& p : deblurred.pixels) EXPECT_LT(max_error(p, Vec3(0.25f, 0.5f, 0.75f)), 1e-4f);
  Synthetic s;
  s.make_photo();
  EXPECT_EQ(deblur(s.photo, 0.0f).pixels, s.photo.pixels);
  AlbedoImages a = recover_albedo(s.photo, {}, s.illumination, s.gbuffer);
  const std::vector<Vec3> before = a.albedo.pixels;
  sharpen_albedo(a, s.gbuffer, 0.0f);
  EXPECT_EQ(a.albedo.pixels, before);
}

}  // namespace
