// hdrfusion bench: speed tables of the synthetic sensor (sim) and of the engine per stage
// (engine, also hdrfusion-bench).
#include <omp.h>
#include <unistd.h>

#include <chrono>
#include <map>
#include <tuple>
#include <vector>
#include <cstdio>

#include "cli/bench_export.h"
#include "cli/bench_tonemap.h"
#include "cli/commands.h"
#include "common/error.h"
#include "pipeline/frame_source.h"
#include "engine_bench.h"
#include "pipeline/pipeline.h"
#include "sensors/recorder.h"
#include "sim/synthetic_source.h"

#include <filesystem>
#include <fstream>
#include <thread>

namespace hdrf::cli {

namespace {

// Recording throughput at VGA: the lossless sequence recorder (PNG colour and depth on its
// writer thread, as `hdrfusion record` runs it), beside the same frames written raw and
// uncompressed (what an uncompressed .oni stream costs the disk), in one run on one disk.
int BenchRecord(int frames, std::string dir) {
  namespace fs = std::filesystem;
  const fs::path root = (dir.empty() ? fs::temp_directory_path() : fs::path(dir)) /
                        ("hdrfusion-bench-record-" + std::to_string(::getpid()));
  if (fs::exists(root)) throw InputError(root, "exists; remove it first");
  fs::create_directories(root);
  struct Cleanup {
    fs::path p;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(p, ec);
    }
  } cleanup{root};
  sim::SimOptions o;
  o.width = 640;
  o.height = 480;
  o.frames = frames;
  o.depth_scale = 1000;
  sim::SyntheticSource src(o);
  SensorInfo sensor = src.sensor();
  sensor.synthetic.reset();
  std::vector<sensors::LiveFrame> input;
  std::vector<double> exposures;
  std::fprintf(stderr, "bench: rendering %d VGA frames (not timed)\n", frames);
  for (int i = 0; i < frames; ++i) {
    sim::SimFrame f = src.Next();
    input.push_back({std::move(f.color), std::move(f.depth), f.timestamp, i, std::nullopt, std::nullopt});
    exposures.push_back(f.exposure_ms);
  }
  std::printf("recording %d VGA frames (640x480 RGB + 16-bit depth) to %s\n\n", frames, root.string().c_str());
  std::printf("| writer | frames/s | MB/s written | MB per frame | needed for 30 Hz |\n|---|---|---|---|---|\n");
  {
    const auto t0 = std::chrono::steady_clock::now();
    sensors::SequenceRecorder rec(root / "sequence", sensor);
    for (int i = 0; i < frames; ++i)
      while (!rec.Push(input[std::size_t(i)].Clone(), exposures[std::size_t(i)])) {
        if (rec.failed()) throw Error(rec.stats().error);
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    const sensors::RecordingStats st = rec.Finish();
    if (!st.error.empty()) throw Error(st.error);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("| sequence recorder (lossless PNG, lists, exposure.txt) | %.1f | %.1f | %.2f | %s |\n", frames / s,
                st.bytes / 1e6 / s, st.bytes / 1e6 / frames, frames / s >= 30 ? "yes" : "no");
  }
  {
    const auto t0 = std::chrono::steady_clock::now();
    std::ofstream raw(root / "raw.bin", std::ios::binary);
    double bytes = 0;
    for (const auto& f : input) {
      raw.write(reinterpret_cast<const char*>(f.color.data()), std::streamsize(f.color.size() * 3));
      raw.write(reinterpret_cast<const char*>(f.depth_mm.data()), std::streamsize(f.depth_mm.size() * 2));
      bytes += double(f.color.size() * 3 + f.depth_mm.size() * 2);
    }
    raw.flush();
    if (!raw) throw InputError(root / "raw.bin", "write failed");
    raw.close();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("| raw uncompressed (reference: an uncompressed .oni stream) | %.1f | %.1f | %.2f | %s |\n",
                frames / s, bytes / 1e6 / s, bytes / 1e6 / frames, frames / s >= 30 ? "yes" : "no");
  }
  return 0;
}

}  // namespace

Command AddBenchCommand(CLI::App& app) {
  struct Args {
    std::string suite = "sim";
    int frames = 60;
    std::string device = "both";
    std::string dir;
    std::vector<std::string> images;
    std::string scan;
    bool markdown = false;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("bench", "Measure speed and print a table");
  cmd->add_option("--suite", a->suite,
                  "sim (the synthetic sensor), engine (per-stage times and frames/s per device and size) or record "
                  "(recording throughput at VGA into --dir), tonemap (the operators beside pfstmo at 640x480) or export "
                  "(the textured export of a scanned room, --frames frames, or of --scan DIR, stage by stage); "
                  "the paper's experiments are hdrfusion-experiments, not part of this tool")
      ->check(CLI::IsMember({"sim", "engine", "record", "tonemap", "export"}))->capture_default_str();
  cmd->add_option("--dir", a->dir, "Record suite: a folder on the disk to measure (default: the system's temporary folder)");
  cmd->add_option("--scan", a->scan, "Export suite: a scan output folder (default: scan the room first)");
  cmd->add_option("--image", a->images, "Tonemap suite: OpenEXR images (default: the shared data's hdr_images)");
  cmd->add_option("--frames", a->frames, "Timed frames per measurement")->check(CLI::Range(5, 100000))
      ->capture_default_str();
  cmd->add_option("--device", a->device, "Engine suite: cpu, cuda or both (CUDA rows where a GPU is usable)")
      ->check(CLI::IsMember({"cpu", "cuda", "both"}))->capture_default_str();
  cmd->add_flag("--markdown", a->markdown,
                "Start with the suite's heading for docs/performance.md: the command and the machine (tools/performance.sh)");
  return {cmd, [a] {
    if (a->markdown) {
      static const std::map<std::string, std::string> kTitles = {
          {"sim", "Synthetic sensor"}, {"engine", "Engine"}, {"record", "Recording"},
          {"tonemap", "Tone mapping"}, {"export", "Export"}};
      std::string command = "hdrfusion bench --suite " + a->suite + " --frames " + std::to_string(a->frames);
      if (a->suite == "engine" && a->device != "both") command += " --device " + a->device;
      std::printf("%s", pipeline::MarkdownHeading(kTitles.at(a->suite), command).c_str());
      std::fflush(stdout);
    }
    if (a->suite == "record") return BenchRecord(a->frames, a->dir);
    if (a->suite == "tonemap") return BenchTonemap(a->frames, a->images);
    if (a->suite == "export") return BenchExport(a->frames, a->scan);
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
        std::fprintf(stderr, "bench: %s %dx%d %g mm voxels done: %.1f frames/s\n", DeviceName(r.device), r.c.width,
                     r.c.height, r.c.voxel_mm, r.fps);
      });
      std::printf("%s", pipeline::EngineBenchTable(rows).c_str());
      std::printf("\nEach stage against its memory-bandwidth floor (the least bytes it must move, at the measured copy bandwidth; on the GPU the frame's upload at the bus's):\n\n%s",
                  pipeline::EngineFloorTable(rows).c_str());
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
