#include "io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <fstream>

#include "core/error.h"

namespace relight {

namespace fs = std::filesystem;

namespace {

// Flushes a file (or folder) to the disk, so that after the rename a power
// cut leaves either the old file or the whole new one. Best effort: a file
// system that cannot sync (some network ones) still gets the atomic rename.
void sync_to_disk(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

void write_atomically(const fs::path& target, const std::function<void(const fs::path&)>& write) {
  static std::atomic<int> counter{0};
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw InputError(target.string(), "", "the output folder does not exist");
  if (fs::is_directory(target, ec)) throw InputError(target.string(), "", "is a folder, expected a file name");
  const fs::path temp = folder / ("." + target.stem().string() + ".tmp" + std::to_string(getpid()) + "-" +
                                  std::to_string(counter++) + target.extension().string());
  try {
    write(temp);
    sync_to_disk(temp);
    fs::rename(temp, target, ec);
    if (ec) throw InputError(target.string(), "", "could not be written (" + ec.message() + ")");
    sync_to_disk(folder);
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
