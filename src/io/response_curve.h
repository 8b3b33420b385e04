// A camera's or renderer's tone curve, given as what each encoded value of an
// 8/16-bit image means in linear light (`--response FILE`, docs/formats.md),
// used in place of the sRGB curve to linearise LDR photos and probes.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <vector>

#include "core/vec.h"

namespace relight {

class ResponseCurve {
 public:
  // Reads the text format of docs/formats.md; throws InputError naming the
  // file and the line for anything else.
  static ResponseCurve read(const std::filesystem::path& path);

  // The linear value of an encoded one (0 = code 0, 1 = the top code),
  // interpolated linearly between the rows, per channel.
  Vec3 linear(const Vec3& encoded) const;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::vector<float> encoded_;                // rising from 0 to 1
  std::array<std::vector<float>, 3> linear_;  // per channel, never falling
};

// The curve every later read_image of an 8/16-bit file linearises through:
// the file is read at the first such read (so that its errors are the
// command's InputErrors); an empty path restores sRGB.
void set_ldr_response_file(const std::filesystem::path& path);
// The curve set, or nothing (sRGB). Throws InputError for a bad file.
const ResponseCurve* ldr_response();

}  // namespace relight
