// oneTBB before any Qt header: Qt's `emit` macro breaks TBB's headers.
// clang-format off
#include <tbb/parallel_for.h>

#include "gui/geometry_overlay.h"
// clang-format on

#include <vector>

namespace relight::gui {

namespace {

// The central sample of every pixel of row y: the compact G-buffer
// recomputes each (a ray), so a row's are computed once, not per neighbour.
std::vector<GBufferSample> central_row(const GBuffer& g, int y) {
  std::vector<GBufferSample> row(size_t(g.width()));
  for (int x = 0; x < g.width(); ++x) row[size_t(x)] = g.central(x, y);
  return row;
}

bool differ(const GBufferSample& a, const GBufferSample& b) {
  return a.hit != b.hit || (a.hit && !GBuffer::same_surface(a.surface, b.surface));
}

}  // namespace

QImage geometry_edges_image(const GBuffer& g) {
  QImage image(g.width(), g.height(), QImage::Format_ARGB32);
  image.fill(Qt::transparent);
  const QRgb edge = kGeometryEdgeColour.rgba();
  uchar* const bits = image.bits();  // detached once here, written by rows below
  const qsizetype stride = image.bytesPerLine();
  tbb::parallel_for(0, g.height(), [&](int y) {
    const std::vector<GBufferSample> row = central_row(g, y);
    const std::vector<GBufferSample> below = y + 1 < g.height() ? central_row(g, y + 1) : row;
    auto* out = reinterpret_cast<QRgb*>(bits + y * stride);
    for (int x = 0; x < g.width(); ++x) {
      const GBufferSample& here = row[size_t(x)];
      if ((x + 1 < g.width() && differ(here, row[size_t(x) + 1])) || differ(here, below[size_t(x)])) out[x] = edge;
    }
  });
  return image;
}

}  // namespace relight::gui
