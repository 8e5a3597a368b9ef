// How every output file is written: never through a name someone else can plant, never
// half-written, and, for a command's whole set of outputs, all or nothing.
//
// An OutputFile is written beside its target under a name with 72 random bits, created
// exclusively (O_CREAT | O_EXCL | O_NOFOLLOW: a file or link already at that name makes the
// creation fail instead of being written through), flushed to the disk, and renamed onto the
// target only when complete. A target that exists and is not a regular file (a device, a
// pipe, a socket, a folder, a symbolic link) is refused, never replaced.
//
// While an OutputSet is open on a thread, the files committed on that thread wait for the
// set's Commit, which moves them all into place; a set destroyed without Commit (an error
// or a cancel while writing) removes them, so the previous outputs stay exactly as they were.
#pragma once

#include <filesystem>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace hdrf::io {

class OutputFile {
 public:
  // Creates the staging file beside `target` (whose folder must exist). Throws InputError
  // naming the target if it cannot be created or the target may not be replaced.
  explicit OutputFile(std::filesystem::path target);
  ~OutputFile();  // removes the staging file unless committed
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::ostream& stream();
  void Write(std::string_view bytes);  // throws InputError naming the target on failure
  const std::filesystem::path& target() const { return target_; }

  // Flushes, syncs and closes the file, then renames it onto the target (or hands it to the
  // thread's open OutputSet). Throws InputError naming the target on any failure (disk full),
  // leaving the target as it was.
  void Commit();

 private:
  struct Impl;
  std::filesystem::path target_, staging_;
  std::unique_ptr<Impl> impl_;
  bool done_ = false;
};

class OutputSet {
 public:
  OutputSet();   // a set opened inside another joins it: the outer one commits
  ~OutputSet();  // removes every staged file unless committed
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;
  void Commit();  // moves every staged file onto its target, in the order they were committed

  // Used by OutputFile::Commit: the set open on this thread, or null.
  static OutputSet* Current();
  void Stage(std::filesystem::path staging, std::filesystem::path target);

 private:
  struct Staged {
    std::filesystem::path staging, target;
  };
  std::vector<Staged> staged_;
  OutputSet* outer_ = nullptr;
  bool committed_ = false;
};

// Writes `content` to `file` as one OutputFile.
void WriteFileAtomically(const std::filesystem::path& file, std::string_view content);

// Whether `p` is the name of a staging file (what a killed process can leave behind).
bool IsStagingFile(const std::filesystem::path& p);

// Throws InputError if `file` exists and is not a regular file (it would be replaced by a
// rename or written through): outputs are only ever regular files.
void CheckReplaceable(const std::filesystem::path& file);

// Throws InputError if `folder`, a folder the programs make for their outputs (a scan's
// keyframes/), exists as anything but a real folder: files written into a link would land
// in (and replace files of) whatever it points to.
void CheckOutputFolder(const std::filesystem::path& folder);

// Whether `path` is `input` or lies inside it, however either is written (links and ".."
// resolved): an output there would replace what the command reads. False where `input`
// does not exist.
bool IsWithin(const std::filesystem::path& path, const std::filesystem::path& input);

// The checks a command makes on an output file before any work, so that a typo or a wrong
// path never costs the work: the file's folder exists and can be written, the file is not a
// link, folder or device (CheckReplaceable), it is none of `inputs` nor inside one
// (IsWithin), and where `extensions` is not empty its name ends in one of them (".exr"), so
// that one format's data is never written under another's name. Throws InputError naming
// the file and what is wrong.
void CheckOutputFile(const std::filesystem::path& file, const std::vector<std::filesystem::path>& inputs = {},
                     const std::vector<std::string>& extensions = {});

// An exclusive claim on an output folder for as long as the object lives: two programs
// writing the same folder at once would mix their outputs (the last writer winning file by
// file). Takes an advisory lock (flock) on `folder`/.hdrfusion-lock, which it creates and
// removes; throws InputError naming the folder, and the holder's process id, where another
// holds it. The folder must exist.
class FolderLock {
 public:
  explicit FolderLock(const std::filesystem::path& folder);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  std::filesystem::path file_;
  int fd_ = -1;
};

// The same for an output folder a command creates or fills: the folder (or, where it does
// not exist yet, its nearest existing parent) is a folder that can be written, and it is
// none of `inputs` nor inside one.
void CheckOutputFolderEarly(const std::filesystem::path& folder, const std::vector<std::filesystem::path>& inputs = {});

}  // namespace hdrf::io
