// The files of a frame sequence: a name whose run of '#' stands for the
// frame number, zero-padded to as many digits (Blender's convention:
// relit.####.exr, frame 7 -> relit.0007.exr).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "scene/animation.h"

namespace relight {

// Whether the file name (not its folders) holds a run of '#'.
bool has_frame_digits(const std::filesystem::path& pattern);
// The file of frame `frame`: the last run of '#' in the name replaced.
std::filesystem::path frame_file(const std::filesystem::path& pattern, int frame);

// "12" or "1-120" (first <= last, both >= 0); none when it is neither.
std::optional<FrameRange> parse_frame_range(const std::string& text);

}  // namespace relight
