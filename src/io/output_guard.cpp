#include "io/output_guard.h"

#include <sys/stat.h>

#include <mutex>
#include <optional>
#include <set>
#include <utility>

#include "core/error.h"

namespace relight {

namespace fs = std::filesystem;

namespace {

using FileId = std::pair<dev_t, ino_t>;

// The active guard's inputs; loaders may run on worker threads.
std::mutex g_guards_mutex;
bool g_active = false;
std::set<FileId> g_inputs;

std::optional<FileId> file_id(const fs::path& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) return std::nullopt;
  return FileId(st.st_dev, st.st_ino);
}

}  // namespace

OutputGuard::OutputGuard() {
  const std::lock_guard lock(g_guards_mutex);
  g_active = true;
  g_inputs.clear();
}

OutputGuard::~OutputGuard() {
  const std::lock_guard lock(g_guards_mutex);
  g_active = false;
  g_inputs.clear();
}

void note_input_file(const fs::path& path) {
  const auto id = file_id(path);
  const std::lock_guard lock(g_guards_mutex);
  if (g_active && id) g_inputs.insert(*id);
}

void allow_replacing_input(const fs::path& path) {
  const auto id = file_id(path);
  const std::lock_guard lock(g_guards_mutex);
  if (id) g_inputs.erase(*id);
}

void check_output_is_not_an_input(const fs::path& target) {
  const auto id = file_id(target);
  const std::lock_guard lock(g_guards_mutex);
  if (id && g_inputs.count(*id))
    throw InputError(target.string(), "", "is an input of this command; it is not replaced (name another output)");
}

}  // namespace relight
