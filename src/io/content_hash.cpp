#include "io/content_hash.h"

#include <xxhash.h>

#include <cstdint>
#include <fstream>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "io/input_file.h"

namespace relight {

struct ContentHash::State {
  XXH3_state_t* xxh = XXH3_createState();
  ~State() { XXH3_freeState(xxh); }
};

ContentHash::ContentHash() : state_(std::make_unique<State>()) {
  if (!state_->xxh || XXH3_128bits_reset(state_->xxh) != XXH_OK) throw std::bad_alloc();
}

ContentHash::~ContentHash() = default;

void ContentHash::add_text(std::string_view text) {
  const uint64_t length = text.size();
  XXH3_128bits_update(state_->xxh, &length, sizeof length);
  XXH3_128bits_update(state_->xxh, text.data(), text.size());
}

void ContentHash::add_file(const std::filesystem::path& path) {
  expect_input_file(path, "a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", "cannot be opened for reading");
  const uint64_t length = std::filesystem::file_size(path);
  XXH3_128bits_update(state_->xxh, &length, sizeof length);
  std::vector<char> buffer(1 << 20);
  while (in) {
    in.read(buffer.data(), std::streamsize(buffer.size()));
    XXH3_128bits_update(state_->xxh, buffer.data(), size_t(in.gcount()));
  }
  if (!in.eof()) throw InputError(path.string(), "", "could not be read to the end");
}

std::string ContentHash::hex() const {
  const XXH128_hash_t h = XXH3_128bits_digest(state_->xxh);
  return fmt::format("{:016x}{:016x}", h.high64, h.low64);
}

}  // namespace relight
