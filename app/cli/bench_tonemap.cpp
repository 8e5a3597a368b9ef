#include "cli/bench_tonemap.h"

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "common/error.h"
#include "io/exr.h"
#include "tonemap/operator.h"

namespace hdrf::cli {

namespace {
namespace fs = std::filesystem;

// Area resampling to w x h (each output pixel averages the input pixels it covers).
RadianceImage Resample(const RadianceImage& in, int w, int h) {
  RadianceImage out(w, h);
  const double sx = double(in.width()) / w, sy = double(in.height()) / h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Float3 s{0, 0, 0};
      int n = 0;
      for (int j = int(y * sy); j < std::min(in.height(), int((y + 1) * sy + 0.999)); ++j)
        for (int i = int(x * sx); i < std::min(in.width(), int((x + 1) * sx + 0.999)); ++i) s += in(i, j), ++n;
      out(x, y) = n ? s / float(n) : Float3{0, 0, 0};
    }
  return out;
}

double Seconds(const std::string& cmd) {
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = std::system(cmd.c_str());
  if (rc != 0) return -1;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int BenchTonemap(int frames, std::vector<std::string> images) {
  if (images.empty()) {
    const char* env = std::getenv("HDRF_DATA");
    const fs::path dir = fs::path(env ? env : "../shared/data") / "hdr_images";
    for (const char* f : {"Desk.exr", "CandleGlass.exr", "MtTamWest.exr", "Carrots.exr"})
      if (fs::exists(dir / f)) images.push_back((dir / f).string());
    if (images.empty())
      throw Error("bench tonemap: no images given and none in " + dir.string() + " (pass --image FILE.exr)");
  }
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
  std::printf("tone mapping at 640x480, %d OpenMP threads, CPU; ours: mean of %d frames after one warm-up;\n"
              "pfstmo: one run of `pfsinexr | TMO | pfsoutexr` minus the same pipeline without the TMO%s\n\n",
              omp_get_max_threads(), frames, pfstmo ? "" : " (pfstmo not installed: no reference column)");
  std::printf("| image | operator | ours ms | ours frames/s | pfstmo ms | speed-up |\n|---|---|---|---|---|---|\n");
  for (const auto& file : images) {
    const RadianceImage img = Resample(io::ReadExr(file), 640, 480);
    const fs::path vga = tmp / "vga.exr";
    io::WriteExr(vga, img, io::ExrPrecision::kFloat);
    const std::string io_only = "pfsinexr '" + vga.string() + "' | pfsoutexr " + (tmp / "o.exr").string() + " 2>/dev/null";
    const double t_io = pfstmo ? Seconds(io_only) : -1;
    for (const std::string op : {"mantiuk08", "mantiuk06", "reinhard"}) {
      const auto& decl = tonemap::FindOperator(op);
      auto o = decl.make(tonemap::ResolveParams(decl, {}));
      Image<Float3> out;
      o->Map(img, out, tonemap::FrameTime::Still());
      const int n = op == "mantiuk06" ? std::max(1, frames / 10) : frames;
      const auto t0 = std::chrono::steady_clock::now();
      for (int i = 0; i < n; ++i) o->Map(img, out, tonemap::FrameTime::Still());
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / n;
      double ref = -1;
      if (pfstmo && op != "reinhard") {
        const std::string tmo = op == "mantiuk08" ? "pfstmo_mantiuk08 -q" : "pfstmo_mantiuk06 -f 0.1 -s 0.8";
        const double t = Seconds("pfsinexr '" + vga.string() + "' | " + tmo + " 2>/dev/null | pfsoutexr " +
                                 (tmp / "o.exr").string() + " 2>/dev/null");
        if (t > 0 && t_io > 0) ref = 1000 * std::max(0.0, t - t_io);
      }
      const std::string name = fs::path(file).filename().string();
      if (ref > 0)
        std::printf("| %s | %s | %.1f | %.1f | %.0f | %.1fx |\n", name.c_str(), op.c_str(), ms, 1000 / ms, ref, ref / ms);
      else
        std::printf("| %s | %s | %.1f | %.1f | - | - |\n", name.c_str(), op.c_str(), ms, 1000 / ms);
      std::fflush(stdout);
    }
  }
  return 0;
}

}  // namespace hdrf::cli
