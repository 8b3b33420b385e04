// The undoable edits of a lighting design (QUndoStack commands). Each holds
// the values before and after, so undo restores them exactly.
#pragma once

#include <QUndoCommand>

#include "gui/lighting_document.h"

namespace relight::gui {

class AddLightCommand : public QUndoCommand {
 public:
  // Appends `light` (redo) / takes it away again (undo).
  AddLightCommand(LightingDocument& document, const Light& light);
  void redo() override;
  void undo() override;

 private:
  LightingDocument& document_;
  Light light_;
  int index_;
};

class DeleteLightCommand : public QUndoCommand {
 public:
  DeleteLightCommand(LightingDocument& document, int index);
  void redo() override;
  void undo() override;  // puts it back where it was

 private:
  LightingDocument& document_;
  Light light_;
  int index_;
};

// A change to one light: moved, re-shaped, recoloured, switched on or off.
// Edits of the same kind to the same light in a row (key moves, a drag)
// merge into one undo step when pushed with a merge kind. QUndoStack never
// merges into the command at its clean index, so a save ends the run and
// undo can come back to what was saved.
class EditLightCommand : public QUndoCommand {
 public:
  // The undo command ids: apart from EnvironmentScaleCommand's (2) and
  // EnvironmentCommand's (5).
  enum class Merge { never = -1, key_move = 1, colour = 3, power = 4 };
  EditLightCommand(LightingDocument& document, int index, const Light& before, const Light& after,
                   const QString& text, Merge merge = Merge::never);
  void redo() override;
  void undo() override;
  int id() const override { return int(merge_); }
  bool mergeWith(const QUndoCommand* other) override;

 private:
  LightingDocument& document_;
  int index_;
  Light before_, after_;
  Merge merge_;
};

class EnvironmentScaleCommand : public QUndoCommand {
 public:
  EnvironmentScaleCommand(LightingDocument& document, float before, float after);
  void redo() override;
  void undo() override;
  int id() const override { return 2; }
  bool mergeWith(const QUndoCommand* other) override;  // a run of spin-box steps is one edit

 private:
  LightingDocument& document_;
  float before_, after_;
};

// A change to the Environment entry: a new sky, a turn, the eye. A run of
// turns pushed with Merge::turn (the turn field's steps) is one undo step.
class EnvironmentCommand : public QUndoCommand {
 public:
  enum class Merge { never = -1, turn = 5 };
  EnvironmentCommand(LightingDocument& document, const SkyEdit& before, const SkyEdit& after, const QString& text,
                     Merge merge = Merge::never);
  void redo() override;
  void undo() override;
  int id() const override { return int(merge_); }
  bool mergeWith(const QUndoCommand* other) override;

 private:
  LightingDocument& document_;
  SkyEdit before_, after_;
  Merge merge_;
};

}  // namespace relight::gui
