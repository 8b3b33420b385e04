#include "io/scene_folder_reads.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <fstream>

#include "core/error.h"
#include "io/file_bytes.h"
#include "io/gltf_scene.h"

namespace relight {

namespace fs = std::filesystem;

namespace {

std::atomic<bool> g_confine{false};

// The absolute path with every symlink resolved (of the part that exists);
// an empty path (the folder of "scene.json") is the current folder.
fs::path resolved(const fs::path& p) {
  const fs::path absolute = fs::absolute(p.empty() ? fs::path(".") : p);
  std::error_code ec;
  const fs::path r = fs::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal() : r;
}

bool is_inside(const fs::path& folder, const fs::path& target) {
  const fs::path relative = target.lexically_relative(folder);
  return !relative.empty() && *relative.begin() != "..";
}

// The material libraries an OBJ names: the rest of each "mtllib" line, as
// Assimp takes it, relative to the OBJ's folder.
std::vector<std::pair<std::string, fs::path>> obj_material_libraries(const fs::path& obj) {
  std::vector<std::pair<std::string, fs::path>> libraries;
  std::ifstream in(obj);
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (line.rfind("mtllib", 0) != 0 || line.size() < 7 || !std::isspace((unsigned char)line[6])) continue;
    const size_t first = line.find_first_not_of(" \t", 6), last = line.find_last_not_of(" \t\r");
    if (first == std::string::npos) continue;
    libraries.emplace_back("line " + std::to_string(number) + " (mtllib)",
                           obj.parent_path() / line.substr(first, last + 1 - first));
  }
  return libraries;
}

}  // namespace

bool confine_to_scene_folder() { return g_confine.load(); }
void set_confine_to_scene_folder(bool confine) { g_confine.store(confine); }

void check_read_inside(const fs::path& folder, const fs::path& file, const std::string& where, const fs::path& target) {
  const fs::path inside = resolved(folder), read = resolved(target);
  if (is_inside(inside, read)) return;
  if (confine_to_scene_folder())
    throw InputError(file.string(), where,
                     "names a file outside the scene's folder: " + read.string() + " (the folder is " +
                         inside.string() + "; refused by --confine-to-scene-folder)");
  spdlog::warn("{}: {}: reads a file outside the scene's folder: {} (the folder is {})", file.string(), where,
               read.string(), inside.string());
}

void check_mesh_references_inside(const fs::path& folder, const fs::path& mesh) {
  std::error_code ec;
  if (!fs::is_regular_file(mesh, ec)) return;  // the mesh reader says what it is
  const std::string ext = lower_extension(mesh);
  if (ext == ".obj") {
    for (const auto& [where, library] : obj_material_libraries(mesh)) check_read_inside(folder, mesh, where, library);
  } else if (is_gltf(mesh)) {
    std::vector<std::pair<std::string, std::string>> uris;
    try {
      uris = gltf_file_uris(mesh);
    } catch (const InputError&) {
      return;  // the mesh reader says what is wrong with the file
    }
    for (const auto& [where, uri] : uris) check_read_inside(folder, mesh, where, mesh.parent_path() / uri);
  }
}

}  // namespace relight
