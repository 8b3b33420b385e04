// LightListModel: the lights of a LightingDocument as a list — each row its
// short description, an eye icon in the light's colour and a checkbox that
// switches the light on and off; while a light is soloed, it says so and the
// others are grey. A click on the checkbox does not change the
// document itself: it asks (enabledToggleRequested) so that the change goes
// through the undo stack. EyeToggleDelegate makes a click on the eye do
// what a click on the checkbox does, and a Ctrl+click on it solo the light.
#pragma once

#include <QAbstractListModel>
#include <QIcon>
#include <QStyledItemDelegate>

#include "gui/lighting_document.h"

namespace relight::gui {

// An eye, open with an iris of colour `iris`, or closed (switched off).
QIcon eye_icon(bool open, const QColor& iris);

// "lamp — point, 250 W" / "sun — sun, 3 W/m²".
QString light_summary(const Light& light);
// What relight studio does with an animated light (one with keys).
QString animated_light_note();

class LightListModel : public QAbstractListModel {
  Q_OBJECT

 public:
  explicit LightListModel(QObject* parent = nullptr);
  // Follows `document` (null: empty list).
  void set_document(LightingDocument* document);

  int rowCount(const QModelIndex& parent = {}) const override;
  QVariant data(const QModelIndex& index, int role) const override;
  bool setData(const QModelIndex& index, const QVariant& value, int role) override;
  Qt::ItemFlags flags(const QModelIndex& index) const override;
  void request_solo_toggle(int row) { emit soloToggleRequested(row); }

 signals:
  void enabledToggleRequested(int row, bool enabled);
  void soloToggleRequested(int row);

 private:
  LightingDocument* document_ = nullptr;
};

// Draws the rows as QStyledItemDelegate does, and takes a click on a row's
// eye icon as a click on its checkbox: the eye is the first thing a Blender
// user clicks to hide a light; Ctrl+click isolates it, as in Blender.
class EyeToggleDelegate : public QStyledItemDelegate {
  Q_OBJECT

 public:
  using QStyledItemDelegate::QStyledItemDelegate;
  // Where `view` draws the eye of row `index`, in its viewport.
  QRect eye_rect(const QAbstractItemView& view, const QModelIndex& index) const;

 protected:
  bool editorEvent(QEvent* event, QAbstractItemModel* model, const QStyleOptionViewItem& option,
                   const QModelIndex& index) override;
};

}  // namespace relight::gui
