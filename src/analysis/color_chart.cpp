#include "analysis/color_chart.h"

#include <opencv2/imgproc.hpp>

#include <array>

namespace relight {

namespace {

// The sRGB values commonly published for the ColorChecker Classic (from
// X-Rite's chart data), row by row from dark skin; linearised below. A
// chart's own measurement differs from them by a few percent.
constexpr std::array<std::array<int, 3>, 24> kColorCheckerSrgb = {{
    {115, 82, 68},   {194, 150, 130}, {98, 122, 157},  {87, 108, 67},   {133, 128, 177}, {103, 189, 170},
    {214, 126, 44},  {80, 91, 166},   {193, 90, 99},   {94, 60, 108},   {157, 188, 64},  {224, 163, 46},
    {56, 61, 150},   {70, 148, 73},   {175, 54, 60},   {231, 199, 31},  {187, 86, 149},  {8, 133, 161},
    {243, 243, 242}, {200, 200, 200}, {160, 160, 160}, {122, 122, 121}, {85, 85, 85},    {52, 52, 52},
}};
constexpr int kColumns = 6, kRows = 4;
constexpr float kPatchShare = 0.4f;  // of a cell's width and height, around its centre

}  // namespace

std::vector<ReferencePatch> colorchecker_patches(const std::vector<Vec2>& corners) {
  const std::vector<cv::Point2f> chart = {{0, 0}, {kColumns, 0}, {kColumns, kRows}, {0, kRows}};
  std::vector<cv::Point2f> photo;
  for (const Vec2& c : corners) photo.emplace_back(c.x(), c.y());
  const cv::Mat homography = cv::getPerspectiveTransform(chart, photo);
  std::vector<ReferencePatch> patches;
  const float half = 0.5f * kPatchShare;
  for (int row = 0; row < kRows; ++row)
    for (int column = 0; column < kColumns; ++column) {
      const cv::Point2f centre(column + 0.5f, row + 0.5f);
      const std::vector<cv::Point2f> square = {centre + cv::Point2f(-half, -half), centre + cv::Point2f(half, -half),
                                               centre + cv::Point2f(half, half), centre + cv::Point2f(-half, half)};
      std::vector<cv::Point2f> seen;
      cv::perspectiveTransform(square, seen, homography);
      ReferencePatch patch;
      for (const cv::Point2f& p : seen) patch.polygon.emplace_back(p.x, p.y);
      const auto& srgb = kColorCheckerSrgb[size_t(row * kColumns + column)];
      for (int c = 0; c < 3; ++c) patch.albedo[c] = srgb_decode(float(srgb[size_t(c)]) / 255.0f);
      patches.push_back(std::move(patch));
    }
  return patches;
}

bool inside_polygon(const std::vector<Vec2>& polygon, const Vec2& p) {
  bool in = false;
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Vec2 &a = polygon[i], &b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      in = !in;
  }
  return in;
}

std::vector<ReferencePatch> reference_patches(const AlbedoReference& reference) {
  if (!reference.colorchecker.empty()) return colorchecker_patches(reference.colorchecker);
  return {{reference.polygon, reference.albedo}};
}

}  // namespace relight
