#include "analysis/color_chart.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>

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

namespace {

// The pixels of which every sample sees a triangle of the object.
ReferencePixels object_pixels(const AlbedoReference& reference, const GBuffer& gbuffer, const TriangleMesh& mesh) {
  ReferencePixels out;
  out.patches = 1;
  const auto found = std::find(mesh.objects.begin(), mesh.objects.end(), reference.object);
  if (found == mesh.objects.end() || !mesh.has_objects()) return out;
  const uint32_t object = uint32_t(found - mesh.objects.begin());
  for (int y = 0; y < gbuffer.height(); ++y)
    for (int x = 0; x < gbuffer.width(); ++x) {
      if (gbuffer.coverage(x, y) < 1.0f) continue;
      bool all_on_it = true;
      for (int k = 0; k < gbuffer.samples_per_pixel() && all_on_it; ++k)
        all_on_it = mesh.triangle_objects[gbuffer.sample(x, y, k).surface.prim] == object;
      if (all_on_it) out.pixels.push_back({size_t(y) * gbuffer.width() + x, reference.albedo, 0});
    }
  return out;
}

}  // namespace

ReferencePixels reference_pixels(const AlbedoReference& reference, const GBuffer& gbuffer, const TriangleMesh& mesh) {
  if (!reference.object.empty()) return object_pixels(reference, gbuffer, mesh);
  ReferencePixels out;
  const std::vector<ReferencePatch> patches = reference_patches(reference);
  out.patches = patches.size();
  for (size_t i = 0; i < patches.size(); ++i) {
    const ReferencePatch& patch = patches[i];
    // Only the pixels of the patch's bounding box can lie inside it.
    Eigen::AlignedBox2f box;
    for (const Vec2& v : patch.polygon) box.extend(v);
    const int x0 = std::max(0, int(std::floor(box.min().x()))), y0 = std::max(0, int(std::floor(box.min().y())));
    const int x1 = std::min(gbuffer.width(), int(std::ceil(box.max().x())) + 1);
    const int y1 = std::min(gbuffer.height(), int(std::ceil(box.max().y())) + 1);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        if (gbuffer.coverage(x, y) >= 1.0f && inside_polygon(patch.polygon, Vec2(x + 0.5f, y + 0.5f)))
          out.pixels.push_back({size_t(y) * gbuffer.width() + x, patch.albedo, i});
  }
  return out;
}

}  // namespace relight
