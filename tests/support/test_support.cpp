#include "support/test_support.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>
#include <memory>
#include <fstream>
#include <random>

#include "io/output_file.h"
#include <sstream>

namespace hdrf::test {

namespace fs = std::filesystem;

TempDir::TempDir() {
  std::random_device rd;
  const auto base = fs::temp_directory_path();
  for (int i = 0; i < 100; ++i) {
    path_ = base / ("hdrf_test_" + std::to_string(rd()));
    if (fs::create_directory(path_)) return;
  }
  throw std::runtime_error("cannot create a temporary folder");
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

fs::path SharedDataDir() {
  if (const char* env = std::getenv("HDRF_DATA"); env && *env) {
    return fs::is_directory(env) ? fs::path(env) : fs::path();
  }
  const fs::path p = HDRF_SHARED_DATA_DIR;
  return fs::is_directory(p) ? p : fs::path();
}

fs::path SharedData(const std::string& relative) {
  const fs::path dir = SharedDataDir();
  if (dir.empty()) return {};
  const fs::path p = dir / relative;
  return fs::exists(p) ? p : fs::path();
}

void WriteText(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary);
  out << text;
}

std::string ReadText(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

CommandResult RunCommand(const std::string& command) {
  const std::string cmd = command + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  while (pipe && fgets(buf, sizeof buf, pipe)) out += buf;
  const int raw = pipe ? pclose(pipe) : -1;
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, out};
}

std::string ExpectErrorContaining(const std::function<void()>& fn,
                                  std::initializer_list<std::string> needles) {
  try {
    fn();
  } catch (const std::exception& e) {
    const std::string msg = e.what();
    for (const auto& n : needles)
      EXPECT_NE(msg.find(n), std::string::npos) << "message '" << msg << "' lacks '" << n << "'";
    return msg;
  }
  ADD_FAILURE() << "expected an error, none was thrown";
  return {};
}

}  // namespace hdrf::test

namespace hdrf::test {

bool EnsureDisplay(int argc, char** argv) {
  bool listing = false;
  for (int i = 1; i < argc; ++i) listing |= std::string(argv[i]).rfind("--gtest_list_tests", 0) == 0;
  auto unset = [](const char* v) { return !std::getenv(v) || !*std::getenv(v); };
  if (!listing && unset("DISPLAY") && unset("HDRF_NO_XVFB") && std::system("command -v xvfb-run >/dev/null 2>&1") == 0) {
    setenv("HDRF_NO_XVFB", "1", 1);  // once: no recursion
    std::vector<char*> args = {const_cast<char*>("xvfb-run"), const_cast<char*>("-a"), const_cast<char*>("-s"),
                               const_cast<char*>("-screen 0 1920x1080x24")};
    for (int i = 0; i < argc; ++i) args.push_back(argv[i]);
    args.push_back(nullptr);
    execvp("xvfb-run", args.data());
  }
  return !listing && !unset("DISPLAY");
}

FileSizeLimit::FileSizeLimit(unsigned long long bytes) {
  rlimit r{};
  getrlimit(RLIMIT_FSIZE, &r);
  cur_ = r.rlim_cur;
  max_ = r.rlim_max;
  previous_ = std::signal(SIGXFSZ, SIG_IGN);
  r.rlim_cur = bytes;
  setrlimit(RLIMIT_FSIZE, &r);
}

FileSizeLimit::~FileSizeLimit() {
  rlimit r{};
  r.rlim_cur = cur_;
  r.rlim_max = max_;
  setrlimit(RLIMIT_FSIZE, &r);
  std::signal(SIGXFSZ, previous_);
}

std::string WithFileSizeLimit(unsigned long long bytes, const std::string& command) {
  // bash's ulimit -f counts 1024-byte blocks; an ignored SIGXFSZ stays ignored across exec.
  return "bash -c 'trap \"\" XFSZ; ulimit -f " + std::to_string((bytes + 1023) / 1024) + "; exec \"$0\" \"$@\"' " +
         command;
}

std::vector<std::filesystem::path> StagingFiles(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> found;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(folder, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec))
    if (io::IsStagingFile(it->path())) found.push_back(it->path());
  return found;
}

}  // namespace hdrf::test
