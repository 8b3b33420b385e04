#include "fuzz_support.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "core/error.h"
#include "io/image_io.h"

namespace relight::fuzz {

namespace fs = std::filesystem;

namespace {
void remove_scratch_folder() {
  std::error_code ignored;
  fs::remove_all(scratch_folder(), ignored);
}
}  // namespace

const fs::path& scratch_folder() {
  // Never destroyed: the exit handler that removes the folder is registered
  // while the path is made, so a path object would be destroyed before it ran.
  static const fs::path& folder = *[] {
    spdlog::set_level(spdlog::level::off);
    set_max_image_pixels(int64_t(1) << 16);  // 256 x 256: a forged size costs little, and no input needs more
    const fs::path p = fs::temp_directory_path() / ("relight_fuzz_" + std::to_string(::getpid()));
    fs::create_directories(p);
    std::atexit(remove_scratch_folder);
    return new fs::path(p);
  }();
  return folder;
}

fs::path write_input(const std::string& name, std::string_view bytes) {
  const fs::path path = scratch_folder() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  check(bool(out), "cannot write the fuzz input to the scratch folder");
  return path;
}

bool loads_or_rejects(const std::function<void()>& load) {
  try {
    load();
    return true;
  } catch (const InputError&) {
    return false;
  } catch (const std::exception& e) {
    // The CLI would report this as an internal error (exit 1): a bug.
    std::fprintf(stderr, "fuzz: bad input escaped as a non-InputError exception: %s\n", e.what());
    std::abort();
  }
}

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz: invariant broken: %s\n", what);
  std::abort();
}

uint8_t ByteReader::byte() {
  if (size_ == 0) return 0;
  --size_;
  return *data_++;
}

float ByteReader::unit() {
  const uint32_t bits = uint32_t(byte()) | uint32_t(byte()) << 8 | uint32_t(byte()) << 16;
  return float(bits) / float(1u << 24);
}

float ByteReader::raw_float() {
  uint32_t bits = 0;
  for (int i = 0; i < 4; ++i) bits |= uint32_t(byte()) << (8 * i);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

}  // namespace relight::fuzz
