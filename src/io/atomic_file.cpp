#include "io/atomic_file.h"

#include <fcntl.h>
#include <spdlog/spdlog.h>
#include <sys/file.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>

#include "core/error.h"
#include "io/output_guard.h"

namespace relight {

namespace fs = std::filesystem;

namespace {

std::atomic<bool> g_force{false};

// ------------------------------------------------ temporaries and signals
//
// The live temporaries, in fixed slots a signal handler can read without
// allocating. Every change to the slots, and every commit, runs inside a
// Section; a handler that finds one in progress leaves the signal pending
// and the section's end delivers it, so a signal never lands between two
// renames of a commit nor on a half-written slot.

constexpr int kSlots = 128;
struct Slot {
  std::atomic<int> state{0};  // 0 free, 1 live, 2 being filled
  char path[PATH_MAX] = {};
};
Slot g_slots[kSlots];
std::atomic<int> g_sections{0};  // sections in progress; -1 once a handler is ending the process
std::atomic<int> g_pending_signal{0};
pid_t g_owner = 0;  // the process that installed the handler

[[noreturn]] void remove_temporaries_and_die(int sig) {
  for (Slot& slot : g_slots)
    if (slot.state.load() == 1) ::unlink(slot.path);
  ::signal(sig, SIG_DFL);
  ::raise(sig);  // in a handler the signal is blocked: it ends the process as the handler returns
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, sig);
  ::sigprocmask(SIG_UNBLOCK, &set, nullptr);
  ::_exit(128 + sig);
}

void on_signal(int sig) {
  if (::getpid() != g_owner) {  // a forked child (the mesh reader): its parent's temporaries are not its own
    ::signal(sig, SIG_DFL);
    ::raise(sig);
    return;
  }
  int idle = 0;
  if (!g_sections.compare_exchange_strong(idle, -1)) {
    g_pending_signal.store(sig);  // the section in progress delivers it when it ends
    return;
  }
  remove_temporaries_and_die(sig);
}

// Signals whose default action ends the process get the handler above; one a
// program has taken over (the command line's Ctrl-C cancels) or ignores
// (nohup) is left alone.
void install_signal_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    g_owner = ::getpid();
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old = {};
      if (::sigaction(sig, nullptr, &old) != 0 || (old.sa_flags & SA_SIGINFO) || old.sa_handler != SIG_DFL) continue;
      struct sigaction action = {};
      action.sa_handler = on_signal;
      sigemptyset(&action.sa_mask);
      for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&action.sa_mask, s);
      action.sa_flags = SA_RESTART;
      ::sigaction(sig, &action, nullptr);
    }
  });
}

class Section {
 public:
  Section() {
    for (;;) {
      int n = g_sections.load();
      if (n < 0) {
        for (;;) ::pause();  // a handler is removing the temporaries and ending the process
      }
      if (g_sections.compare_exchange_weak(n, n + 1)) return;
    }
  }
  ~Section() {
    if (g_sections.fetch_sub(1) != 1) return;
    const int sig = g_pending_signal.exchange(0);
    if (sig == 0) return;
    int idle = 0;
    if (g_sections.compare_exchange_strong(idle, -1))
      remove_temporaries_and_die(sig);
    else
      g_pending_signal.store(sig);  // another section began: it delivers the signal
  }
  Section(const Section&) = delete;
  Section& operator=(const Section&) = delete;
};

// Registers a temporary's path; -1 where every slot is taken or the path is
// too long for one (the temporary then goes only with an exception).
int register_temporary(const fs::path& path) {
  const std::string& name = path.native();
  if (name.size() >= PATH_MAX) return -1;
  const Section section;
  for (int i = 0; i < kSlots; ++i) {
    Slot& slot = g_slots[i];
    int free = 0;
    if (!slot.state.compare_exchange_strong(free, 2)) continue;  // sections may run on several threads
    std::memcpy(slot.path, name.c_str(), name.size() + 1);
    slot.state.store(1);
    return i;
  }
  return -1;
}

void forget_temporary(int slot) {
  if (slot >= 0) g_slots[slot].state.store(0);
}

// ------------------------------------------------------------ the target

// What a replaced file keeps.
struct Previous {
  bool exists = false;
  mode_t mode = 0;
  uid_t uid = 0;
  gid_t gid = 0;
};

