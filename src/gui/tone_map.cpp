// oneTBB before any Qt header: Qt's `emit` macro breaks TBB's headers.
#include <tbb/parallel_for.h>

#include "gui/tone_map.h"

#include <QRegularExpression>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace relight::gui {

namespace {

// The linear values where the 8-bit sRGB code steps up: code k+1 starts at
// srgb_decode((k + 0.5) / 255). Looking a value up among them gives
// round(255 srgb_encode(x)) without a pow per channel (a frame is millions).
const std::array<float, 255>& code_boundaries() {
  static const std::array<float, 255> boundaries = [] {
    std::array<float, 255> b;
    for (int k = 0; k < 255; ++k) b[size_t(k)] = srgb_decode((float(k) + 0.5f) / 255.0f);
    return b;
  }();
  return boundaries;
}

int srgb_byte(float linear) {
  const auto& b = code_boundaries();
  return int(std::upper_bound(b.begin(), b.end(), linear) - b.begin());
}

}  // namespace

QImage to_qimage(const Image& linear, float exposure_stops) {
  const float scale = std::exp2(exposure_stops);
  QImage image(linear.width, linear.height, QImage::Format_RGB888);
  tbb::parallel_for(0, linear.height, [&](int y) {
    uchar* row = image.scanLine(y);
    for (int x = 0; x < linear.width; ++x) {
      const Vec3 v = linear.at(x, y) * scale;
      for (int c = 0; c < 3; ++c) row[3 * x + c] = uchar(srgb_byte(v[c]));
    }
  });
  return image;
}

float display_exposure_for(const Image& photo) {
  std::vector<float> peaks;
  peaks.reserve(photo.size());
  for (const Vec3& p : photo.pixels)
    if (p.allFinite()) peaks.push_back(p.maxCoeff());
  if (peaks.empty()) return 0.0f;
  const auto at = peaks.begin() + std::ptrdiff_t(0.99 * double(peaks.size() - 1));
  std::nth_element(peaks.begin(), at, peaks.end());
  if (!(*at > 0.0f)) return 0.0f;
  return std::clamp(std::round(-2.0f * std::log2(*at)) / 2.0f, -10.0f, 10.0f);
}

QColor display_colour(const Vec3& linear) {
  const float peak = linear.maxCoeff();
  const Vec3 c = peak > 1.0f ? Vec3(linear / peak) : linear;
  return QColor(srgb_byte(c.x()), srgb_byte(c.y()), srgb_byte(c.z()));
}

QString colour_hex(const Vec3& linear) {
  return QStringLiteral("#%1%2%3")
      .arg(srgb_byte(linear.x()), 2, 16, QLatin1Char('0'))
      .arg(srgb_byte(linear.y()), 2, 16, QLatin1Char('0'))
      .arg(srgb_byte(linear.z()), 2, 16, QLatin1Char('0'));
}

std::optional<Vec3> colour_from_hex(const QString& hex) {
  static const QRegularExpression pattern(QStringLiteral("^#([0-9a-fA-F]{2})([0-9a-fA-F]{2})([0-9a-fA-F]{2})$"));
  const QRegularExpressionMatch m = pattern.match(hex.trimmed());
  if (!m.hasMatch()) return std::nullopt;
  Vec3 c;
  for (int i = 0; i < 3; ++i) c[i] = srgb_decode(float(m.captured(i + 1).toInt(nullptr, 16)) / 255.0f);
  return c;
}

}  // namespace relight::gui
