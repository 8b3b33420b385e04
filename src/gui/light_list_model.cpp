#include "gui/light_list_model.h"

#include <QAbstractItemView>
#include <QIcon>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QPixmap>

#include "gui/tone_map.h"

namespace relight::gui {

namespace {

QString type_name(LightType type) { return type == LightType::directional ? QStringLiteral("sun") : to_string(type); }

}  // namespace

QIcon eye_icon(bool open, const QColor& iris) {
  constexpr int size = 20;
  QPixmap pixmap(size, size);
  pixmap.fill(Qt::transparent);
  QPainter p(&pixmap);
  p.setRenderHint(QPainter::Antialiasing);
  QPainterPath lid;
  lid.moveTo(2, 10);
  lid.quadTo(10, 1, 18, 10);
  if (open) {
    lid.quadTo(10, 19, 2, 10);
    p.setPen(QPen(QColor(60, 60, 60), 1.4));
    p.setBrush(Qt::white);
    p.drawPath(lid);
    p.setBrush(iris);
    p.drawEllipse(QPointF(10, 10), 4, 4);
    p.setBrush(Qt::black);
    p.drawEllipse(QPointF(10, 10), 1.5, 1.5);
  } else {
    p.setPen(QPen(QColor(150, 150, 150), 1.4));
    p.setBrush(Qt::NoBrush);
    QPainterPath closed;
    closed.moveTo(2, 9);
    closed.quadTo(10, 16, 18, 9);
    p.drawPath(closed);
    for (int x : {6, 10, 14}) p.drawLine(QPointF(x, 12.5), QPointF(x, 15.5));
  }
  return QIcon(pixmap);
}

QString light_summary(const Light& light) {
  const QString name = QString::fromStdString(light.name);
  const QString summary =
      light.type == LightType::directional
          ? QStringLiteral("%1 \u2014 sun, %2 W/m\u00b2").arg(name).arg(double(light.irradiance), 0, 'g', 4)
          : QStringLiteral("%1 \u2014 %2, %3 W").arg(name, type_name(light.type)).arg(double(light.power), 0, 'g', 4);
  return light.keys.empty() ? summary : QStringLiteral("%1, animated (%2 keys)").arg(summary).arg(light.keys.size());
}

QString animated_light_note() {
  return QStringLiteral(
      "Animated: shown and edited here as the rig gives it outside its keys; its keys are kept when the rig is "
      "saved, and `relight render --frames` renders them (frame by frame, the keys decide)");
}

LightListModel::LightListModel(QObject* parent) : QAbstractListModel(parent) {}

void LightListModel::set_document(LightingDocument* document) {
  beginResetModel();
  if (document_) disconnect(document_, nullptr, this, nullptr);
  document_ = document;
  if (document_) {
    connect(document_, &LightingDocument::lightChanged, this, [this](int row) {
      emit dataChanged(index(row), index(row));
    });
    // Lights come and go after the document has changed: the list is read
    // again (the main window restores the selection).
    for (auto signal : {&LightingDocument::lightInserted, &LightingDocument::lightRemoved})
      connect(document_, signal, this, [this] {
        beginResetModel();
        endResetModel();
      });
    connect(document_, &LightingDocument::rigReset, this, [this] {
      beginResetModel();
      endResetModel();
    });
    connect(document_, &LightingDocument::soloChanged, this, [this] {
      if (rowCount() > 0) emit dataChanged(index(0), index(rowCount() - 1));
    });
    connect(document_, &QObject::destroyed, this, [this] { set_document(nullptr); });
  }
  endResetModel();
}

int LightListModel::rowCount(const QModelIndex& parent) const {
  return parent.isValid() || !document_ ? 0 : document_->light_count();
}

QVariant LightListModel::data(const QModelIndex& index, int role) const {
  if (!document_ || !index.isValid() || index.row() >= document_->light_count()) return {};
  const Light& light = document_->light(index.row());
  switch (role) {
    case Qt::DisplayRole:
      return index.row() == document_->solo() ? tr("%1 \u2014 solo").arg(light_summary(light)) : light_summary(light);
    case Qt::ForegroundRole:  // the others, while a light is soloed: off for now
      if (document_->solo() >= 0 && index.row() != document_->solo()) return QColor(150, 150, 150);
      return {};
    case Qt::DecorationRole:
      return eye_icon(light.enabled, display_colour(light.color));
    case Qt::CheckStateRole:
      return light.enabled ? Qt::Checked : Qt::Unchecked;
    case Qt::ToolTipRole: {
      QString tip = light.enabled ? QStringLiteral("Shown: untick to switch the light off (it stays in the rig)")
                                  : QStringLiteral("Switched off: tick to show it again");
      if (!light.keys.empty()) tip += QStringLiteral(".\n") + animated_light_note();
      return tip;
    }
    default:
      return {};
  }
}

bool LightListModel::setData(const QModelIndex& index, const QVariant& value, int role) {
  if (!document_ || role != Qt::CheckStateRole || !index.isValid()) return false;
  const bool enabled = value.toInt() == Qt::Checked;
  if (enabled != document_->light(index.row()).enabled) emit enabledToggleRequested(index.row(), enabled);
  return true;
}

Qt::ItemFlags LightListModel::flags(const QModelIndex& index) const {
  return QAbstractListModel::flags(index) | Qt::ItemIsUserCheckable;
}

QRect EyeToggleDelegate::eye_rect(const QAbstractItemView& view, const QModelIndex& index) const {
  QStyleOptionViewItem option;
  option.initFrom(view.viewport());
  option.widget = &view;
  option.rect = view.visualRect(index);
  option.decorationSize = view.iconSize();
  initStyleOption(&option, index);
  return view.style()->subElementRect(QStyle::SE_ItemViewItemDecoration, &option, &view);
}

bool EyeToggleDelegate::editorEvent(QEvent* event, QAbstractItemModel* model, const QStyleOptionViewItem& option,
                                    const QModelIndex& index) {
  const auto* view = qobject_cast<const QAbstractItemView*>(option.widget);
  if (view && event->type() == QEvent::MouseButtonRelease) {
    const auto* mouse = static_cast<QMouseEvent*>(event);
    if (mouse->button() == Qt::LeftButton && eye_rect(*view, index).contains(mouse->position().toPoint())) {
      auto* lights = qobject_cast<LightListModel*>(model);
      if (lights && mouse->modifiers() & Qt::ControlModifier) {
        lights->request_solo_toggle(index.row());
        return true;
      }
      const bool on = index.data(Qt::CheckStateRole).toInt() == Qt::Checked;
      return model->setData(index, on ? Qt::Unchecked : Qt::Checked, Qt::CheckStateRole);
    }
  }
  return QStyledItemDelegate::editorEvent(event, model, option, index);
}

}  // namespace relight::gui
