// hdrfusion bench: prints speed tables. Suites grow with the engine; today: the synthetic
// sensor at 320x240 and 640x480.
#include <omp.h>

#include <chrono>
#include <tuple>
#include <vector>
#include <cstdio>

#include "cli/commands.h"
#include "common/error.h"
#include "pipeline/frame_source.h"
#include "pipeline/pipeline.h"
#include "sim/synthetic_source.h"

namespace hdrf::cli {

Command AddBenchCommand(CLI::App& app) {
  struct Args {
    std::string suite = "sim";
    int frames = 60;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("bench", "Measure speed and print a table");
  cmd->add_option("--suite", a->suite, "sim (the synthetic sensor) or engine (per-stage times)")
      ->check(CLI::IsMember({"sim", "engine"}))->capture_default_str();
  cmd->add_option("--frames", a->frames, "Frames per measurement")->check(CLI::Range(5, 100000))
      ->capture_default_str();
  return {cmd, [a] {
    if (a->suite == "engine") {
      std::printf("engine on the CPU, scene room, flicker auto exposure, tracker nr+icp, %d OpenMP threads;\n"
                  "frames rendered first (not timed), %d timed after 5 warm-up frames\n\n",
                  omp_get_max_threads(), a->frames);
      std::printf("| size | volume | convert | normalize | track | compensate | integrate | raycast | total ms | frames/s |\n"
                  "|---|---|---|---|---|---|---|---|---|---|\n");
      for (auto [w, h, res] : {std::tuple{320, 240, 256}, {640, 480, 512}}) {
        sim::SimOptions so;
        so.width = w;
        so.height = h;
        so.frames = a->frames + 5;
        so.ae.mode = sim::AeMode::kFlicker;
        pipeline::SyntheticFrameSource src(so);
        std::vector<pipeline::FrameInput> frames(std::size_t(src.size()));
        for (auto& f : frames) src.Next(f);
        pipeline::PipelineOptions po;
        po.volume.resolution = res;
        pipeline::Pipeline pipe(po, src.sensor().camera, src.sensor());
        pipeline::StageTimes sum;
        for (std::size_t i = 0; i < frames.size(); ++i) {
          const auto r = pipe.Process(frames[i]);
          if (i < 5) continue;
          sum.convert += r.ms.convert; sum.normalize += r.ms.normalize; sum.track += r.ms.track;
          sum.compensate += r.ms.compensate; sum.integrate += r.ms.integrate; sum.raycast += r.ms.raycast;
        }
        const double n = a->frames;
        std::printf("| %dx%d | %d^3 | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f |\n", w, h, res,
                    sum.convert / n, sum.normalize / n, sum.track / n, sum.compensate / n, sum.integrate / n,
                    sum.raycast / n, sum.total() / n, 1000.0 * n / sum.total());
        std::fflush(stdout);
      }
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
