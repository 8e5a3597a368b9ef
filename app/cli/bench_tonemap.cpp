#include "cli/bench_tonemap.h"

#include <omp.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "common/cuda_runtime.h"
#include "common/error.h"
#include "io/exr.h"
#include "tonemap_bench.h"

namespace hdrf::cli {

namespace {
namespace fs = std::filesystem;

double Seconds(const std::string& cmd) {
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = std::system(cmd.c_str());
  if (rc != 0) return -1;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

int BenchTonemap(int frames, std::vector<std::string> files) {
  if (files.empty()) {
    const char* env = std::getenv("HDRF_DATA");
    const fs::path dir = fs::path(env ? env : "../shared/data") / "hdr_images";
    for (const char* f : {"Desk.exr", "CandleGlass.exr", "MtTamWest.exr", "Carrots.exr"})
      if (fs::exists(dir / f)) files.push_back((dir / f).string());
    if (files.empty())
      throw Error("bench tonemap: no images given and none in " + dir.string() + " (pass --image FILE.exr)");
  }
  std::string why;
  const bool gpu = CudaAvailable(&why);
  const bool pfstmo = std::system("command -v pfstmo_mantiuk08 >/dev/null && command -v pfsinexr >/dev/null") == 0;
  const fs::path tmp = fs::temp_directory_path() / ("hdrfusion-bench-tonemap-" + std::to_string(::getpid()));
  fs::create_directories(tmp);
  struct Cleanup {
    fs::path p;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(p, ec);
    }
  } cleanup{tmp};
  std::printf("tone mapping at 640x480, %d OpenMP threads%s%s; ours: mean of %d frames after one warm-up (mantiuk06 on\n"
              "the CPU: a tenth), transfers included; pfstmo (CPU): one run of `pfsinexr | TMO | pfsoutexr` minus the same\n"
              "pipeline without the TMO%s\n\n",
              omp_get_max_threads(), gpu ? ", GPU " : " (no GPU rows: ", gpu ? CudaDeviceDescription().c_str() : (why + ")").c_str(),
              frames, pfstmo ? "" : " (pfstmo not installed: no reference column)");
  std::printf("| image | operator | device | ours ms | ours frames/s | pfstmo ms | speed-up | mantiuk06 iterations |\n"
              "|---|---|---|---|---|---|---|---|\n");
  std::vector<Device> devices = {Device::kCpu};
  if (gpu) devices.push_back(Device::kCuda);
  for (const auto& file : files) {
    const RadianceImage img = bench::Resample(io::ReadExr(file), 640, 480);
    const fs::path vga = tmp / "vga.exr";
    io::WriteExr(vga, img, io::ExrPrecision::kFloat);
    std::map<std::string, double> ref;
    if (pfstmo) {
      const std::string in = "pfsinexr '" + vga.string() + "' | ", out = " | pfsoutexr " + (tmp / "o.exr").string() + " 2>/dev/null";
      const double t_io = Seconds(in + "cat" + out);
      for (const auto& [op, tmo] : {std::pair<std::string, std::string>{"mantiuk08", "pfstmo_mantiuk08 -q 2>/dev/null"},
                                    {"mantiuk06", "pfstmo_mantiuk06 -f 0.1 -s 0.8 2>/dev/null"}}) {
        const double t = Seconds(in + tmo + out);
        if (t > 0 && t_io > 0) ref[op] = 1000 * std::max(0.0, t - t_io);
      }
    }
    const std::string name = fs::path(file).filename().string();
    for (const auto& r : bench::RunTonemapBench({{name, &img}}, frames, devices)) {
      const auto it = ref.find(r.op);
      const std::string iters = r.op == "mantiuk06" ? std::to_string(r.iterations) : "";
      if (it != ref.end())
        std::printf("| %s | %s | %s | %.2f | %.1f | %.0f | %.1fx | %s |\n", name.c_str(), r.op.c_str(), DeviceName(r.device),
                    r.ms, 1000 / r.ms, it->second, it->second / r.ms, iters.c_str());
      else
        std::printf("| %s | %s | %s | %.2f | %.1f | - | - | %s |\n", name.c_str(), r.op.c_str(), DeviceName(r.device), r.ms,
                    1000 / r.ms, iters.c_str());
      std::fflush(stdout);
    }
  }
  return 0;
}

}  // namespace hdrf::cli
