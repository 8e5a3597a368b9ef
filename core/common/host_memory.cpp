#include "common/host_memory.h"

#include <cstdio>

namespace hdrf {

std::optional<std::size_t> AvailableHostBytes() {
  std::FILE* f = std::fopen("/proc/meminfo", "r");
  if (!f) return std::nullopt;
  char line[256];
  std::optional<std::size_t> kb;
  while (std::fgets(line, sizeof line, f)) {
    unsigned long long v = 0;
    if (std::sscanf(line, "MemAvailable: %llu kB", &v) == 1) {
      kb = std::size_t(v);
      break;
    }
  }
  std::fclose(f);
  if (!kb) return std::nullopt;
  return *kb * 1024;
}

}  // namespace hdrf
