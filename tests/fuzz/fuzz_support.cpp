#include "fuzz_support.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "common/error.h"

namespace hdrf::fuzz {

namespace fs = std::filesystem;

namespace {
fs::path Scratch() {
  static const fs::path dir = [] {
    std::error_code ec;
    const fs::path base = fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
    fs::path d = base / ("hdrfusion-fuzz-" + std::to_string(getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}
}  // namespace

fs::path AsFile(const std::uint8_t* data, std::size_t size, const char* name) {
  const fs::path p = Scratch() / name;
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  out.close();
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", p.c_str());
    std::abort();
  }
  return p;
}

void Expect(const std::function<void()>& read) {
  try {
    read();
  } catch (const Error&) {
    // A refusal naming the file: the expected outcome for most inputs.
  }
}

}  // namespace hdrf::fuzz
