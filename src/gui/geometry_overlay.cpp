// oneTBB before any Qt header: Qt's `emit` macro breaks TBB's headers.
// clang-format off
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gui/geometry_overlay.h"
// clang-format on

#include <vector>

namespace relight::gui {

namespace {

// The central sample of every pixel of row y: the compact G-buffer
// recomputes each (a ray), so each row's are computed once.
void central_row(const GBuffer& g, int y, std::vector<GBufferSample>& row) {
  row.resize(size_t(g.width()));
  for (int x = 0; x < g.width(); ++x) row[size_t(x)] = g.central(x, y);
}

}  // namespace

QImage geometry_edges_image(const GBuffer& g) {
  QImage image(g.width(), g.height(), QImage::Format_ARGB32);
  image.fill(Qt::transparent);
  const QRgb edge = kGeometryEdgeColour.rgba();
  uchar* const bits = image.bits();  // detached once here, written by rows below
  const qsizetype stride = image.bytesPerLine();
  // Bands of rows in parallel, each row's samples computed once (and the
  // row after each band's last once more).
  constexpr int kBandRows = 16;
  tbb::parallel_for(tbb::blocked_range<int>(0, g.height(), kBandRows), [&](const tbb::blocked_range<int>& band) {
    std::vector<GBufferSample> row, below;
    central_row(g, band.begin(), row);
    for (int y = band.begin(); y < band.end(); ++y, std::swap(row, below)) {
      if (y + 1 < g.height()) central_row(g, y + 1, below);
      auto* out = reinterpret_cast<QRgb*>(bits + y * stride);
      for (int x = 0; x < g.width(); ++x) {
        const GBufferSample& here = row[size_t(x)];
        if ((x + 1 < g.width() && GBuffer::edge_between(here, row[size_t(x) + 1])) ||
            (y + 1 < g.height() && GBuffer::edge_between(here, below[size_t(x)])))
          out[x] = edge;
      }
    }
  });
  return image;
}

}  // namespace relight::gui
