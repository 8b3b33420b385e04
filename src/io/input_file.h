// The checks every loader makes before it opens a path, so that a missing
// file, a folder, a device or an unreadable path is a one-line InputError
// rather than a library's exception or a read that never ends.
#pragma once

#include <filesystem>
#include <string>

namespace relight {

// Throws InputError unless `path` is an existing regular file; `expected`
// names what it should be ("an image file"). Notes the file as an input of
// the command (io/output_guard.h), so that no output replaces it.
void expect_input_file(const std::filesystem::path& path, const char* expected);

// The whole of input file `path`, after expect_input_file's checks;
// InputError where it cannot be opened.
std::string read_input_bytes(const std::filesystem::path& path, const char* expected);

}  // namespace relight
