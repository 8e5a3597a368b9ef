// Helpers shared by the tests: temporary folders, the shared real-data folder, and
// matchers for error messages.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace hdrf::test {

// A fresh, empty folder under the system temp dir, removed when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& s) const { return path_ / s; }

 private:
  std::filesystem::path path_;
};

// ../shared/data (or $HDRF_DATA) if it exists, else empty.
std::filesystem::path SharedDataDir();

// The path to a file in the shared data, or empty (the caller skips with a message).
std::filesystem::path SharedData(const std::string& relative);

void WriteText(const std::filesystem::path& file, const std::string& text);
std::string ReadText(const std::filesystem::path& file);

// Runs a shell command, capturing stdout and stderr together, and its exit status.
struct CommandResult {
  int status;
  std::string output;
};
CommandResult RunCommand(const std::string& command);

// For test programs that need an X display (OpenGL contexts, VTK): without DISPLAY, re-runs
// this program under `xvfb-run` (once; never when only listing tests) and does not return.
// Returns whether a display is there now (false: xvfb-run is missing, the tests skip).
bool EnsureDisplay(int argc, char** argv);

// A full disk, as the process sees it: while one lives, writing a file beyond `bytes` fails
// (RLIMIT_FSIZE, with SIGXFSZ ignored so that the write returns EFBIG instead of killing).
class FileSizeLimit {
 public:
  explicit FileSizeLimit(unsigned long long bytes);
  ~FileSizeLimit();
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  unsigned long long cur_, max_;
  void (*previous_)(int);
};

// The command prefix that runs a program with the same full disk (a shell's `ulimit -f`).
std::string WithFileSizeLimit(unsigned long long bytes, const std::string& command);

// The staging files (io/output_file.h) in `folder`: what a failed write must not leave.
std::vector<std::filesystem::path> StagingFiles(const std::filesystem::path& folder);

// Runs fn, expects it to throw a std::exception whose message contains every needle.
// Returns the message.
std::string ExpectErrorContaining(const std::function<void()>& fn,
                                  std::initializer_list<std::string> needles);

}  // namespace hdrf::test

#define HDRF_SKIP_WITHOUT(path_expr, what)                                              \
  do {                                                                                  \
    if ((path_expr).empty())                                                            \
      GTEST_SKIP() << "shared data not present (" << (what)                             \
                   << "); put ../shared/data beside the checkout or set HDRF_DATA";   \
  } while (0)
