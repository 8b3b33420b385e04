// Atomic output: every file is written under a temporary name in its target
// folder and renamed into place, so a crash or a kill never leaves a half
// file and never destroys the previous one (a writer killed mid-write may
// leave its hidden temporary, ".NAME.tmpPID-N.EXT", beside the target). The
// temporary is flushed to disk before the rename, so a power cut cannot
// leave an empty target either.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace relight {

// Calls write(temp_path) with a temporary path beside `target` (same
// extension, so format-by-extension writers work), then renames it onto
// `target`. On any exception the temporary is removed and the target is
// untouched.
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path&)>& write);

void write_text_atomically(const std::filesystem::path& target, const std::string& text);

}  // namespace relight
