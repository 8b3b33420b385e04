// Reads outside a scene's folder. A scene.json names the files it is made
// of (photo, geometry, probe images), and its geometry may name more (a
// glTF's buffers and images, an OBJ's mtllib). A scene from someone else can
// name any file on the machine that way ("../../../../etc/passwd" read as a
// glTF buffer): each such file that resolves, symlinks followed, outside the
// folder the scene.json is in draws a warning naming the file that names it,
// the key and the resolved path. With confinement on (--confine-to-scene-
// folder, RELIGHT_CONFINE_TO_SCENE_FOLDER=1), for a service that takes
// scenes from others, it is an InputError before that file is read.
#pragma once

#include <filesystem>
#include <string>

namespace relight {

bool confine_to_scene_folder();
void set_confine_to_scene_folder(bool confine);

// Checks `target`, named at `where` (a JSON pointer, a line) in `file`,
// against `folder`.
void check_read_inside(const std::filesystem::path& folder, const std::filesystem::path& file, const std::string& where,
                       const std::filesystem::path& target);

// Checks the files the mesh file `mesh` refers to (glTF buffer and image
// URIs, OBJ mtllib lines) against `folder`. A file that cannot be parsed is
// left to the mesh reader to report.
void check_mesh_references_inside(const std::filesystem::path& folder, const std::filesystem::path& mesh);

}  // namespace relight
