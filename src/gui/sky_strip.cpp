#include "gui/sky_strip.h"

#include <QMouseEvent>
#include <QPainter>
#include <algorithm>
#include <cmath>

#include "gui/tone_map.h"

namespace relight::gui {

float wrapped_turn(float degrees) { return degrees - 360.0f * std::floor((degrees + 180.0f) / 360.0f); }

QImage sky_thumbnail(const Probe& sky, int width) {
  const int height = std::max(1, width / 2);
  const ProbeFrame frame(sky.forward, sky.up);
  const Image& image = sky.image;
  Image strip(width, height);
  double luminance_sum = 0.0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Vec2 uv((x + 0.5f) / width, (y + 0.5f) / height);
      const std::optional<Vec3> d = probe_uv_to_direction(ProbeMapping::equirect, frame, uv);
      if (!d) continue;
      const Vec2 at = probe_direction_to_uv(sky.mapping, frame, *d);
      strip.at(x, y) = image.at(std::clamp(int(at.x() * image.width), 0, image.width - 1),
                                std::clamp(int(at.y() * image.height), 0, image.height - 1));
      luminance_sum += luminance(strip.at(x, y));
    }
  // Any sky's brightness shows: its mean at 1/2, the sun compressed.
  const float scale = luminance_sum > 0.0 ? float(0.5 * strip.size() / luminance_sum) : 1.0f;
  for (Vec3& p : strip.pixels) p = (scale * p).array() / (1.0f + scale * p.array());
  return to_qimage(strip, 0.0f);
}

SkyStrip::SkyStrip(QWidget* parent) : QWidget(parent) {
  setToolTip(tr("The new sky, all the way round: drag it sideways to turn it"));
  setCursor(Qt::SizeHorCursor);
}

void SkyStrip::set_sky(const std::optional<RigEnvironment>& sky, float turn_deg) {
  const std::shared_ptr<const Probe> image = sky ? sky->image : nullptr;
  if (image != image_) {
    image_ = image;
    thumbnail_ = image_ ? sky_thumbnail(*image_, 256) : QImage();
  }
  colour_ = sky && !image ? std::optional<Vec3>(sky->color) : std::nullopt;
  turn_deg_ = turn_deg;
  setCursor(image_ ? Qt::SizeHorCursor : Qt::ArrowCursor);
  update();
}

void SkyStrip::paintEvent(QPaintEvent*) {
  QPainter p(this);
  const QRect r = rect().adjusted(0, 0, -1, -1);
  if (colour_) {
    p.fillRect(r, display_colour(*colour_));
  } else if (thumbnail_.isNull()) {
    p.fillRect(r, palette().window());
    p.setPen(palette().color(QPalette::PlaceholderText));
    p.drawText(r, Qt::AlignCenter, tr("the scene's own environment"));
  } else {
    // A turn counter-clockwise seen from above moves the sky to the left of
    // the one who looks along forward: the strip's content shifts left.
    const double shift = -double(turn_deg_) / 360.0 * width();
    const double offset = shift - width() * std::floor(shift / width());
    p.setRenderHint(QPainter::SmoothPixmapTransform);
    for (const double x : {offset - width(), offset})
      p.drawImage(QRectF(x, 0, width(), height()), thumbnail_);
    // The horizon and the sky's forward, as opened.
    p.setPen(QPen(QColor(255, 255, 255, 110), 1, Qt::DashLine));
    p.drawLine(QPointF(0, height() / 2.0), QPointF(width(), height() / 2.0));
    const double forward = std::fmod(offset + width() / 2.0, double(width()));
    p.setPen(QPen(QColor(255, 220, 80), 2));
    p.drawLine(QPointF(forward, 0), QPointF(forward, height()));
  }
  p.setPen(palette().color(QPalette::Mid));
  p.drawRect(r);
}

float SkyStrip::turn_under_mouse(const QMouseEvent& event) const {
  const double dx = event.position().x() - drag_start_x_;
  return wrapped_turn(*drag_start_turn_ - float(dx / std::max(1, width()) * 360.0));
}

void SkyStrip::mousePressEvent(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton || !image_) return QWidget::mousePressEvent(event);
  drag_start_turn_ = turn_deg_;
  drag_start_x_ = event->position().x();
}

void SkyStrip::mouseMoveEvent(QMouseEvent* event) {
  if (!drag_start_turn_) return QWidget::mouseMoveEvent(event);
  const float turn = turn_under_mouse(*event);
  if (turn == turn_deg_) return;
  turn_deg_ = turn;
  update();
  emit turnDragged(turn);
}

void SkyStrip::mouseReleaseEvent(QMouseEvent* event) {
  if (!drag_start_turn_ || event->button() != Qt::LeftButton) return QWidget::mouseReleaseEvent(event);
  const float before = *drag_start_turn_;
  turn_deg_ = turn_under_mouse(*event);
  drag_start_turn_.reset();
  update();
  if (turn_deg_ != before) emit turnDropped(before, turn_deg_);
}

}  // namespace relight::gui
