// Bresenham's line walk (thesis 4.2.2): every pixel of the digital line
// between two pixels, both ends included, with integer steps only. The
// refinement reads pixels with it; the mesh pictures draw with it.
#pragma once

#include <cstdlib>

namespace relight {

template <class Visit>
void walk_line(int x0, int y0, int x1, int y1, Visit&& visit) {
  const int dx = std::abs(x1 - x0), sx = x0 < x1 ? 1 : -1;
  const int dy = -std::abs(y1 - y0), sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  for (;;) {
    visit(x0, y0);
    if (x0 == x1 && y0 == y1) return;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x0 += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y0 += sy;
    }
  }
}

}  // namespace relight
