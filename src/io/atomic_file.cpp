#include "io/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <fstream>

#include "core/error.h"

namespace relight {

namespace fs = std::filesystem;

void write_atomically(const fs::path& target, const std::function<void(const fs::path&)>& write) {
  static std::atomic<int> counter{0};
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(folder)) throw InputError(target.string(), "", "the output folder does not exist");
  if (fs::is_directory(target)) throw InputError(target.string(), "", "is a folder, expected a file name");
  const fs::path temp = folder / ("." + target.stem().string() + ".tmp" + std::to_string(getpid()) + "-" +
                                  std::to_string(counter++) + target.extension().string());
  try {
    write(temp);
    fs::rename(temp, target);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
}

void write_text_atomically(const fs::path& target, const std::string& text) {
  write_atomically(target, [&](const fs::path& temp) {
    std::ofstream out(temp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw InputError(target.string(), "", "could not be written");
  });
}

}  // namespace relight
