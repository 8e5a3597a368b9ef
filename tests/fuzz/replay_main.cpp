// A main for the fuzz targets where libFuzzer is not there (GCC builds, the test suite): runs
// the target on every seed file, then on `--mutations N` inputs made from them by random
// byte edits (flips, interesting values, insertions, deletions, repeats, truncation), with a
// fixed seed so that a failure repeats. The coverage-guided runs use libFuzzer itself
// (tools/fuzz.sh); this keeps every target exercised in every test run.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

std::vector<std::uint8_t> Mutate(std::vector<std::uint8_t> b, std::mt19937_64& rng) {
  static const std::uint8_t kInteresting[] = {0, 1, 0x7f, 0x80, 0xff, '0', '9', '-', '.', 'e', ' ', '\n', '"', '{', '[', 0x7e};
  const int edits = 1 + int(rng() % 8);
  for (int e = 0; e < edits; ++e) {
    const std::size_t n = b.size();
    const std::size_t at = n ? rng() % n : 0;
    switch (rng() % 7) {
      case 0:
        if (n) b[at] ^= std::uint8_t(1u << (rng() % 8));
        break;
      case 1:
        if (n) b[at] = kInteresting[rng() % sizeof kInteresting];
        break;
      case 2:  // insert a few bytes
        b.insert(b.begin() + long(at), 1 + rng() % 16, kInteresting[rng() % sizeof kInteresting]);
        break;
      case 3:  // delete a range
        if (n) b.erase(b.begin() + long(at), b.begin() + long(std::min(n, at + 1 + rng() % 64)));
        break;
      case 4:  // repeat a range
        if (n) {
          const std::size_t len = std::min(n - at, std::size_t(1 + rng() % 64));
          const std::vector<std::uint8_t> piece(b.begin() + long(at), b.begin() + long(at + len));
          b.insert(b.begin() + long(rng() % (n + 1)), piece.begin(), piece.end());
        }
        break;
      case 5:  // truncate
        b.resize(at);
        break;
      default:  // a 32-bit value at a random place (sizes, counts)
        if (n >= 4) {
          const std::uint32_t v = rng() % 2 ? 0xffffffffu >> (rng() % 32) : std::uint32_t(rng());
          const std::size_t p = rng() % (n - 3);
          for (int k = 0; k < 4; ++k) b[p + std::size_t(k)] = std::uint8_t(v >> (8 * k));
        }
    }
  }
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  long mutations = 0;
  std::uint64_t seed = 1;
  std::vector<std::vector<std::uint8_t>> corpus;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--mutations" && i + 1 < argc) {
      mutations = std::atol(argv[++i]);
    } else if (a == "--seed" && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else {
      std::vector<std::filesystem::path> files;
      if (std::filesystem::is_directory(a)) {
        for (const auto& e : std::filesystem::directory_iterator(a))
          if (e.is_regular_file()) files.push_back(e.path());
      } else {
        files.push_back(a);
      }
      for (const auto& f : files) {
        std::ifstream in(f, std::ios::binary);
        corpus.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      }
    }
  }
  if (corpus.empty()) {
    std::fprintf(stderr, "usage: %s [--mutations N] [--seed S] SEED_FILE_OR_FOLDER...\n", argv[0]);
    return 2;
  }
  for (const auto& c : corpus) LLVMFuzzerTestOneInput(c.data(), c.size());
  std::mt19937_64 rng(seed);
  for (long m = 0; m < mutations; ++m) {
    const std::vector<std::uint8_t> in = Mutate(corpus[rng() % corpus.size()], rng);
    LLVMFuzzerTestOneInput(in.data(), in.size());
  }
  std::printf("%zu seed inputs and %ld mutations ran without a finding\n", corpus.size(), mutations);
  return 0;
}
