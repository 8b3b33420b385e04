// scene.json and rig.json (FORMAT.md, version 1): loading with full
// validation, and writing rigs.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/progress.h"
#include "scene/scene.h"

namespace relight {

class JsonReader;

// Reads scene.json with its photo, geometry and probes. Throws InputError
// naming the file, the JSON pointer and what was expected; Cancelled where
// `progress` is cancelled while the geometry is read.
Scene load_scene(const std::filesystem::path& path, const Progress& progress = Progress::silent());
// Frame `index` of a shot as a still: the scene with that frame's photo and
// camera (the photo read now, its aspect checked against the camera).
Scene load_shot_frame(const Scene& scene, size_t index);

Rig load_rig(const std::filesystem::path& path);

// An HDR image as a rig's new environment (relight studio's Environment
// entry): equirect where twice as wide as high, a mirror ball where square,
// in Blender's default frame (forward [1, 0, 0], up [0, 0, 1]). Throws
// InputError naming the file.
RigEnvironment load_environment_image(const std::filesystem::path& path);

// scene.json text for a scene; photo, geometry and probe paths are written
// relative to `folder` (the folder the scene.json will be in).
std::string scene_to_json(const Scene& scene, const std::filesystem::path& folder);

// The `camera` block of scene.json (principal_point only where off centre),
// and read back from where `ptr` (a JSON pointer) names it: InputError
// naming r's file and the key where it is malformed.
nlohmann::json camera_to_json(const CameraSpec& camera);
CameraSpec camera_from_json(const JsonReader& r, const nlohmann::json& v, const std::string& ptr);

// The rig as rig.json text, an environment image's path relative to `folder`
// (the folder the rig.json will be in), and written atomically.
std::string rig_to_json(const Rig& rig, const std::filesystem::path& folder = ".");
void save_rig(const std::filesystem::path& path, const Rig& rig);

}  // namespace relight
