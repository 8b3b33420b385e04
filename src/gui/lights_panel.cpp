#include "gui/lights_panel.h"

#include <QGroupBox>
#include <QHBoxLayout>
#include <QListView>
#include <QPushButton>
#include <QSplitter>
#include <QVBoxLayout>

#include "gui/environment_entry.h"
#include "gui/geometry_view.h"
#include "gui/light_details.h"
#include "gui/light_list_model.h"
#include "gui/lighting_document.h"

namespace relight::gui {

LightsPanel::LightsPanel(QWidget* parent)
    : QWidget(parent),
      geometry_(new GeometryView),
      model_(new LightListModel(this)),
      environment_(new EnvironmentEntry),
      list_(new QListView),
      new_button_(new QPushButton(tr("&New\u2026"))),
      change_button_(new QPushButton(tr("&Change\u2026"))),
      delete_button_(new QPushButton(tr("&Delete"))),
      details_(new LightDetails) {
  geometry_->setObjectName("geometry_view");
  list_->setObjectName("light_list");
  list_->setModel(model_);
  list_->setItemDelegate(new EyeToggleDelegate(list_));
  list_->setIconSize(QSize(20, 20));
  list_->setSpacing(2);
  list_->setFocusPolicy(Qt::NoFocus);  // the keys move lights (geometry view), not the list's cursor
  list_->setSelectionMode(QAbstractItemView::SingleSelection);
  connect(list_->selectionModel(), &QItemSelectionModel::currentChanged, this,
          [this](const QModelIndex& current) { emit lightSelected(current.isValid() ? current.row() : -1); });
  connect(list_, &QListView::doubleClicked, this, &LightsPanel::changeRequested);

  new_button_->setToolTip(tr("Add a light (Insert)"));
  change_button_->setToolTip(tr("Edit the selected light (Enter, or double-click it)"));
  delete_button_->setToolTip(tr("Delete the selected light (Del)"));
  connect(new_button_, &QPushButton::clicked, this, &LightsPanel::newRequested);
  connect(change_button_, &QPushButton::clicked, this, &LightsPanel::changeRequested);
  connect(delete_button_, &QPushButton::clicked, this, &LightsPanel::deleteRequested);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(new_button_);
  buttons->addWidget(change_button_);
  buttons->addWidget(delete_button_);

  auto* lights = new QGroupBox(tr("Lights"));
  auto* lights_layout = new QVBoxLayout(lights);
  lights_layout->addWidget(environment_);
  lights_layout->addWidget(list_, 1);
  lights_layout->addLayout(buttons);

  auto* splitter = new QSplitter(Qt::Vertical);
  splitter->addWidget(geometry_);
  splitter->addWidget(lights);
  splitter->addWidget(details_);
  splitter->setStretchFactor(0, 3);
  splitter->setStretchFactor(1, 2);
  splitter->setStretchFactor(2, 0);
  splitter->setChildrenCollapsible(false);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(6, 6, 2, 6);
  layout->addWidget(splitter);
}

void LightsPanel::set_document(LightingDocument* document) {
  document_ = document;
  model_->set_document(document);
  environment_->set_document(document);
  geometry_->set_document(document);
}

void LightsPanel::show_selection(int index) {
  geometry_->set_selected(index);
  const QModelIndex row = index >= 0 ? model_->index(index) : QModelIndex();
  if (list_->currentIndex() != row) {
    const QSignalBlocker block(list_->selectionModel());
    list_->selectionModel()->setCurrentIndex(row, QItemSelectionModel::ClearAndSelect);
    list_->viewport()->update();
  }
  details_->show_light(document_ && index >= 0 ? &document_->light(index) : nullptr);
}

void LightsPanel::show_details(int index) { details_->refresh_light(document_->light(index)); }

void LightsPanel::set_list_menu(const QList<QAction*>& actions) {
  list_->addActions(actions);
  list_->setContextMenuPolicy(Qt::ActionsContextMenu);
}

void LightsPanel::enable_buttons(bool open, bool selected) {
  new_button_->setEnabled(open);
  environment_->setEnabled(open);
  change_button_->setEnabled(selected);
  delete_button_->setEnabled(selected);
}

}  // namespace relight::gui
