// An output never replaces an input. While an OutputGuard lives (the command
// line holds one for each command), every file a loader opens is noted by its
// identity (device and inode, so a hard link, a symbolic link or another
// spelling of the path is the same file), and write_atomically refuses to
// replace any of them: `render -o scene/photo.exr` or `rig scene.json -o
// scene.json` is an error naming the file, not a lost photo or scene.
#pragma once

#include <filesystem>

namespace relight {

class OutputGuard {
 public:
  OutputGuard();  // one at a time; the inputs are those opened while it lives
  ~OutputGuard();
  OutputGuard(const OutputGuard&) = delete;
  OutputGuard& operator=(const OutputGuard&) = delete;
};

// Called by expect_input_file for every file a loader opens.
void note_input_file(const std::filesystem::path& path);
// The one input a command exists to rewrite (camera-from-fspy --scene): it may
// be replaced.
void allow_replacing_input(const std::filesystem::path& path);
// Throws InputError naming `target` when it is a file the command has read.
void check_output_is_not_an_input(const std::filesystem::path& target);

}  // namespace relight
