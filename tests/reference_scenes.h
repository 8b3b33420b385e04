// Where the reference scenes are: $RELIGHT_SCENES, else ../shared/scenes
// beside the source tree. Tests on them skip where the folder is absent.
#pragma once

#include <cstdlib>
#include <filesystem>

namespace relight::test {

inline std::filesystem::path reference_scenes_folder() {
  if (const char* env = std::getenv("RELIGHT_SCENES")) return env;
  return std::filesystem::path(RELIGHT_SOURCE_DIR) / ".." / "shared" / "scenes";
}

}  // namespace relight::test
