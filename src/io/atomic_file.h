// Safe outputs. Every file is written under a temporary name in its target's
// folder and renamed into place, so a crash or a kill never leaves a half
// file and never destroys the previous one. What is at the target must be a
// regular file relight may replace: a folder, a device, a pipe, a socket or
// a symbolic link is refused, so is a read-only file (unless forced) and any
// file the command has read (io/output_guard.h). The temporary is created
// exclusively under an unpredictable short name (".relight-XXXXXXXXXXXX.EXT"),
// flushed to disk before the rename, and removed when the process is ended by
// SIGINT, SIGTERM or SIGHUP (only SIGKILL or a power cut can leave one).
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace relight {

// Throws InputError, naming `target`, where its folder does not exist: to
// check an output before long work rather than after it.
void check_output_folder(const std::filesystem::path& target);

// Calls write(temp_path) with a fresh temporary path beside `target` (same
// extension, so format-by-extension writers work), then renames it onto
// `target`, keeping the mode (and, where allowed, the owner) of the file it
// replaces. On any exception the temporary is removed and the target is
// untouched. Throws InputError, naming the target, when the target may not be
// replaced. Inside an OutputBatch the rename waits for the batch's commit.
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path&)>& write);

void write_text_atomically(const std::filesystem::path& target, const std::string& text);

// The command line's --force: a read-only target may be replaced (keeping
// its mode), and an analysis may be written into a folder holding files of
// its names that are not of an analysis (save_analysis).
void set_force_outputs(bool force);
bool force_outputs();

// Creates output folder `folder` (and its parents) where it is not there;
// InputError naming it where it cannot be made a folder.
void create_output_folder(const std::filesystem::path& folder);

// Outputs that belong together (render's EXR and PNG, an analysis folder):
// while a batch lives, every write_atomically on this thread writes its
// temporary and leaves the target alone; commit() renames them all onto their
// targets in one step, which a signal cannot cut in two (SIGTERM, SIGHUP and
// SIGINT wait for it to end). A batch locks each folder it writes into
// (flock, exclusive) from its first file to its end, so two processes writing
// one folder take turns and never leave the files of one beside those of the
// other. Destroyed without commit() (an exception), it removes its
// temporaries and replaces nothing. A batch opened inside another joins it:
// the outermost one commits. Keep a batch's files in one folder: two batches
// locking two folders in opposite orders would wait for each other.
class OutputBatch {
 public:
  OutputBatch();
  ~OutputBatch();
  OutputBatch(const OutputBatch&) = delete;
  OutputBatch& operator=(const OutputBatch&) = delete;

  void commit();
  // The file holding the new contents of `target`, written in this batch and
  // not yet committed (its temporary), to read back before the commit.
  std::filesystem::path staged(const std::filesystem::path& target) const;

  struct State;

 private:
  std::unique_ptr<State> own_;  // null for a batch that joined an outer one
};

// A lock on a folder (flock on the folder itself), held while it lives: the
// one an OutputBatch takes while writing, or a shared one for a reader that
// must see a folder's files from one writer (render reading an analysis).
// Waits for the other holders, saying so on stderr once.
class FolderLock {
 public:
  enum class Mode { shared, exclusive };
  FolderLock(const std::filesystem::path& folder, Mode mode);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace relight