std::string file_kind(mode_t mode) {
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISFIFO(mode)) return "a pipe (FIFO)";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Throws InputError unless `target` is absent or a regular file this command
// may replace.
Previous inspect_target(const fs::path& target) {
  const std::string name = target.string();
  struct stat st;
  if (::lstat(target.c_str(), &st) != 0) {
    if (errno == ENOENT) return {};
    throw InputError(name, "", std::string("cannot be written (") + std::strerror(errno) + ")");
  }
  if (S_ISLNK(st.st_mode)) {
    std::error_code ec;
    throw InputError(name, "",
                     "is a symbolic link (to " + fs::read_symlink(target, ec).string() +
                         "); relight does not write through links: name the file itself");
  }
  if (S_ISDIR(st.st_mode)) throw InputError(name, "", "is a folder, expected a file name");
  if (!S_ISREG(st.st_mode))
    throw InputError(name, "", "is " + file_kind(st.st_mode) + "; relight writes only regular files");
  const bool read_only = (st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0 || ::access(target.c_str(), W_OK) != 0;
  if (read_only && !g_force.load())
    throw InputError(name, "", "is read-only; relight --force replaces it (keeping its mode)");
  check_output_is_not_an_input(target);
  return {true, st.st_mode & 07777, st.st_uid, st.st_gid};
}

fs::path folder_of(const fs::path& target) { return target.has_parent_path() ? target.parent_path() : fs::path("."); }

// ---------------------------------------------------------- a temporary

struct Temporary {
  fs::path path;
  int slot = -1;
  mode_t mode = 0;  // what a new file gets (0666 less the umask)
};

std::string random_name_part() {
  constexpr char kAlphabet[] = "abcdefghijklmnopqrstuvwxyz0123456789";
  unsigned char bytes[12];
  if (::getrandom(bytes, sizeof bytes, 0) != ssize_t(sizeof bytes))
    throw std::runtime_error(std::string("getrandom failed: ") + std::strerror(errno));
  std::string s;
  for (unsigned char b : bytes) s += kAlphabet[b % 36];
  return s;
}

// A new file beside `target`, created exclusively (O_EXCL, so a file or a
// link planted at the name is never opened) under an unpredictable name of
// at most 21 bytes plus the target's extension: any name the folder can hold
// has a temporary.
Temporary create_temporary(const fs::path& target) {
  install_signal_handlers();
  std::string extension = target.extension().string();
  if (extension.size() > 16) extension.clear();
  for (int attempt = 0; attempt < 100; ++attempt) {
    const fs::path path = folder_of(target) / (".relight-" + random_name_part() + extension);
    Temporary temp{path, register_temporary(path)};
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0) {
      const int error = errno;
      {
        const Section section;
        forget_temporary(temp.slot);
      }
      if (error == EEXIST) continue;
      throw InputError(
          target.string(), "",
          "cannot be written: no file can be made in its folder (" + std::string(std::strerror(error)) + ")");
    }
    struct stat st;
    ::fstat(fd, &st);
    temp.mode = st.st_mode & 07777;
    ::fchmod(fd, S_IRUSR | S_IWUSR);  // private while it is written
    ::close(fd);
    return temp;
  }
  throw InputError(target.string(), "", "cannot be written: no free temporary name in its folder");
}

void remove_temporary(const Temporary& temp) {
  const Section section;
  ::unlink(temp.path.c_str());
  forget_temporary(temp.slot);
}

// Gives the written temporary the mode (and owner, where allowed) of the
// file it replaces, and flushes it to disk so that after the rename a power
// cut leaves the old file or the whole new one.
void finish_temporary(const Temporary& temp, const Previous& previous, const fs::path& target) {
  const int fd = ::open(temp.path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) throw InputError(target.string(), "", "could not be written (the temporary file disappeared)");
  if (previous.exists && ::fchown(fd, previous.uid, previous.gid) != 0) {
    // Only root may give a file to another user: the new file stays the writer's.
  }
  ::fchmod(fd, previous.exists ? previous.mode : temp.mode);
  ::fsync(fd);  // best effort: a file system that cannot sync still gets the atomic rename
  ::close(fd);
}

