// JsonReader: typed, validated access to a parsed JSON document. Every error
// names the file, the JSON pointer of the value and what was expected
// (FORMAT.md's rule). Internal to io.
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/vec.h"

namespace relight {

class JsonReader {
 public:
  using json = nlohmann::json;

  // Reads and parses a file; syntax errors carry the line and column.
  static json parse_file(const std::filesystem::path& path);
  // Parses JSON text held in memory; errors name `file` as parse_file's do.
  static json parse_text(const std::string& file, const std::string& text);

  explicit JsonReader(std::string file) : file_(std::move(file)) {}
  const std::string& file() const { return file_; }

  [[noreturn]] void fail(const std::string& pointer, const std::string& what) const;

  // The member `key` of object `obj` (at `pointer`); required or optional.
  const json& required(const json& obj, const std::string& pointer, const char* key) const;
  const json* optional(const json& obj, const char* key) const;

  void expect_object(const json& v, const std::string& pointer) const;
  float number(const json& v, const std::string& pointer, float min = -3.0e38f, float max = 3.0e38f) const;
  // A number that must be strictly greater than `above`.
  float number_above(const json& v, const std::string& pointer, float above) const;
  // A whole number in [min, max] (uint64_t for seeds and counts).
  uint64_t unsigned_integer(const json& v, const std::string& pointer, uint64_t max = UINT64_MAX) const;
  std::string string(const json& v, const std::string& pointer) const;
  bool boolean(const json& v, const std::string& pointer) const;
  Vec3 vec3(const json& v, const std::string& pointer) const;
  // A non-zero vector, normalised.
  Vec3 direction(const json& v, const std::string& pointer) const;
  // [r, g, b] linear, or "#rrggbb" sRGB (linearised).
  Vec3 color(const json& v, const std::string& pointer) const;

  // Warns about keys of `obj` not in `known`.
  void warn_unknown_keys(const json& obj, const std::string& pointer, std::initializer_list<const char*> known) const;

 private:
  std::string file_;
};

inline std::string json_child(const std::string& pointer, const std::string& key) { return pointer + "/" + key; }
inline std::string json_child(const std::string& pointer, size_t index) {
  return pointer + "/" + std::to_string(index);
}

}  // namespace relight
