// hdrfusion bench: prints speed tables. Suites grow with the engine; today: the synthetic
// sensor at 320x240 and 640x480.
#include <omp.h>

#include <chrono>
#include <cstdio>

#include "cli/commands.h"
#include "common/error.h"
#include "sim/synthetic_source.h"

namespace hdrf::cli {

Command AddBenchCommand(CLI::App& app) {
  struct Args {
    std::string suite = "sim";
    int frames = 60;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("bench", "Measure speed and print a table");
  cmd->add_option("--suite", a->suite, "What to measure")->check(CLI::IsMember({"sim"}))
      ->capture_default_str();
  cmd->add_option("--frames", a->frames, "Frames per measurement")->check(CLI::Range(5, 100000))
      ->capture_default_str();
  return {cmd, [a] {
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
