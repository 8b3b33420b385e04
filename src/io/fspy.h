// fSpy camera matches: the binary project file (.fspy) fSpy saves and the
// JSON it exports, turned into relight's camera (docs/formats.md, "fSpy").
#pragma once

#include <filesystem>

#include "scene/camera.h"

namespace relight {

struct FspyCamera {
  CameraSpec camera;
  int image_width = 0, image_height = 0;  // the image fSpy was given
};

// Reads either form; throws InputError naming the file and the problem (not
// fSpy's, an unknown project version, no camera solution, a truncated file).
FspyCamera read_fspy_camera(const std::filesystem::path& path);

}  // namespace relight
