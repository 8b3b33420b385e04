// The relight-studio program: `relight-studio [SCENE.json [RIG.json]]`, and
// --screenshot to write a picture of the main form once the view has
// converged (used for the documentation).
#pragma once

namespace relight::gui {

int run_studio(int argc, char** argv);

}  // namespace relight::gui
