// oneTBB before any Qt header: Qt's `emit` macro breaks TBB's headers.
// clang-format off
#include <tbb/parallel_for.h>

#include "gui/tone_map.h"
// clang-format on

#include <QRegularExpression>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

namespace relight::gui {

namespace {

// round(255 srgb_encode(x)) for x clamped to [0, 1] (NaN: 0), without a pow
// or a search per channel: a frame is millions of them.
class SrgbBytes {
 public:
  SrgbBytes() {
    // Code k+1 starts at srgb_decode((k + 0.5) / 255).
    for (int k = 0; k < 255; ++k) boundaries_[size_t(k)] = srgb_decode((float(k) + 0.5f) / 255.0f);
    for (uint32_t r = 0; r < kRanges; ++r) {
      const float start = std::bit_cast<float>(r << kRangeShift);
      range_codes_[r] = uint8_t(std::upper_bound(boundaries_.begin(), boundaries_.end(), start) - boundaries_.begin());
    }
  }

  int operator()(float linear) const {
    if (!(linear > 0.0f)) return 0;
    if (linear >= 1.0f) return 255;
    const int code = range_codes_[std::bit_cast<uint32_t>(linear) >> kRangeShift];
    return code < 255 && linear >= boundaries_[size_t(code)] ? code + 1 : code;
  }

 private:
  // A value in [0, 1) is looked up by its float's top bits: its exponent and
  // 8 bits of mantissa, a range of values 0.4 % wide. Neighbouring code
  // boundaries are at least 0.9 % apart, so at most one falls in a range:
  // a value's code is its range's first, or the next past that boundary.
  static constexpr int kRangeShift = 15;
  static constexpr uint32_t kRanges = 0x3F800000u >> kRangeShift;  // up to the bits of 1.0f
  std::array<float, 255> boundaries_;
  std::array<uint8_t, kRanges> range_codes_;
};

const SrgbBytes& srgb_bytes() {
  static const SrgbBytes bytes;
  return bytes;
}

int srgb_byte(float linear) { return srgb_bytes()(linear); }

}  // namespace

QImage to_qimage(const Image& linear, float exposure_stops) {
  const float scale = std::exp2(exposure_stops);
  const SrgbBytes& srgb = srgb_bytes();
  // 32 bits a pixel, as the painter draws it: an RGB888 image was
  // converted each time the picture was painted.
  QImage image(linear.width, linear.height, QImage::Format_RGB32);
  tbb::parallel_for(0, linear.height, [&](int y) {
    auto* row = reinterpret_cast<QRgb*>(image.scanLine(y));
    for (int x = 0; x < linear.width; ++x) {
      const Vec3 v = linear.at(x, y) * scale;
      row[x] = qRgb(srgb(v.x()), srgb(v.y()), srgb(v.z()));
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
