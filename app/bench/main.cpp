// hdrfusion-bench: the engine benchmark with nothing but the core (for core-only builds such
// as the GPU machine's). `hdrfusion bench --suite engine` prints the same table.
//   hdrfusion-bench [--frames N] [--device cpu|cuda|both] [--case WxHxVOXEL_MM]... [--voxel E|all]
//                   [--markdown] (a heading for docs/performance.md: the command and the machine)
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include <algorithm>

#include "common/cuda_runtime.h"
#include "common/error.h"
#include "engine_bench.h"
#include "tonemap_bench.h"

int main(int argc, char** argv) {
  using namespace hdrf;
  pipeline::EngineBenchOptions o;
  o.devices = {Device::kCpu, Device::kCuda};
  bool custom_cases = false;
  bool tonemap = false;
  bool markdown = false;
  std::string command = "hdrfusion-bench";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a != "--markdown") command += " " + a + (has_value && a != "--help" ? std::string(" ") + argv[i + 1] : "");
    if (a == "--markdown") {
      markdown = true;
    } else if (a == "--suite" && has_value) {
      const std::string s = argv[++i];
      if (s != "engine" && s != "tonemap") {
        std::fprintf(stderr, "hdrfusion-bench: --suite must be engine or tonemap, not '%s'\n", s.c_str());
        return 2;
      }
      tonemap = s == "tonemap";
    } else if (a == "--frames" && has_value) {
      o.frames = std::atoi(argv[++i]);
    } else if (a == "--device" && has_value) {
      const std::string d = argv[++i];
      if (d == "cpu") o.devices = {Device::kCpu};
      else if (d == "cuda") o.devices = {Device::kCuda};
      else if (d == "both") o.devices = {Device::kCpu, Device::kCuda};
      else { std::fprintf(stderr, "hdrfusion-bench: --device must be cpu, cuda or both, not '%s'\n", d.c_str()); return 2; }
    } else if (a == "--voxel" && has_value) {
      const std::string v = argv[++i];
      if (v == "all") {
        o.encodings = {volume::VoxelEncoding::kFull, volume::VoxelEncoding::kNoNr, volume::VoxelEncoding::kCompact};
      } else {
        try {
          o.encodings = {volume::ParseVoxelEncoding(v)};
        } catch (const std::exception& e) {
          std::fprintf(stderr, "hdrfusion-bench: %s\n", e.what());
          return 2;
        }
      }
    } else if (a == "--case" && has_value) {
      pipeline::BenchCase c{};
      if (std::sscanf(argv[++i], "%dx%dx%lf", &c.width, &c.height, &c.voxel_mm) != 3 || !(c.voxel_mm >= 1 && c.voxel_mm <= 1000)) {
        std::fprintf(stderr, "hdrfusion-bench: --case wants WIDTHxHEIGHTxVOXEL_MM, e.g. 640x480x10 (voxel 1 .. 1000 mm)\n");
        return 2;
      }
      if (!custom_cases) o.cases.clear();
      custom_cases = true;
      o.cases.push_back(c);
    } else {
      std::fprintf(stderr, "usage: hdrfusion-bench [--suite engine|tonemap] [--frames N] [--device cpu|cuda|both] [--case WxHxVOXEL_MM]... [--voxel full|no-nr|compact|all] [--markdown]\n");
      return a == "--help" ? 0 : 2;
    }
  }
  if (o.frames < 5) {
    std::fprintf(stderr, "hdrfusion-bench: --frames must be at least 5\n");
    return 2;
  }
  std::string why;
  const bool gpu = CudaAvailable(&why);
  // Asked for the GPU alone where there is none: an empty table would read as a result.
  if (!gpu && std::none_of(o.devices.begin(), o.devices.end(), [](Device d) { return d == Device::kCpu; })) {
    std::fprintf(stderr, "hdrfusion-bench: --device cuda, but no CUDA device can be used here: %s\n", why.c_str());
    return 1;
  }
  if (markdown) std::printf("%s", pipeline::MarkdownHeading(tonemap ? "Tone mapping" : "Engine", command).c_str());
  if (tonemap) {
    std::vector<Device> devices;
    for (Device d : o.devices)
      if (d == Device::kCpu || gpu) devices.push_back(d);
    const auto frames = bench::SyntheticHdrFrames();
    std::vector<std::pair<std::string, const RadianceImage*>> images;
    for (const auto& [n, img] : frames) images.emplace_back(n, &img);
    std::printf("tone-mapping bench: synthetic HDR frames at 640x480, %d timed frames after one warm-up (mantiuk06 on the\n"
                "CPU: a tenth), transfers included; GPU: %s\n\n| image | operator | device | ms | frames/s | mantiuk06 iterations |\n"
                "|---|---|---|---|---|---|\n", o.frames, gpu ? CudaDeviceDescription().c_str() : why.c_str());
    try {
      for (const auto& r : bench::RunTonemapBench(images, o.frames, devices))
        std::printf("| %s | %s | %s | %.2f | %.1f | %s |\n", r.image.c_str(), r.op.c_str(), DeviceName(r.device), r.ms,
                    1000 / r.ms, r.op == "mantiuk06" ? std::to_string(r.iterations).c_str() : "");
    } catch (const std::exception& e) {
      std::fprintf(stderr, "hdrfusion-bench: %s\n", e.what());
      return 1;
    }
    return 0;
  }
  std::printf("engine bench: synthetic room, flicker auto exposure, tracker nr+icp, %d timed frames after 5 warm-up\n"
              "GPU: %s\n\n", o.frames, gpu ? CudaDeviceDescription().c_str() : why.c_str());
  try {
    const auto rows = pipeline::RunEngineBench(o, [](const pipeline::EngineBenchRow& r) {
      std::fprintf(stderr, "  done: %s %dx%d %g mm voxels: %.1f frames/s\n", DeviceName(r.device), r.c.width, r.c.height,
                   r.c.voxel_mm, r.fps);
    });
    std::printf("%s", pipeline::EngineBenchTable(rows).c_str());
    std::printf("\nEach stage against its memory-bandwidth floor (the least bytes it must move, at the measured copy bandwidth; on the GPU the frame's upload at the bus's):\n\n%s",
                pipeline::EngineFloorTable(rows).c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hdrfusion-bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
