// A small valid scene in a fresh temporary folder, for the command-line
// tests that break one thing in it (bad_input_test, no_lost_work_test), and
// running the command line in-process with its output captured.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli/run.h"
#include "io/image_io.h"
#include "temp_dir.h"

namespace relight::test {

namespace fs = std::filesystem;
using json = nlohmann::json;

// A floor and a closed unit cube standing on it.
inline constexpr const char* kGeometry =
    "v -3 -3 0\nv 3 -3 0\nv 3 3 0\nv -3 3 0\nf 1 2 3\nf 1 3 4\n"
    "v -0.5 -0.5 0\nv 0.5 -0.5 0\nv 0.5 0.5 0\nv -0.5 0.5 0\n"
    "v -0.5 -0.5 1\nv 0.5 -0.5 1\nv 0.5 0.5 1\nv -0.5 0.5 1\n"
    "f 5 7 6\nf 5 8 7\nf 9 10 11\nf 9 11 12\nf 5 6 10\nf 5 10 9\n"
    "f 6 7 11\nf 6 11 10\nf 7 8 12\nf 7 12 11\nf 8 5 9\nf 8 9 12\n";

inline void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

inline std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A valid 8 x 6 scene: photo.exr, geometry.obj, a point light, and a rig;
// write_json() writes `scene` as scene.json and `rig` as rig.json.
struct SceneFolder {
  TempDir folder;  // made first, removed last
  fs::path dir = folder.path();
  json scene = json::parse(R"({
    "format": "relight-scene/1", "photo": "photo.exr", "geometry": "geometry.obj",
    "camera": {"position": [0, -5, 2], "look_at": [0, 0, 0.5], "up": [0, 0, 1], "vfov_deg": 40},
    "lights": [{"type": "point", "position": [2, -2, 4], "power": 200}],
    "background": [0.3, 0.3, 0.3]
  })");
  json rig = json::parse(R"({
    "format": "relight-rig/1", "environment_scale": 0.5,
    "lights": [{"type": "spot", "position": [0, -2, 3], "direction": [0, 0.5, -1], "power": 300,
                "spot_angle_deg": 40}]
  })");
  std::optional<std::string> scene_text;  // written instead of `scene` when set (malformed JSON, 1e400)

  explicit SceneFolder(const std::string& name) : folder("scene_folder_" + name) {
    replace_photo(Image(8, 6, Vec3(0.3f, 0.25f, 0.2f)));
    write_text(dir / "geometry.obj", kGeometry);
  }

  fs::path operator/(const std::string& name) const { return dir / name; }

  void write_json() const {
    write_text(dir / "scene.json", scene_text.value_or(scene.dump(2)));
    if (!rig.is_null()) write_text(dir / "rig.json", rig.dump(2));
  }
  void replace_photo(const Image& photo) const { write_exr(dir / "photo.exr", photo); }
  // A probe image and its entry in scene.json.
  void add_probe(const std::string& mapping, int width, int height) {
    write_exr(dir / "probe.exr", Image(width, height, Vec3(0.5f, 0.5f, 0.5f)));
    scene["probes"] = json::array({{{"image", "probe.exr"}, {"mapping", mapping}, {"position", {0, 0, 1}},
                                    {"forward", {0, 1, 0}}, {"up", {0, 0, 1}}}});
  }
  // Sets scene_text to scene.json with `from` replaced by `to`.
  void replace_in_scene_text(const std::string& from, const std::string& to) {
    std::string text = scene.dump(2);
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    scene_text = text.replace(at, from.size(), to);
  }
};

struct CliResult {
  int status;
  std::string err;  // stderr
};

// relight::cli::run with argv[0] added, stdout and stderr captured.
inline CliResult run_cli(std::vector<std::string> args) {
  args.insert(args.begin(), "relight");
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const int status = cli::run(args);
  CliResult result{status, testing::internal::GetCapturedStderr()};
  testing::internal::GetCapturedStdout();
  return result;
}

// The lines of stderr other than warnings: a refusal has exactly one.
inline std::vector<std::string> error_lines(const std::string& err) {
  std::vector<std::string> lines;
  std::istringstream in(err);
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line.rfind("relight: warning:", 0) != 0) lines.push_back(line);
  return lines;
}

}  // namespace relight::test
