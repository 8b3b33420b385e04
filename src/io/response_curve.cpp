#include "io/response_curve.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <mutex>
#include <sstream>

#include "core/error.h"
#include "io/input_file.h"

namespace relight {

namespace fs = std::filesystem;

ResponseCurve ResponseCurve::read(const fs::path& path) {
  expect_input_file(path, "a response curve (text: rows of `encoded linear` or `encoded r g b`)");
  std::ifstream in(path);
  ResponseCurve curve;
  curve.path_ = path;
  std::string text;
  for (int number = 1; std::getline(in, text); ++number) {
    text = text.substr(0, text.find('#'));
    std::istringstream row(text);
    std::vector<double> values;
    std::string word;
    while (row >> word) {
      size_t used = 0;
      double v = 0.0;
      try {
        v = std::stod(word, &used);
      } catch (const std::exception&) {
      }
      if (used != word.size() || !std::isfinite(v))
        throw InputError(path.string(), fmt::format("line {}", number), "expected numbers, found \"" + word + "\"");
      values.push_back(v);
    }
    if (values.empty()) continue;
    const std::string where = fmt::format("line {}", number);
    if (values.size() != 2 && values.size() != 4)
      throw InputError(path.string(), where, "expected `encoded linear` or `encoded r g b`");
    if (values[0] < 0.0 || values[0] > 1.0)
      throw InputError(path.string(), where, "the encoded value must lie in [0, 1] (1 = the top code value)");
    if (!curve.encoded_.empty() && values[0] <= curve.encoded_.back())
      throw InputError(path.string(), where, "the encoded values must rise from row to row");
    curve.encoded_.push_back(float(values[0]));
    for (int c = 0; c < 3; ++c) {
      const float v = float(values.size() == 2 ? values[1] : values[1 + c]);
      auto& column = curve.linear_[c];
      if (v < 0.0f || (!column.empty() && v < column.back()))
        throw InputError(path.string(), where,
                         "the linear values must be >= 0 and never fall (a curve that falls cannot be inverted)");
      column.push_back(v);
    }
  }
  if (curve.encoded_.size() < 2 || curve.encoded_.front() != 0.0f || curve.encoded_.back() != 1.0f)
    throw InputError(path.string(), "", "the rows must run from encoded 0 to encoded 1 (two rows at least)");
  return curve;
}

Vec3 ResponseCurve::linear(const Vec3& encoded) const {
  Vec3 out;
  for (int c = 0; c < 3; ++c) {
    const float e = std::clamp(encoded[c], 0.0f, 1.0f);
    const size_t hi = std::clamp(size_t(std::upper_bound(encoded_.begin(), encoded_.end(), e) - encoded_.begin()),
                                 size_t(1), encoded_.size() - 1);
    const float t = (e - encoded_[hi - 1]) / (encoded_[hi] - encoded_[hi - 1]);
    out[c] = linear_[c][hi - 1] + t * (linear_[c][hi] - linear_[c][hi - 1]);
  }
  return out;
}

namespace {
std::mutex g_response_mutex;
fs::path g_path;
std::optional<ResponseCurve> g_curve;
}  // namespace

void set_ldr_response_file(const fs::path& path) {
  const std::lock_guard lock(g_response_mutex);
  g_path = path;
  g_curve.reset();
}

const ResponseCurve* ldr_response() {
  const std::lock_guard lock(g_response_mutex);
  if (g_path.empty()) return nullptr;
  if (!g_curve) g_curve = ResponseCurve::read(g_path);
  return &*g_curve;
}

}  // namespace relight
