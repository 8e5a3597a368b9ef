#include "cli/bench_export.h"

#include <omp.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <vector>

#include "io/asset_export.h"
#include "pipeline/scan_session.h"
#include "sim/synthetic_source.h"

namespace hdrf::cli {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

int BenchExport(int frames, const std::string& scan_dir) {
  io::ScanData scan;
  if (!scan_dir.empty()) {
    scan = io::LoadScan(scan_dir);
  } else {
    sim::SimOptions so;
    so.frames = frames;
    sim::SyntheticSource src(so);
    pipeline::ScanSession session(pipeline::PipelineOptions{}, src.sensor().camera, src.sensor());
    std::fprintf(stderr, "bench: scanning the room, %d frames (not timed)...\n", frames);
    while (!src.done()) {
      const sim::SimFrame f = src.Next();
      pipeline::FrameInput in;
      in.color = f.color.Clone();
      in.depth_m = DepthImage(f.depth.width(), f.depth.height());
      for (std::size_t i = 0; i < f.depth.size(); ++i) in.depth_m[i] = float(f.depth[i] / so.depth_scale);
      in.timestamp = f.timestamp;
      session.Process(in);
    }
    scan = io::ScanDataFromSession(session, "synthetic:frames=" + std::to_string(frames));
  }
  const fs::path tmp = fs::temp_directory_path() / ("hdrfusion-bench-export-" + std::to_string(::getpid()));
  std::printf("export of %s: %zu triangles in, %zu keyframes, %d OpenMP threads\n\n", scan.source.c_str(),
              scan.mesh.triangles.size(), scan.keyframes ? scan.keyframes->keyframes.size() : 0, omp_get_max_threads());
  std::printf("| texture | triangles | texels | charts | clean-up s | atlas s | views s | bake s | write s | total s |\n"
              "|---|---|---|---|---|---|---|---|---|---|\n");
  for (int mode = 0; mode < 2; ++mode) {
    io::AssetOptions o;
    if (mode == 1) o.atlas.fit_size = 4096;
    std::map<std::string, double> spent;
    std::string current;
    Clock::time_point since = Clock::now();
    const auto t0 = since;
    const io::AssetResult r = io::ExportAsset(scan, o, tmp / std::to_string(mode), [&](const std::string& stage, double) {
      if (stage != current) {
        const auto now = Clock::now();
        if (!current.empty()) spent[current] += std::chrono::duration<double>(now - since).count();
        current = stage;
        since = now;
      }
      return true;
    });
    const double total = std::chrono::duration<double>(Clock::now() - t0).count();
    char label[64];
    std::snprintf(label, sizeof label, "%s %dx%d", mode == 0 ? "2 mm" : "fit 4096", r.atlas_width, r.atlas_height);
    const long charts = nlohmann::json::parse(r.report_json)["texture"]["charts"].get<long>();
    std::printf("| %s | %zu | %ld | %ld | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", label, r.triangles,
                r.texels_from_frames + r.texels_from_volume, charts, spent["clean-up"], spent["UV atlas"],
                spent["keyframes"], spent["texture"], spent["writing"], total);
    std::error_code ec;
    fs::remove_all(tmp / std::to_string(mode), ec);
  }
  std::error_code ec;
  fs::remove_all(tmp, ec);
  return 0;
}

}  // namespace hdrf::cli
