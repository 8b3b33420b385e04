#include "gui/light_commands.h"

namespace relight::gui {

namespace {

QString quoted(const Light& light) { return QStringLiteral("\u201c%1\u201d").arg(QString::fromStdString(light.name)); }

}  // namespace

AddLightCommand::AddLightCommand(LightingDocument& document, const Light& light)
    : QUndoCommand(QStringLiteral("New light %1").arg(quoted(light))), document_(document), light_(light),
      index_(document.light_count()) {}

void AddLightCommand::redo() { document_.insert_light(index_, light_); }
void AddLightCommand::undo() { document_.remove_light(index_); }

DeleteLightCommand::DeleteLightCommand(LightingDocument& document, int index)
    : QUndoCommand(QStringLiteral("Delete light %1").arg(quoted(document.light(index)))), document_(document),
      light_(document.light(index)), index_(index) {}

void DeleteLightCommand::redo() { document_.remove_light(index_); }
void DeleteLightCommand::undo() { document_.insert_light(index_, light_); }

EditLightCommand::EditLightCommand(LightingDocument& document, int index, const Light& before, const Light& after,
                                   const QString& text, Merge merge)
    : QUndoCommand(text), document_(document), index_(index), before_(before), after_(after), merge_(merge) {}

void EditLightCommand::redo() { document_.set_light(index_, after_); }
void EditLightCommand::undo() { document_.set_light(index_, before_); }

bool EditLightCommand::mergeWith(const QUndoCommand* other) {
  const auto* edit = static_cast<const EditLightCommand*>(other);
  if (edit->index_ != index_) return false;
  after_ = edit->after_;
  return true;
}

EnvironmentScaleCommand::EnvironmentScaleCommand(LightingDocument& document, float before, float after)
    : QUndoCommand(QStringLiteral("Ambient light \u00d7%1").arg(double(after))), document_(document),
      before_(before), after_(after) {}

void EnvironmentScaleCommand::redo() { document_.set_environment_scale(after_); }
void EnvironmentScaleCommand::undo() { document_.set_environment_scale(before_); }

bool EnvironmentScaleCommand::mergeWith(const QUndoCommand* other) {
  after_ = static_cast<const EnvironmentScaleCommand*>(other)->after_;
  setText(QStringLiteral("Ambient light \u00d7%1").arg(double(after_)));
  return true;
}

EnvironmentCommand::EnvironmentCommand(LightingDocument& document, const SkyEdit& before, const SkyEdit& after,
                                       const QString& text, Merge merge)
    : QUndoCommand(text), document_(document), before_(before), after_(after), merge_(merge) {}

void EnvironmentCommand::redo() { document_.set_sky(after_); }
void EnvironmentCommand::undo() { document_.set_sky(before_); }

bool EnvironmentCommand::mergeWith(const QUndoCommand* other) {
  after_ = static_cast<const EnvironmentCommand*>(other)->after_;
  return true;
}

}  // namespace relight::gui
