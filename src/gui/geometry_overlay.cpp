#include "gui/geometry_overlay.h"

namespace relight::gui {

QImage geometry_edges_image(const GBuffer& g) {
  QImage image(g.width(), g.height(), QImage::Format_ARGB32);
  image.fill(Qt::transparent);
  const QRgb edge = kGeometryEdgeColour.rgba();
  const auto differ = [&](int x, int y, int nx, int ny) {
    const bool a = g.central(x, y).hit, b = g.central(nx, ny).hit;
    return a != b || (a && !g.same_surface(x, y, nx, ny));
  };
  for (int y = 0; y < g.height(); ++y)
    for (int x = 0; x < g.width(); ++x)
      if ((x + 1 < g.width() && differ(x, y, x + 1, y)) || (y + 1 < g.height() && differ(x, y, x, y + 1)))
        image.setPixel(x, y, edge);
  return image;
}

}  // namespace relight::gui
