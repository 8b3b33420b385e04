// LightListModel: the lights of a LightingDocument as a list — each row its
// short description, an eye icon in the light's colour and a checkbox that
// switches the light on and off. A click on the checkbox does not change the
// document itself: it asks (enabledToggleRequested) so that the change goes
// through the undo stack.
#pragma once

#include <QAbstractListModel>

#include "gui/lighting_document.h"

namespace relight::gui {

// "lamp — point, 250 W" / "sun — sun, 3 W/m²".
QString light_summary(const Light& light);

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

 signals:
  void enabledToggleRequested(int row, bool enabled);

 private:
  LightingDocument* document_ = nullptr;
};

}  // namespace relight::gui
