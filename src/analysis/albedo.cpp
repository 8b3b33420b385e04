#include "analysis/albedo.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "analysis/photo_blur.h"

namespace relight {

namespace {

constexpr float kMinCoverage = 0.5f;        // below: too little geometry in the pixel to divide
constexpr float kMinRelativeLight = 0.01f;  // below this share of the median illumination: unreliable
constexpr float kMaxAlbedo = 10.0f;         // guards against division blow-ups
// A matte surface reflects at most what reaches it: an albedo above 1 says
// the illumination divided by is wrong there (a side face the model shows and
// the photo does not, a shadow that is not in the photo, an unmodelled
// highlight). The bound is 1, or a margin above the 99th percentile where the
// albedo's scale is itself off (the lights' powers only roughly known).
constexpr float kBrightPercentile = 0.99f;
constexpr float kBrightMargin = 1.25f;
constexpr int kFillPasses = 256;

// Grows the albedo of the reliable pixels (known 1) into those to fill
// (known 0), one ring of pixels per pass, each taking the mean of its
// reliable neighbours (on its own surface only, or any); returns how many
// it filled.
size_t grow_reliable(Image& albedo, std::vector<int8_t>& known, const GBuffer& g, bool same_surface_only) {
  const int w = albedo.width, h = albedo.height;
  size_t filled = 0;
  for (int pass = 0; pass < kFillPasses; ++pass) {
    std::vector<std::pair<size_t, Vec3>> updates;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        if (known[size_t(y) * w + x] != 0) continue;
        Vec3 acc = Vec3::Zero();
        int n = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
            if (known[size_t(ny) * w + nx] != 1 || (same_surface_only && !g.same_surface(x, y, nx, ny))) continue;
            acc += albedo.at(nx, ny);
            ++n;
          }
        if (n) updates.emplace_back(size_t(y) * w + x, acc / float(n));
      }
    if (updates.empty()) break;
    for (const auto& [i, a] : updates) {
      albedo.pixels[i] = a;
      known[i] = 1;
    }
    filled += updates.size();
  }
  return filled;
}

}  // namespace

AlbedoImages recover_albedo(const Image& photo, const std::vector<uint8_t>& clipped, const IlluminationImages& illum,
                            const GBuffer& g) {
  const int w = photo.width, h = photo.height;
  const bool any_clipped = clipped.size() == photo.size();
  AlbedoImages out;
  out.albedo = Image(w, h);
  out.albedo_coverage = Image(w, h);

  // One buffer, sized once (pushed into, it would hold twice the view's
  // pixels while it grows): the illumination's luminances, then each divided
  // pixel's largest channel.
  std::vector<float> values;
  values.reserve(size_t(std::count_if(g.coverage().begin(), g.coverage().end(), [](float c) { return c > 0.0f; })));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (g.coverage(x, y) > 0.0f) values.push_back(luminance(illum.surface.at(x, y)));
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  const float threshold = kMinRelativeLight * values[values.size() / 2];

  // known: 1 reliable, 0 to fill, -1 background (nothing to fill)
  std::vector<int8_t> known(size_t(w) * h, -1);
  std::vector<float>& brightest = values;  // each divided pixel's largest channel
  brightest.clear();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float c = g.coverage(x, y);
      if (c <= 0.0f) continue;
      const Vec3& L = illum.surface.at(x, y);
      const size_t i = size_t(y) * w + x;
      known[i] = 0;
      if (c < kMinCoverage || luminance(L) <= threshold || L.minCoeff() <= 0.0f) continue;
      // photo = c a L + (1-c) B  =>  a = (photo - (1-c) B) / (c L)
      const Vec3 surface_part = (photo.at(x, y) - (1.0f - c) * illum.background.at(x, y)).cwiseMax(0.0f);
      const Vec3 a = surface_part.cwiseQuotient(c * L).cwiseMin(kMaxAlbedo);
      out.albedo.at(x, y) = a;
      known[i] = 1;
      if (!(any_clipped && clipped[i])) brightest.push_back(a.maxCoeff());
    }
  out.bright_bound = 1.0f;
  if (!brightest.empty()) {
    const auto at = brightest.begin() + ptrdiff_t(kBrightPercentile * float(brightest.size() - 1));
    std::nth_element(brightest.begin(), at, brightest.end());
    out.bright_bound = std::max(1.0f, kBrightMargin * *at);
  }
  std::vector<std::pair<size_t, Vec3>> at_least;  // the clipped pixels' lower bounds
  Vec3 sum = Vec3::Zero();
  size_t count = 0;
  for (size_t i = 0; i < known.size(); ++i) {
    if (known[i] != 1) continue;
    const Vec3& a = out.albedo.pixels[i];
    // A clipped pixel's radiance is only known to be at least its value:
    // its albedo is filled, and then raised to that lower bound.
    if (any_clipped && clipped[i]) {
      at_least.emplace_back(i, a.cwiseMin(out.bright_bound));
      known[i] = 0;
    } else if (a.maxCoeff() > out.bright_bound) {
      out.as_divided.emplace_back(uint32_t(i), a);
      known[i] = 0;
    } else {
      sum += a;
      ++count;
    }
  }
  if (count) out.mean = sum / float(count);

  // The reliable albedo grown into the unreliable pixels of the same
  // surface; what no pixel of its surface reaches (a face whose every pixel
  // is unreliable) then from any neighbour.
  out.filled += grow_reliable(out.albedo, known, g, true);
  out.filled += grow_reliable(out.albedo, known, g, false);
  for (size_t i = 0; i < known.size(); ++i)
    if (known[i] == 0) {
      out.albedo.pixels[i] = out.mean;
      ++out.filled;
    }
  for (const auto& [i, bound] : at_least) out.albedo.pixels[i] = out.albedo.pixels[i].cwiseMax(bound);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) out.albedo_coverage.at(x, y) = out.albedo.at(x, y) * g.coverage(x, y);
  return out;
}

