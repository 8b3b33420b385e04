#include "io/frame_files.h"

#include <charconv>
#include <cstdio>

namespace relight {

bool has_frame_digits(const std::filesystem::path& pattern) {
  return pattern.filename().string().find('#') != std::string::npos;
}

std::filesystem::path frame_file(const std::filesystem::path& pattern, int frame) {
  std::string name = pattern.filename().string();
  const size_t end = name.rfind('#');
  if (end == std::string::npos) return pattern;
  size_t begin = end;
  while (begin > 0 && name[begin - 1] == '#') --begin;
  const int digits = int(end - begin + 1);
  char number[32];
  std::snprintf(number, sizeof number, "%0*d", digits, frame);
  name.replace(begin, size_t(digits), number);
  return pattern.parent_path() / name;
}

std::optional<FrameRange> parse_frame_range(const std::string& text) {
  const auto whole = [](const char* begin, const char* end) -> std::optional<int> {
    int value = 0;
    const auto [at, error] = std::from_chars(begin, end, value);
    if (error != std::errc() || at != end || begin == end || value < 0) return std::nullopt;
    return value;
  };
  const char* begin = text.data();
  const char* end = begin + text.size();
  const size_t dash = text.find('-');
  if (dash == std::string::npos) {
    const auto frame = whole(begin, end);
    if (!frame) return std::nullopt;
    return FrameRange{*frame, *frame};
  }
  const auto first = whole(begin, begin + dash), last = whole(begin + dash + 1, end);
  if (!first || !last || *first > *last) return std::nullopt;
  return FrameRange{*first, *last};
}

}  // namespace relight
