// Shared by the fuzz targets: a scratch folder per process, the fuzz input
// written to a file for loaders that take a path, a reader of typed values
// from the fuzz bytes, and the rule every target enforces — bad input must
// surface as relight::InputError (the CLI's exit 2); any other exception or
// a broken invariant is a bug and aborts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

// libFuzzer's entry points, also called by replay_main.cpp.
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace relight::fuzz {

// A folder of this process, removed at exit. The first call also silences
// the log and lowers the image size limit, so that a forged header costs
// the fuzzer little time and memory.
const std::filesystem::path& scratch_folder();

// Writes bytes to scratch_folder()/name and returns the path.
std::filesystem::path write_input(const std::string& name, std::string_view bytes);

// Runs load(); returns false when it threw InputError (bad input, handled),
// true when it succeeded. Any other exception aborts.
bool loads_or_rejects(const std::function<void()>& load);

// Aborts with a message when an invariant does not hold.
void check(bool ok, const char* what);

// Typed values taken from the front of the fuzz input; zeros once it runs out.
class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  uint8_t byte();
  // A float in [0, 1) from 24 bits.
  float unit();
  // A float in [lo, hi].
  float in_range(float lo, float hi) { return lo + (hi - lo) * unit(); }
  // Any 32-bit pattern as a float (NaN, infinities and denormals included).
  float raw_float();
  size_t left() const { return size_; }

 private:
  const uint8_t* data_;
  size_t size_;
};

}  // namespace relight::fuzz
