#include "gui/tone_map.h"

#include <QRegularExpression>
#include <algorithm>
#include <cmath>

namespace relight::gui {

namespace {

int srgb_byte(float linear) { return int(std::lround(255.0f * srgb_encode(std::clamp(linear, 0.0f, 1.0f)))); }

}  // namespace

QImage to_qimage(const Image& linear, float exposure_stops) {
  const float scale = std::exp2(exposure_stops);
  QImage image(linear.width, linear.height, QImage::Format_RGB888);
  for (int y = 0; y < linear.height; ++y) {
    uchar* row = image.scanLine(y);
    for (int x = 0; x < linear.width; ++x) {
      const Vec3 v = linear.at(x, y) * scale;
      for (int c = 0; c < 3; ++c) row[3 * x + c] = uchar(srgb_byte(v[c]));
    }
  }
  return image;
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
