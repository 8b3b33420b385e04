// The main window's left panel: the geometry view, the environment entry
// (EnvironmentEntry) and the list of lights (eye checkbox, short
// description) with New, Change and Delete (and a
// right-click menu of the window's light actions), and the
// selected light's details. It shows a document and a selection; what the
// user asks for comes out as signals (and the geometry view's own), for the
// window to turn into undoable edits.
#pragma once

#include <QWidget>

class QListView;
class QPushButton;

namespace relight::gui {

class EnvironmentEntry;
class GeometryView;
class LightDetails;
class LightListModel;
class LightingDocument;

class LightsPanel : public QWidget {
  Q_OBJECT

 public:
  explicit LightsPanel(QWidget* parent = nullptr);

  GeometryView& geometry_view() const { return *geometry_; }
  LightListModel& model() const { return *model_; }
  LightDetails& details() const { return *details_; }
  EnvironmentEntry& environment() const { return *environment_; }

  void set_document(LightingDocument* document);
  // Shows light `index` as selected (-1: none) in the view, the list and the details.
  void show_selection(int index);
  // Refreshes the details of light `index` (it changed).
  void show_details(int index);
  // open: a document is open and no long task runs (the environment entry
  // is editable then); selected: a light is selected too.
  void enable_buttons(bool open, bool selected);
  // What a right click on a light in the list offers (it selects the light first).
  void set_list_menu(const QList<QAction*>& actions);

 signals:
  void lightSelected(int index);  // a row of the list was chosen (-1: none)
  void newRequested();
  void changeRequested();
  void deleteRequested();

 private:
  const LightingDocument* document_ = nullptr;
  GeometryView* geometry_;
  LightListModel* model_;
  EnvironmentEntry* environment_;
  QListView* list_;
  QPushButton *new_button_, *change_button_, *delete_button_;
  LightDetails* details_;
};

}  // namespace relight::gui
