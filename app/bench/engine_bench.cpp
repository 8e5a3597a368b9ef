#include "engine_bench.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "pipeline/scan_session.h"
#include "pipeline/frame_source.h"

namespace hdrf::pipeline {

std::vector<EngineBenchRow> RunEngineBench(const EngineBenchOptions& o,
                                           const std::function<void(const EngineBenchRow&)>& progress) {
  std::vector<EngineBenchRow> rows;
  constexpr int kWarmup = 5;
  for (const BenchCase& c : o.cases) {
    sim::SimOptions so;
    so.width = c.width;
    so.height = c.height;
    so.frames = o.frames + kWarmup;
    so.ae.mode = sim::AeMode::kFlicker;
    SyntheticFrameSource src(so);
    const std::vector<FrameInput> frames = ReadAll(src);  // rendered first, not timed
    const Pose T0inv = frames[0].T_world_camera_true->inverse();
    for (Device dev : o.devices)
    for (volume::VoxelEncoding enc : o.encodings) {
      if (dev == Device::kCuda && !CudaAvailable()) continue;
      const std::size_t mem0 = dev == Device::kCuda ? CudaMemoryUsed() : 0;
      PipelineOptions po;
      po.volume.voxel_m = float(c.voxel_mm / 1000);
      po.tracker.kind = o.tracker;
      po.device = dev;
      po.volume.encoding = enc;
      EngineBenchRow row;
      row.device = dev;
      row.encoding = enc;
      row.c = c;
      {
        ScanSession session(po, src.sensor().camera, src.sensor());
        double visible = 0;
        std::chrono::steady_clock::time_point t0;
        for (std::size_t i = 0; i < frames.size(); ++i) {
          if (int(i) == kWarmup) t0 = std::chrono::steady_clock::now();
          session.Process(frames[i]);
          if (int(i) >= kWarmup) visible += double(session.pipeline().last_visible_bricks());
        }
        const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        Pipeline& pipe = session.pipeline();
        double se = 0;
        for (std::size_t i = 0; i < frames.size(); ++i) {
          const FrameReport& r = session.reports()[i];
          const Pose truth = T0inv * *frames[i].T_world_camera_true;
          se += (truth.translation() - r.T_world_camera.translation()).squaredNorm();
          if (int(i) >= kWarmup) row.ms += r.ms;
        }
        row.lost = session.lost();
        const double n = o.frames;
        row.ms = row.ms / n;
        row.wall_ms = wall / n;
        row.fps = 1000.0 / row.wall_ms;
        row.visible_bricks = visible / n;
        const VolumeStats vs = pipe.volume_stats();
        row.bricks = vs.allocated_bricks;
        const double bytes = double(vs.bytes);
        row.volume_mib = bytes / (1024.0 * 1024.0);
        row.bytes_per_voxel = row.bricks ? bytes / (double(row.bricks) * 512.0) : 0;
        if (dev == Device::kCuda) row.gpu_mib = double(CudaMemoryUsed() - mem0) / (1024.0 * 1024.0);
        row.ate_cm = 100.0 * std::sqrt(se / double(frames.size()));
        const auto m0 = std::chrono::steady_clock::now();
        row.triangles = pipe.ExtractMesh().triangles.size();
        row.mesh_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - m0).count();
      }
      if (progress) progress(row);
      rows.push_back(row);
    }
  }
  return rows;
}

std::string EngineBenchTable(const std::vector<EngineBenchRow>& rows) {
  std::string out =
      "| device | voxel | size | voxel size | convert | normalize | track | compensate | integrate | raycast | "
      "ms/frame | frames/s | bricks (visible/frame) | volume MiB | bytes/voxel | GPU MiB | ATE cm | mesh ms (triangles) |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  char line[512];
  for (const auto& r : rows) {
    std::snprintf(line, sizeof line,
                  "| %s | %s | %dx%d | %g mm | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f | %zu (%.0f) | %.1f | "
                  "%.1f | %s | %.2f | %.1f (%zu) |\n",
                  DeviceName(r.device), volume::VoxelEncodingName(r.encoding), r.c.width, r.c.height, r.c.voxel_mm, r.ms.convert, r.ms.normalize,
                  r.ms.track, r.ms.compensate, r.ms.integrate, r.ms.raycast, r.wall_ms, r.fps, r.bricks,
                  r.visible_bricks, r.volume_mib, r.bytes_per_voxel,
                  r.device == Device::kCuda ? std::to_string(int(std::lround(r.gpu_mib))).c_str() : "-", r.ate_cm,
                  r.mesh_ms, r.triangles);
    out += line;
  }
  return out;
}

}  // namespace hdrf::pipeline