void sharpen_albedo(AlbedoImages& albedo, const GBuffer& g, float sigma_px, int band_rows) {
  if (!(sigma_px > 0.0f)) return;
  const int w = albedo.albedo.width, h = albedo.albedo.height;
  cv::Mat coverage_blurred;
  cv::GaussianBlur(cv::Mat(h, w, CV_32F, const_cast<float*>(g.coverage().data())), coverage_blurred, cv::Size(0, 0),
                   sigma_px, sigma_px, cv::BORDER_REPLICATE);
  // In bands of rows, each deconvolved with the rows the filter reaches
  // beyond it (deblur_reach_px), and only the band's own rows kept: the
  // band's transforms, not the view's, are held at once. A band's rows are
  // written back once the next band has read the albedo it reaches into
  // (bands at least as tall as the reach: no further back than that).
  const int reach = deblur_reach_px(sigma_px);
  if (band_rows <= 0) band_rows = int(kSharpenBandPixels / std::max(1, w));
  band_rows = std::max(band_rows, reach);
  int pending_row = 0;
  Image pending;  // the last band's sharpened rows, not yet written
  const auto write_pending = [&] {
    for (int y = 0; y < pending.height; ++y)
      for (int x = 0; x < w; ++x) {
        const float c = g.coverage(x, pending_row + y);
        Vec3& a = albedo.albedo.at(x, pending_row + y);
        if (c >= kMinCoverage) a = (pending.at(x, y) / c).cwiseMax(0.0f).cwiseMin(albedo.bright_bound);
        albedo.albedo_coverage.at(x, pending_row + y) = a * c;
      }
  };
  for (int y0 = 0; y0 < h; y0 += band_rows) {
    const int y1 = std::min(h, y0 + band_rows), top = std::max(0, y0 - reach), bottom = std::min(h, y1 + reach);
    Image blurred(w, bottom - top);  // blur(c a)
    for (int y = top; y < bottom; ++y)
      for (int x = 0; x < w; ++x) blurred.at(x, y - top) = albedo.albedo.at(x, y) * coverage_blurred.at<float>(y, x);
    write_pending();
    const Image sharp = deblur(blurred, sigma_px);
    pending = Image(w, y1 - y0);
    std::copy(sharp.pixels.begin() + ptrdiff_t(y0 - top) * w, sharp.pixels.begin() + ptrdiff_t(y1 - top) * w,
              pending.pixels.begin());
    pending_row = y0;
  }
  write_pending();
}

}  // namespace relight
