// The cameras and KHR_lights_punctual lights of a glTF 2.0 geometry file
// (.gltf or .glb), placed in the world by its node hierarchy and converted
// to relight's units (docs/formats.md, "glTF cameras and lights").
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scene/camera.h"
#include "scene/light.h"

namespace relight {

struct GltfCamera {
  std::string node_name, camera_name;  // either names it in scene.json
  CameraSpec spec;
};

struct GltfCamerasAndLights {
  std::vector<GltfCamera> cameras;
  std::vector<Light> lights;
};

// True for the files this reads: .gltf or .glb.
bool is_gltf(const std::filesystem::path& path);

// Throws InputError naming the file and the JSON pointer of a bad value.
GltfCamerasAndLights read_gltf_cameras_and_lights(const std::filesystem::path& path);

// The files a glTF refers to: each buffer's and image's "uri" that is not a
// "data:" URI (those hold their bytes inline), as (JSON pointer, the URI
// percent-decoded). Throws InputError where the JSON cannot be read.
std::vector<std::pair<std::string, std::string>> gltf_file_uris(const std::filesystem::path& path);

// The camera a node or a camera is called `name`; InputError listing the
// names there are where none is.
CameraSpec find_gltf_camera(const std::filesystem::path& path, const GltfCamerasAndLights& contents,
                            const std::string& name);

}  // namespace relight
