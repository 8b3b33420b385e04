// ContentHash, the key of the analysis cache: a fixed function of the parts
// added (a changed value would make every cached analysis stale), each part
// counted with its length, a file hashed as its bytes.
#include "io/content_hash.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace fs = std::filesystem;
using namespace relight;

namespace {

std::string hash_of(std::initializer_list<std::string_view> parts) {
  ContentHash hash;
  for (std::string_view part : parts) hash.add_text(part);
  return hash.hex();
}

fs::path write_file(const std::string& name, const std::string& bytes) {
  const fs::path path = fs::path(testing::TempDir()) / name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

TEST(ContentHash, IsXXH3OfEachPartsLengthAndBytes) {
  // XXH3-128 of nothing (xxHash's published value), high word first.
  EXPECT_EQ(ContentHash().hex(), "99aa06d3014798d86001c324468d497f");
  // Each part as its length (8 bytes, little-endian) and then its bytes.
  EXPECT_EQ(hash_of({"relight", "scene"}), "75c8cc24be89076a039159a359ec8228");
}

TEST(ContentHash, TellsWhereOnePartEndsAndTheNextBegins) {
  EXPECT_NE(hash_of({"ab", "c"}), hash_of({"a", "bc"}));
  EXPECT_NE(hash_of({"abc"}), hash_of({"abc", ""}));
  EXPECT_EQ(hash_of({"ab", "c"}), hash_of({"ab", "c"}));
}

TEST(ContentHash, AFileHashesAsItsBytes) {
  std::string bytes(3 << 20, '\0');  // more than the 1 MiB read buffer
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = char(i * 131 % 251);
  const fs::path path = write_file("content_hash_big.bin", bytes);
  ContentHash file;
  file.add_file(path);
  EXPECT_EQ(file.hex(), hash_of({bytes}));

  bytes[2 << 20] ^= 1;  // one bit, in the third buffer's worth
  ContentHash changed;
  changed.add_file(write_file("content_hash_big.bin", bytes));
  EXPECT_NE(changed.hex(), file.hex());
}

TEST(ContentHash, AMissingFileIsBadInputNamingIt) {
  ContentHash hash;
  const fs::path missing = fs::path(testing::TempDir()) / "no_such_file.json";
  try {
    hash.add_file(missing);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_file.json"), std::string::npos) << e.what();
  }
}

}  // namespace
