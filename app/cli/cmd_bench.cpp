// hdrfusion bench: speed tables of the synthetic sensor (sim) and of the engine per stage
// (engine, also hdrfusion-bench).
#include <omp.h>

#include <chrono>
#include <tuple>
#include <vector>
#include <cstdio>

#include "cli/commands.h"
#include "common/error.h"
#include "pipeline/frame_source.h"
#include "engine_bench.h"
#include "pipeline/pipeline.h"
#include "sim/synthetic_source.h"

namespace hdrf::cli {

Command AddBenchCommand(CLI::App& app) {
  struct Args {
    std::string suite = "sim";
    int frames = 60;
    std::string device = "both";
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("bench", "Measure speed and print a table");
  cmd->add_option("--suite", a->suite,
                  "sim (the synthetic sensor) or engine (per-stage times and frames/s per device and size); "
                  "the paper's experiments are hdrfusion-experiments, not part of this tool")
      ->check(CLI::IsMember({"sim", "engine"}))->capture_default_str();
  cmd->add_option("--frames", a->frames, "Timed frames per measurement")->check(CLI::Range(5, 100000))
      ->capture_default_str();
  cmd->add_option("--device", a->device, "Engine suite: cpu, cuda or both (CUDA rows where a GPU is usable)")
      ->check(CLI::IsMember({"cpu", "cuda", "both"}))->capture_default_str();
  return {cmd, [a] {
    if (a->suite == "engine") {
      pipeline::EngineBenchOptions o;
      o.frames = a->frames;
      o.devices = a->device == "cpu" ? std::vector<Device>{Device::kCpu}
                  : a->device == "cuda" ? std::vector<Device>{Device::kCuda}
                                        : std::vector<Device>{Device::kCpu, Device::kCuda};
      std::string why;
      const bool gpu = CudaAvailable(&why);
      if (!gpu && a->device != "cpu") std::fprintf(stderr, "bench: no CUDA rows: %s\n", why.c_str());
      std::printf("engine, scene room, flicker auto exposure, tracker nr+icp, %d OpenMP threads%s%s;\n"
                  "frames rendered first (not timed), %d timed after 5 warm-up frames\n\n",
                  omp_get_max_threads(), gpu ? ", GPU " : "", gpu ? CudaDeviceDescription().c_str() : "", a->frames);
      const auto rows = pipeline::RunEngineBench(o, [](const pipeline::EngineBenchRow& r) {
        std::fprintf(stderr, "bench: %s %dx%d %d^3 done: %.1f frames/s\n", DeviceName(r.device), r.c.width,
                     r.c.height, r.c.resolution, r.fps);
      });
      std::printf("%s", pipeline::EngineBenchTable(rows).c_str());
      return 0;
    }
    std::printf("synthetic sensor, scene room, flicker auto exposure, %d OpenMP threads\n\n",
                omp_get_max_threads());
    std::printf("| size | frames | ms/frame | frames/s |\n|---|---|---|---|\n");
    for (auto [w, h] : {std::pair{320, 240}, {640, 480}}) {
      sim::SimOptions o;
      o.width = w;
      o.height = h;
      o.frames = a->frames + 2;
      o.ae.mode = sim::AeMode::kFlicker;
      sim::SyntheticSource src(o);
      src.Next();  // warm-up
      src.Next();
      const auto t0 = std::chrono::steady_clock::now();
      for (int i = 0; i < a->frames; ++i) src.Next();
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::printf("| %dx%d | %d | %.2f | %.1f |\n", w, h, a->frames, 1000.0 * s / a->frames,
                  a->frames / s);
      std::fflush(stdout);
    }
    return 0;
  }};
}

}  // namespace hdrf::cli
