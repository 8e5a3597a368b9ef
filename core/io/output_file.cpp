#include "io/output_file.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ext/stdio_filebuf.h>
#include <fcntl.h>
#include <random>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "common/error.h"

namespace hdrf::io {

namespace fs = std::filesystem;

namespace {

thread_local OutputSet* g_current_set = nullptr;

constexpr char kSuffix[] = ".partial";
constexpr std::size_t kRandomChars = 12;  // 6 bits each
constexpr std::size_t kMaxNameBytes = 255;  // NAME_MAX of Linux file systems
constexpr std::size_t kStagingBytes = 2 + kRandomChars + (sizeof kSuffix - 1);  // "." name "." random suffix

std::string RandomChars() {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-";
  thread_local std::mt19937_64 rng([] {
    std::random_device rd;
    std::seed_seq seq{rd(), rd(), rd(), rd(), unsigned(getpid())};
    return std::mt19937_64(seq);
  }());
  std::string s(kRandomChars, 'x');
  for (char& c : s) c = kAlphabet[rng() % 64];
  return s;
}

void RemoveQuietly(const fs::path& p) {
  if (!p.empty()) ::unlink(p.c_str());
}

}  // namespace

void CheckOutputFolder(const fs::path& folder) {
  struct stat st {};
  if (::lstat(folder.c_str(), &st) != 0 || S_ISDIR(st.st_mode)) return;
  if (S_ISLNK(st.st_mode))
    throw InputError(folder, "is a symbolic link: output files are never written through links (remove it)");
  throw InputError(folder, "is not a folder: the outputs that go in it cannot be written (remove it)");
}

bool IsWithin(const fs::path& path, const fs::path& input) {
  std::error_code ec;
  if (input.empty() || !fs::exists(input, ec)) return false;
  const fs::path in = fs::weakly_canonical(input, ec);
  if (ec) return false;
  const fs::path p = fs::weakly_canonical(path, ec);
  if (ec) return false;
  const auto [i, q] = std::mismatch(in.begin(), in.end(), p.begin(), p.end());
  return i == in.end() || (std::next(i) == in.end() && i->empty());
}

void CheckReplaceable(const fs::path& file) {
  struct stat st {};
  if (::lstat(file.c_str(), &st) != 0) return;  // absent (or unreadable: the rename will say)
  if (S_ISREG(st.st_mode)) return;
  if (S_ISLNK(st.st_mode))
    throw InputError(file, "is a symbolic link: outputs are never written through links nor replace them (remove it, "
                           "or write to the file it points to by its own name)");
  if (S_ISDIR(st.st_mode)) throw InputError(file, "is a folder: an output file cannot replace it");
  throw InputError(file, "is a device, pipe or socket, not a regular file: an output cannot replace it");
}

namespace {

// Throws unless `folder` is a folder this process can create files in.
void CheckWritableFolder(const fs::path& folder, const fs::path& named) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    throw InputError(named, "its folder " + folder.string() + " does not exist (create it first)");
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    throw InputError(named, "its folder " + folder.string() + " cannot be written (" + std::strerror(errno) + ")");
}

void CheckNotAnInput(const fs::path& out, const std::vector<fs::path>& inputs) {
  for (const fs::path& in : inputs)
    if (IsWithin(out, in))
      throw InputError(out, "is " + (fs::weakly_canonical(out) == fs::weakly_canonical(in) ? std::string("") : "inside ") +
                                "an input of this command (" + in.string() + "): the output would replace what it reads");
}

}  // namespace

void CheckOutputFile(const fs::path& file, const std::vector<fs::path>& inputs, const std::vector<std::string>& extensions) {
  if (!extensions.empty()) {
    const std::string ext = file.extension().string();
    if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) {
      std::string list;
      for (const std::string& e : extensions) list += (list.empty() ? "" : " or ") + e;
      throw InputError(file, "the output's name must end in " + list + " (the format written)");
    }
  }
  CheckReplaceable(file);
  CheckNotAnInput(file, inputs);
  CheckWritableFolder(file.has_parent_path() ? file.parent_path() : fs::path("."), file);
}

void CheckOutputFolderEarly(const fs::path& folder, const std::vector<fs::path>& inputs) {
  CheckNotAnInput(folder, inputs);
  std::error_code ec;
  fs::path existing = fs::absolute(folder, ec);
  while (!existing.empty() && !fs::exists(existing, ec) && existing != existing.root_path()) existing = existing.parent_path();
  if (fs::exists(folder, ec) && !fs::is_directory(folder, ec))
    throw InputError(folder, "is not a folder: give a folder for the outputs");
  if (!fs::is_directory(existing, ec))
    throw InputError(folder, "cannot be made: " + existing.string() + " is a file, not a folder");
  if (::access(existing.c_str(), W_OK | X_OK) != 0)
    throw InputError(folder, (existing == fs::absolute(folder, ec) ? std::string("cannot be written (")
                                                                    : "cannot be made in " + existing.string() + " (") +
                                 std::strerror(errno) + ")");
}

