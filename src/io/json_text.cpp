#include "io/json_text.h"

#include <charconv>
#include <cmath>
#include <cstdlib>

namespace relight {

namespace {

// A double that holds a float's value, as the shortest decimal of the float.
double shortest_float(double value) {
  const float f = float(value);
  if (double(f) != value || !std::isfinite(f)) return value;  // not a float's value: kept
  char text[32];
  const auto end = std::to_chars(text, text + sizeof(text) - 1, f).ptr;
  *end = '\0';
  return std::strtod(text, nullptr);
}

void round_floats(nlohmann::json& j) {
  if (j.is_number_float()) {
    j = shortest_float(j.get<double>());
  } else if (j.is_structured()) {
    for (auto& child : j) round_floats(child);
  }
}

}  // namespace

std::string json_text(const nlohmann::json& j) {
  nlohmann::json rounded = j;
  round_floats(rounded);
  return rounded.dump(2) + "\n";
}

}  // namespace relight
