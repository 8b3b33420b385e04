#include "io/json_reader.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/image.h"
#include "io/input_file.h"

namespace relight {

namespace fs = std::filesystem;

JsonReader::json JsonReader::parse_file(const fs::path& path) {
  return parse_text(path.string(), read_input_bytes(path, "a JSON file"));
}

JsonReader::json JsonReader::parse_text(const std::string& name, const std::string& text) {
  const auto line_at = [&](size_t offset) {
    return "line " +
           std::to_string(1 + std::count(text.begin(), text.begin() + long(std::min(offset, text.size())), '\n'));
  };
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    std::string what = e.what();
    const auto colon = what.rfind(": ");
    throw InputError(name, line_at(e.byte),
                     "malformed JSON (" + (colon == std::string::npos ? what : what.substr(colon + 2)) + ")");
  } catch (const json::out_of_range& e) {
    // A number beyond a double (1e400): nlohmann names the number, not where it is.
    const std::string what = e.what();
    const size_t open = what.find('\''), close = what.rfind('\'');
    const std::string number = open < close ? what.substr(open + 1, close - open - 1) : std::string();
    const size_t at = number.empty() ? std::string::npos : text.find(number);
    throw InputError(name, at == std::string::npos ? "" : line_at(at),
                     "the number " + number + " is out of range; expected a number within a double's range");
  } catch (const json::exception& e) {
    throw InputError(name, "", std::string("malformed JSON (") + e.what() + ")");
  }
}

void JsonReader::fail(const std::string& pointer, const std::string& what) const {
  throw InputError(file_, pointer.empty() ? "/" : pointer, what);
}

const JsonReader::json& JsonReader::required(const json& obj, const std::string& pointer, const char* key) const {
  expect_object(obj, pointer);
  const auto it = obj.find(key);
  if (it == obj.end()) fail(json_child(pointer, key), "missing required key");
  return *it;
}

const JsonReader::json* JsonReader::optional(const json& obj, const char* key) const {
  const auto it = obj.find(key);
  return it == obj.end() || it->is_null() ? nullptr : &*it;
}

void JsonReader::expect_object(const json& v, const std::string& pointer) const {
  if (!v.is_object()) fail(pointer, std::string("expected an object, found ") + v.type_name());
}

float JsonReader::number(const json& v, const std::string& pointer, float min, float max) const {
  if (!v.is_number()) fail(pointer, std::string("expected a number, found ") + v.type_name());
  const double d = v.get<double>();
  if (!std::isfinite(d) || d < min || d > max)
    fail(pointer, fmt::format("expected a number in [{}, {}], found {}", min, max, d));
  return float(d);
}

uint64_t JsonReader::unsigned_integer(const json& v, const std::string& pointer, uint64_t max) const {
  if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<int64_t>() >= 0))
    fail(pointer, std::string("expected a whole number of at least 0, found ") + v.dump());
  const uint64_t n = v.get<uint64_t>();
  if (n > max) fail(pointer, fmt::format("expected a whole number up to {}, found {}", max, n));
  return n;
}

float JsonReader::number_above(const json& v, const std::string& pointer, float above) const {
  const float x = number(v, pointer);
  if (!(x > above)) fail(pointer, fmt::format("expected a number greater than {}, found {}", above, x));
  return x;
}

std::string JsonReader::string(const json& v, const std::string& pointer) const {
  if (!v.is_string()) fail(pointer, std::string("expected a string, found ") + v.type_name());
  return v.get<std::string>();
}

bool JsonReader::boolean(const json& v, const std::string& pointer) const {
  if (!v.is_boolean()) fail(pointer, std::string("expected true or false, found ") + v.type_name());
  return v.get<bool>();
}

Vec3 JsonReader::vec3(const json& v, const std::string& pointer) const {
  if (!v.is_array() || v.size() != 3) fail(pointer, "expected an array of 3 numbers");
  constexpr float kLimit = 1.0e7f;  // metres or radiance: anything larger is a mistake
  return {number(v[0], json_child(pointer, size_t(0)), -kLimit, kLimit),
          number(v[1], json_child(pointer, size_t(1)), -kLimit, kLimit),
          number(v[2], json_child(pointer, size_t(2)), -kLimit, kLimit)};
}

Vec3 JsonReader::direction(const json& v, const std::string& pointer) const {
  const Vec3 d = vec3(v, pointer);
  if (d.norm() < 1e-8f) fail(pointer, "expected a non-zero direction vector");
  return d.normalized();
}

Vec3 JsonReader::color(const json& v, const std::string& pointer) const {
  if (v.is_string()) {
    const std::string s = v.get<std::string>();
    const bool ok = s.size() == 7 && s[0] == '#' &&
                    std::all_of(s.begin() + 1, s.end(), [](char c) { return std::isxdigit((unsigned char)c); });
    if (!ok) fail(pointer, "expected a colour \"#rrggbb\" or [r, g, b], found \"" + s + "\"");
    Vec3 c;
    for (int i = 0; i < 3; ++i) c[i] = srgb_decode(float(std::stoi(s.substr(1 + 2 * i, 2), nullptr, 16)) / 255.0f);
    return c;
  }
  if (!v.is_array() || v.size() != 3) fail(pointer, "expected a colour \"#rrggbb\" or [r, g, b]");
  Vec3 c;
  for (size_t i = 0; i < 3; ++i) c[int(i)] = number(v[i], json_child(pointer, i), 0.0f, 1.0e6f);
  return c;
}

void JsonReader::warn_unknown_keys(const json& obj, const std::string& pointer,
                                   std::initializer_list<const char*> known) const {
  for (const auto& item : obj.items()) {
    const std::string& key = item.key();  // not a structured binding: clang 14 cannot capture those
    if (std::none_of(known.begin(), known.end(), [&](const char* k) { return key == k; }))
      spdlog::warn("{}: {}: unknown key ignored", file_, json_child(pointer, key));
  }
}

}  // namespace relight
