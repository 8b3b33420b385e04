#include "io/input_file.h"

#include <fstream>
#include <sstream>
#include <string>

#include "core/error.h"
#include "io/output_guard.h"

namespace relight {

namespace fs = std::filesystem;

void expect_input_file(const fs::path& path, const char* expected) {
  const std::string name = path.string();
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);  // no exception: a too-long name is bad input too
  if (status.type() == fs::file_type::not_found) throw InputError(name, "", "file not found");
  if (ec) throw InputError(name, "", "cannot be read (" + ec.message() + ")");
  if (status.type() == fs::file_type::directory)
    throw InputError(name, "", std::string("is a folder, expected ") + expected);
  if (status.type() != fs::file_type::regular)
    throw InputError(name, "", std::string("is not a regular file (a device or a pipe?), expected ") + expected);
  note_input_file(path);
}

std::string read_input_bytes(const fs::path& path, const char* expected) {
  expect_input_file(path, expected);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", "cannot be opened for reading");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace relight
