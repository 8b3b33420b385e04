// ContentHash: a 128-bit XXH3 hash (xxHash, Debian's libxxhash) of file
// contents and strings, for caches that must notice when an input changes
// (the analysis folder records the hash of the scene it was made from).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace relight {

class ContentHash {
 public:
  ContentHash();
  ~ContentHash();
  ContentHash(const ContentHash&) = delete;
  ContentHash& operator=(const ContentHash&) = delete;

  // Each part is added with its length, so ("ab", "c") and ("a", "bc") differ.
  void add_text(std::string_view text);
  // The file's bytes; throws InputError when it cannot be read.
  void add_file(const std::filesystem::path& path);
  // 32 lowercase hex digits.
  std::string hex() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace relight