void sync_folder(const fs::path& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

struct Staged {
  fs::path target;
  Temporary temp;
  bool renamed = false;
};

// Renames the temporaries onto their targets, all or (where a target turned
// into something that may not be replaced since it was checked) none.
void commit_files(std::vector<Staged>& files) {
  {
    const Section section;
    for (const Staged& f : files) inspect_target(f.target);
    for (Staged& f : files) {
      if (::rename(f.temp.path.c_str(), f.target.c_str()) != 0)
        throw InputError(f.target.string(), "", std::string("could not be written (") + std::strerror(errno) + ")");
      forget_temporary(f.temp.slot);
      f.renamed = true;
    }
  }
  std::vector<fs::path> folders;
  for (const Staged& f : files)
    if (std::find(folders.begin(), folders.end(), folder_of(f.target)) == folders.end())
      folders.push_back(folder_of(f.target));
  for (const fs::path& folder : folders) sync_folder(folder);
}

void remove_unrenamed(const std::vector<Staged>& files) {
  for (const Staged& f : files)
    if (!f.renamed) remove_temporary(f.temp);
}

std::pair<dev_t, ino_t> folder_id(const fs::path& folder) {
  struct stat st;
  if (::stat(folder.c_str(), &st) != 0) return {0, 0};
  return {st.st_dev, st.st_ino};
}

}  // namespace

// ---------------------------------------------------------------- batches

struct OutputBatch::State {
  std::vector<Staged> files;
  std::map<std::pair<dev_t, ino_t>, std::unique_ptr<FolderLock>> locks;  // by identity: one lock a folder

  void lock_folder(const fs::path& folder) {
    auto& lock = locks[folder_id(folder)];
    if (!lock) lock = std::make_unique<FolderLock>(folder, FolderLock::Mode::exclusive);
  }
};

namespace {
thread_local OutputBatch::State* t_batch = nullptr;
}

OutputBatch::OutputBatch() {
  if (t_batch) return;
  own_ = std::make_unique<State>();
  t_batch = own_.get();
}

OutputBatch::~OutputBatch() {
  if (!own_) return;
  t_batch = nullptr;
  remove_unrenamed(own_->files);
}

void OutputBatch::commit() {
  if (!own_) return;
  commit_files(own_->files);
  own_->files.clear();
  own_->locks.clear();
}

fs::path OutputBatch::staged(const fs::path& target) const {
  const State* state = own_ ? own_.get() : t_batch;
  for (const Staged& f : state->files)
    if (f.target == target) return f.temp.path;
  throw std::logic_error(target.string() + " is not written in this batch");
}

void check_output_folder(const fs::path& target) {
  std::error_code ec;
  if (!fs::is_directory(folder_of(target), ec))
    throw InputError(target.string(), "", "the output folder does not exist");
}

void write_atomically(const fs::path& target, const std::function<void(const fs::path&)>& write) {
  const fs::path folder = folder_of(target);
  check_output_folder(target);
  const Previous previous = inspect_target(target);
  if (t_batch) t_batch->lock_folder(folder);
  Staged staged{target, create_temporary(target)};
  try {
    write(staged.temp.path);
    finish_temporary(staged.temp, previous, target);
  } catch (...) {
    remove_temporary(staged.temp);
    throw;
  }
  if (!t_batch) {
    std::vector<Staged> files{staged};
    try {
      commit_files(files);
    } catch (...) {
      remove_unrenamed(files);
      throw;
    }
    return;
  }
  for (Staged& f : t_batch->files)
    if (f.target == target) {  // written twice in one batch: the second version wins
      remove_temporary(f.temp);
      f.temp = staged.temp;
      return;
    }
  t_batch->files.push_back(staged);
}

void write_text_atomically(const fs::path& target, const std::string& text) {
  write_atomically(target, [&](const fs::path& temp) {
    std::ofstream out(temp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw InputError(target.string(), "", "could not be written");
  });
}

void set_force_outputs(bool force) { g_force.store(force); }
bool force_outputs() { return g_force.load(); }

void create_output_folder(const fs::path& folder) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (!fs::is_directory(folder, ec)) throw InputError(folder.string(), "", "cannot create the output folder");
}

// ------------------------------------------------------------ folder lock

FolderLock::FolderLock(const fs::path& folder, Mode mode) {
  fd_ = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0)
    throw InputError(folder.string(), "", std::string("cannot be opened as a folder (") + std::strerror(errno) + ")");
  const int operation = mode == Mode::shared ? LOCK_SH : LOCK_EX;
  if (::flock(fd_, operation | LOCK_NB) == 0) return;
  if (errno != EWOULDBLOCK) return;  // a file system without locks: go on unlocked
  spdlog::warn("{}: waiting for another relight writing or reading this folder", folder.string());
  while (::flock(fd_, operation) != 0 && errno == EINTR) {
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the lock
}

}  // namespace relight