FolderLock::FolderLock(const fs::path& folder) : file_(folder / ".hdrfusion-lock") {
  // Locked, and still the file at that name: a holder that removed the file as this one
  // opened it leaves a lock on a file nobody else will see, so take the new file instead.
  for (int attempt = 0; attempt < 10; ++attempt) {
    fd_ = ::open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd_ < 0) throw InputError(folder, std::string("cannot take the folder's lock: ") + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      char pid[32] = {};
      const ssize_t n = ::pread(fd_, pid, sizeof pid - 1, 0);
      ::close(fd_);
      fd_ = -1;
      std::string who = n > 0 ? std::string(pid, std::size_t(n)) : std::string();
      while (!who.empty() && (who.back() == '\n' || who.back() == ' ')) who.pop_back();
      throw InputError(folder, "another hdrfusion program" + (who.empty() ? std::string() : " (process " + who + ")") +
                                   " is writing into this folder; wait for it to finish or choose another folder");
    }
    struct stat held {}, named {};
    if (::fstat(fd_, &held) == 0 && ::stat(file_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev) {
      const std::string me = std::to_string(::getpid()) + "\n";
      if (::ftruncate(fd_, 0) == 0 && ::pwrite(fd_, me.data(), me.size(), 0) < 0) {
        // The process id only helps the message of a second program; the lock holds without it.
      }
      return;
    }
    ::close(fd_);
    fd_ = -1;
  }
  throw InputError(folder, "cannot take the folder's lock: it keeps changing");
}

FolderLock::~FolderLock() {
  if (fd_ < 0) return;
  ::unlink(file_.c_str());  // while held: a program waiting on this file then takes a new one
  ::close(fd_);
}

bool IsStagingFile(const fs::path& p) {
  const std::string n = p.filename().string();
  const std::size_t tail = 1 + kRandomChars + (sizeof kSuffix - 1);
  return n.size() > tail + 1 && n[0] == '.' && n.compare(n.size() - (sizeof kSuffix - 1), std::string::npos, kSuffix) == 0 &&
         n[n.size() - tail] == '.';
}

struct OutputFile::Impl {
  explicit Impl(int fd) : fd(fd), buf(fd, std::ios::out | std::ios::binary, 1 << 16), out(&buf) {}
  int fd;
  __gnu_cxx::stdio_filebuf<char> buf;  // closes fd when destroyed
  std::ostream out;
};

OutputFile::OutputFile(fs::path target) : target_(std::move(target)) {
  CheckReplaceable(target_);
  const fs::path folder = target_.has_parent_path() ? target_.parent_path() : fs::path(".");
  for (int attempt = 0; attempt < 64; ++attempt) {
    std::string hidden = ".";  // (appended piece by piece: GCC 12 warns falsely on "." + string&&)
    // A name near the file system's limit (255 bytes) is shortened here: the staging name adds
    // 22 bytes, and a 234-byte name was refused at the end of the work.
    hidden += target_.filename().string().substr(0, kMaxNameBytes - kStagingBytes);
    hidden += '.';
    hidden += RandomChars();
    hidden += kSuffix;
    const fs::path name = folder / hidden;
    const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0) {
      staging_ = name;
      impl_ = std::make_unique<Impl>(fd);
      return;
    }
    if (errno != EEXIST)
      throw InputError(target_, std::string("cannot be written: cannot create a file in its folder (") +
                                    std::strerror(errno) + ")");
  }
  throw InputError(target_, "cannot be written: no free temporary name beside it");
}

OutputFile::~OutputFile() {
  impl_.reset();
  if (!done_) RemoveQuietly(staging_);
}

std::ostream& OutputFile::stream() { return impl_->out; }

void OutputFile::Write(std::string_view bytes) {
  impl_->out.write(bytes.data(), std::streamsize(bytes.size()));
  if (!impl_->out) throw InputError(target_, "write failed (disk full?)");
}

void OutputFile::Commit() {
  if (done_) return;
  impl_->out.flush();
  bool ok = bool(impl_->out) && impl_->buf.fd() >= 0 && ::fsync(impl_->buf.fd()) == 0;
  ok = impl_->buf.close() != nullptr && ok;
  impl_.reset();
  if (!ok) throw InputError(target_, "write failed (disk full?)");
  if (OutputSet* set = OutputSet::Current()) {
    set->Stage(staging_, target_);
    done_ = true;  // the set owns the staging file now
    return;
  }
  CheckReplaceable(target_);
  if (::rename(staging_.c_str(), target_.c_str()) != 0)
    throw InputError(target_, std::string("cannot be written (rename failed: ") + std::strerror(errno) + ")");
  done_ = true;
}

OutputSet::OutputSet() {
  if (g_current_set)
    outer_ = g_current_set;
  else
    g_current_set = this;
}

OutputSet::~OutputSet() {
  if (outer_) return;
  g_current_set = nullptr;
  if (!committed_)
    for (const Staged& s : staged_) RemoveQuietly(s.staging);
}

OutputSet* OutputSet::Current() { return g_current_set; }

void OutputSet::Stage(fs::path staging, fs::path target) {
  staged_.push_back({std::move(staging), std::move(target)});
}

void OutputSet::Commit() {
  if (outer_) return;
  // Everything that can be checked before the first file moves: a half-replaced set would mix
  // two runs' outputs.
  for (const Staged& s : staged_) CheckReplaceable(s.target);
  for (std::size_t i = 0; i < staged_.size(); ++i) {
    if (::rename(staged_[i].staging.c_str(), staged_[i].target.c_str()) != 0) {
      const int err = errno;
      for (std::size_t j = i; j < staged_.size(); ++j) RemoveQuietly(staged_[j].staging);
      committed_ = true;
      throw InputError(staged_[i].target, std::string("cannot be moved into place (") + std::strerror(err) + "); " +
                                              std::to_string(i) + " of the " + std::to_string(staged_.size()) +
                                              " outputs before it were replaced");
    }
  }
  committed_ = true;
  g_current_set = nullptr;
}

void WriteFileAtomically(const fs::path& file, std::string_view content) {
  OutputFile f(file);
  f.Write(content);
  f.Commit();
}

}  // namespace hdrf::io
