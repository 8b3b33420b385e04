#include "gui/photo_view.h"

#include <QMouseEvent>
#include <QPainter>
#include <algorithm>
#include <cmath>

#include "gui/tone_map.h"

namespace relight::gui {

PhotoView::PhotoView(QWidget* parent) : QWidget(parent) {
  setFocusPolicy(Qt::NoFocus);
  setAttribute(Qt::WA_OpaquePaintEvent);
  setCursor(Qt::CrossCursor);
  setToolTip(tr("Click a light to select it; Ctrl+click, or click with the Place Light tool (P), to put the "
                "selected light in front of the surface"));
}

void PhotoView::set_photo(std::shared_ptr<const Image> photo) {
  photo_ = std::move(photo);
  photo_image_ = photo_ ? to_qimage(*photo_, exposure_) : QImage();
  compose();
}

void PhotoView::set_relit(std::shared_ptr<const Image> relit) {
  relit_ = std::move(relit);
  relit_image_ = relit_ ? to_qimage(*relit_, exposure_) : QImage();
  compose();
}

void PhotoView::set_exposure(float stops) {
  exposure_ = stops;
  photo_image_ = photo_ ? to_qimage(*photo_, exposure_) : QImage();
  relit_image_ = relit_ ? to_qimage(*relit_, exposure_) : QImage();
  compose();
}

void PhotoView::set_split(double share) {
  split_ = std::clamp(share, 0.0, 1.0);
  compose();
}

void PhotoView::compose() {
  displayed_ = relit_image_;
  if (!displayed_.isNull() && !photo_image_.isNull() && split_ > 0.0) {
    const QImage before = photo_image_.size() == displayed_.size()
                              ? photo_image_
                              : photo_image_.scaled(displayed_.size(), Qt::IgnoreAspectRatio, Qt::SmoothTransformation);
    const int columns = int(std::lround(split_ * displayed_.width()));
    QPainter painter(&displayed_);
    painter.drawImage(QRect(0, 0, columns, displayed_.height()), before, QRect(0, 0, columns, before.height()));
  }
  update();
}

QRectF PhotoView::picture_rect() const {
  if (displayed_.isNull()) return {};
  QSizeF fitted = QSizeF(displayed_.size()).scaled(QSizeF(size()), Qt::KeepAspectRatio);
  return QRectF(QPointF(0.5 * (width() - fitted.width()), 0.5 * (height() - fitted.height())), fitted);
}

std::optional<QPointF> PhotoView::image_position(const QPointF& widget_point) const {
  const QRectF r = picture_rect();
  if (r.isEmpty() || !r.contains(widget_point)) return std::nullopt;
  return QPointF((widget_point.x() - r.left()) * displayed_.width() / r.width(),
                 (widget_point.y() - r.top()) * displayed_.height() / r.height());
}

QPointF PhotoView::widget_position(const QPointF& image_position) const {
  const QRectF r = picture_rect();
  if (r.isEmpty()) return {};
  return QPointF(r.left() + image_position.x() * r.width() / displayed_.width(),
                 r.top() + image_position.y() * r.height() / displayed_.height());
}

void PhotoView::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  painter.fillRect(rect(), QColor(28, 28, 30));
  if (displayed_.isNull()) {
    painter.setPen(QColor(170, 170, 170));
    painter.drawText(rect(), Qt::AlignCenter, tr("The re-lit photo appears here"));
    return;
  }
  const QRectF r = picture_rect();
  painter.setRenderHint(QPainter::SmoothPixmapTransform);
  painter.drawImage(r, displayed_);
  if (split_ > 0.0) {
    const double x = r.left() + split_ * r.width();
    painter.setPen(QPen(QColor(255, 255, 255, 220), 1.5));
    painter.drawLine(QPointF(x, r.top()), QPointF(x, r.bottom()));
    painter.setRenderHint(QPainter::Antialiasing);
    const QFontMetrics metrics(font());
    const auto tag = [&](const QString& text, double left) {
      const QRectF box(left, r.top() + 8, metrics.horizontalAdvance(text) + 12, metrics.height() + 4);
      painter.setPen(Qt::NoPen);
      painter.setBrush(QColor(0, 0, 0, 150));
      painter.drawRoundedRect(box, 4, 4);
      painter.setPen(Qt::white);
      painter.drawText(box, Qt::AlignCenter, text);
    };
    if (x - r.left() > 70) tag(tr("Before"), x - metrics.horizontalAdvance(tr("Before")) - 20);
    if (r.right() - x > 70) tag(tr("After"), x + 8);
  }
}

void PhotoView::mousePressEvent(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return;
  if (const auto p = image_position(event->position())) emit photoClicked(*p, event->modifiers());
}

}  // namespace relight::gui
