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
#include "pipeline/bench.h"
#include "pipeline/pipeline.h"
#include "sim/synthetic_source.h"

namespace hdrf::cli {

Command AddBenchCommand(CLI::App& app) {
  struct Args {
    std::string suite = "sim";
    int frames = 60;
    std::string device = "both";
    std::string out = "docs/results";
    int pairs = 10;
    std::string size = "320x240", work = "build/bench-data";
    std::vector<std::string> ae = {"flicker", "smooth"};
    bool no_peers = false;
    std::string data = "../shared/data", scene = "room";
    int sweeps = 0;
    double noise_scale = 1.0;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("bench", "Measure speed and print a table");
  cmd->add_option("--suite", a->suite,
                  "sim (the synthetic sensor), engine (per-stage times), landscape (error functions "
                  "around the true pose, the paper's figure), nr-figure (NR across an exposure change), tracking "
                  "(trackers and peers over 1000 frames), radiance (HDR accuracy, dynamic range), calibration "
                  "(response fitting on every DoRF curve), or paper (all of docs/results)")
      ->check(CLI::IsMember({"sim", "engine", "landscape", "nr-figure", "tracking", "radiance", "calibration", "paper"}))->capture_default_str();
  cmd->add_option("--out", a->out, "landscape, nr-figure: output folder")->capture_default_str();
  cmd->add_option("--pairs", a->pairs, "landscape: frame pairs a stop or more apart")->check(CLI::Range(1, 50))
      ->capture_default_str();
  auto* frames_opt = cmd->add_option("--frames", a->frames, "Frames per measurement (tracking: default 1000)")->check(CLI::Range(5, 100000))
      ->capture_default_str();
  cmd->add_option("--device", a->device, "Engine suite: cpu, cuda or both (CUDA rows where a GPU is usable)")
      ->check(CLI::IsMember({"cpu", "cuda", "both"}))->capture_default_str();
  cmd->add_option("--size", a->size, "tracking: image size")->capture_default_str();
  cmd->add_option("--ae", a->ae, "tracking: auto-exposure modes")->delimiter(',')
      ->check(CLI::IsMember({"flicker", "smooth", "fixed"}))->capture_default_str();
  cmd->add_option("--work", a->work, "tracking: folder for the sequences everyone reads (its room-* and peers-* folders are replaced)")->capture_default_str();
  cmd->add_option("--data", a->data, "calibration, paper: folder holding dorf/ and emor/ (SOURCES.md)")->capture_default_str();
  cmd->add_option("--sweeps", a->sweeps, "calibration: at most this many sweeps of 3 curves (default: all 67)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--scene", a->scene, "calibration: scene of the simulated sweeps")
      ->check(CLI::IsMember({"room", "desk"}))->capture_default_str();
  cmd->add_option("--noise-scale", a->noise_scale, "calibration: multiplies the simulated sensor noise")
      ->check(CLI::Range(0.0, 10.0))->capture_default_str();
  cmd->add_flag("--no-peers", a->no_peers, "tracking: do not run the peers (OpenCV rgbd, Open3D)");
  return {cmd, [a, frames_opt] {
    if (a->suite == "radiance")
      return RunRadianceAccuracy(a->out, frames_opt->count() > 0 ? a->frames : 300, a->size);
    if (a->suite == "tracking" || a->suite == "paper") {
      TrackingExperimentArgs t;
      if (frames_opt->count() > 0) t.frames = a->frames;
      t.size = a->size;
      t.ae_modes = a->ae;
      t.out = a->out;
      t.work = a->work;
      t.peers = !a->no_peers;
      return a->suite == "paper" ? RunPaper(t, a->pairs, a->data) : RunTrackingExperiment(t);
    }
    if (a->suite == "calibration")
      return RunCalibrationAccuracy({a->out, a->data, a->scene, a->sweeps, a->noise_scale});
    if (a->suite == "landscape") return RunLandscape(a->out, a->pairs, 10);
    if (a->suite == "nr-figure") return RunNrFigure(a->out);
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
