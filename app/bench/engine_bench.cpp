#include "engine_bench.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>
#include <vector>
#include <algorithm>

#include "pipeline/scan_session.h"
#include "pipeline/frame_source.h"

namespace hdrf::pipeline {

std::vector<EngineBenchRow> RunEngineBench(const EngineBenchOptions& o,
                                           const std::function<void(const EngineBenchRow&)>& progress) {
  std::vector<EngineBenchRow> rows;
  constexpr int kWarmup = 5;
  // Each device's copy bandwidth, measured once for the whole table.
  double bandwidth[2] = {-1, -1};
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
        std::vector<double> frame_ms;
        for (std::size_t i = 0; i < frames.size(); ++i) {
          const FrameReport& r = session.reports()[i];
          const Pose truth = T0inv * *frames[i].T_world_camera_true;
          se += (truth.translation() - r.T_world_camera.translation()).squaredNorm();
          if (int(i) < kWarmup) continue;
          row.ms += r.ms;
          frame_ms.push_back(r.ms.total());
          row.worst_integrate_ms = std::max(row.worst_integrate_ms, r.ms.integrate);
        }
        std::sort(frame_ms.begin(), frame_ms.end());
        if (!frame_ms.empty()) {
          row.worst_ms = frame_ms.back();
          row.p99_ms = frame_ms[std::min(frame_ms.size() - 1, std::size_t(std::ceil(0.99 * double(frame_ms.size()))) - 1)];
        }
        std::array<double, 4> level_iterations{};
        for (std::size_t i = kWarmup; i < frames.size(); ++i)
          for (std::size_t l = 0; l < 4; ++l)
            level_iterations[l] += session.reports()[i].tracking.level_iterations[l] / double(o.frames);
        row.level_iterations = level_iterations;
        row.lost = session.lost();
        const double n = o.frames;
        row.ms = row.ms / n;
        row.wall_ms = wall / n;
        row.fps = 1000.0 / row.wall_ms;
        row.visible_bricks = visible / n;
        row.bytes = StageFloorBytes(c.width, c.height, level_iterations, row.visible_bricks, double(po.volume.brick_bytes()));
        double& bw = bandwidth[dev == Device::kCuda ? 1 : 0];
        if (bw < 0) bw = dev == Device::kCuda ? CudaCopyBandwidth() : CpuCopyBandwidth();
        row.bandwidth = bw;
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
        // Again, the stages not timed (no per-stage wait for the device).
        ScanSession untimed(po, src.sensor().camera, src.sensor());
        untimed.pipeline().set_stage_timing(false);
        std::chrono::steady_clock::time_point u0;
        for (std::size_t i = 0; i < frames.size(); ++i) {
          if (int(i) == kWarmup) u0 = std::chrono::steady_clock::now();
          untimed.Process(frames[i]);
        }
        untimed.pipeline().Synchronize();  // (the last frame's work done)
        row.untimed_wall_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - u0).count() / n;
        for (std::size_t i = 0; i < frames.size(); ++i)
          row.untimed_pose_diff_m =
              std::max(row.untimed_pose_diff_m, (session.reports()[i].T_world_camera.translation() -
                                                 untimed.reports()[i].T_world_camera.translation())
                                                    .norm());
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

StageTimes StageFloorBytes(int width, int height, const std::array<double, 4>& level_iterations,
                           double visible_bricks, double brick_bytes) {
  const double px = double(width) * double(height);
  StageTimes b;
  b.convert = 27 * px;
  b.normalize = 16 * px;
  double pyramid = 0;
  for (std::size_t l = 0; l < 4; ++l) {
    const double level_px = double(width >> l) * double(height >> l);
    b.track += 68 * level_px * level_iterations[l];
    if (level_iterations[l] > 0 || l == 0) pyramid += level_px;
  }
  b.track += 40 * pyramid;
  b.integrate = 2 * visible_bricks * brick_bytes + 20 * px;
  b.raycast = visible_bricks * brick_bytes + 36 * px;
  return b;
}

double CpuCopyBandwidth() {
  constexpr std::size_t kBytes = 256ull << 20;
  std::vector<char> a(kBytes, 1), b(kBytes, 0);
  double best = 0;
  for (int k = 0; k < 4; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    const int chunks = 64;
#pragma omp parallel for schedule(static)
    for (int c = 0; c < chunks; ++c) {
      const std::size_t lo = kBytes / chunks * std::size_t(c);
      std::memcpy(b.data() + lo, a.data() + lo, kBytes / chunks);
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (k > 0 && s > 0) best = std::max(best, 2.0 * double(kBytes) / s);  // the first warms up
  }
  return best;
}

std::string EngineFloorTable(const std::vector<EngineBenchRow>& rows) {
  std::string out =
      "| device | voxel | size | copy GB/s | stage | ms | least MB moved | floor ms | x floor |\n"
      "|---|---|---|---|---|---|---|---|---|\n";
  char line[512];
  for (const auto& r : rows) {
    const std::pair<const char*, double> stages[] = {{"convert", r.ms.convert},     {"normalize", r.ms.normalize},
                                                     {"track", r.ms.track},         {"integrate", r.ms.integrate},
                                                     {"raycast", r.ms.raycast}};
    const double bytes[] = {r.bytes.convert, r.bytes.normalize, r.bytes.track, r.bytes.integrate, r.bytes.raycast};
    for (std::size_t k = 0; k < 5; ++k) {
      const double floor_ms = r.bandwidth > 0 ? 1e3 * bytes[k] / r.bandwidth : 0;
      std::snprintf(line, sizeof line, "| %s | %s | %dx%d | %.0f | %s | %.3f | %.2f | %.4f | %.0f |\n", DeviceName(r.device),
                    volume::VoxelEncodingName(r.encoding), r.c.width, r.c.height, r.bandwidth / 1e9, stages[k].first,
                    stages[k].second, bytes[k] / 1e6, floor_ms, floor_ms > 0 ? stages[k].second / floor_ms : 0.0);
      out += line;
    }
  }
  // How the tracking stage's time divides over its iterations (what a faster sum or step buys).
  out += "\nGauss-Newton iterations a frame (mean; levels finest first) and the tracking stage's time per iteration:\n\n"
         "| device | voxel | size | iterations (level 0 / 1 / 2) | all | track ms per iteration |\n"
         "|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    const double all = r.level_iterations[0] + r.level_iterations[1] + r.level_iterations[2] + r.level_iterations[3];
    std::snprintf(line, sizeof line, "| %s | %s | %dx%d | %.1f / %.1f / %.1f | %.1f | %.4f |\n", DeviceName(r.device),
                  volume::VoxelEncodingName(r.encoding), r.c.width, r.c.height, r.level_iterations[0], r.level_iterations[1],
                  r.level_iterations[2], all, all > 0 ? r.ms.track / all : 0.0);
    out += line;
  }
  out += "\nThe slow frames (the sum of the stages; a stall shows here, not in the mean):\n\n"
         "| device | voxel | size | voxel size | mean ms | 99th percentile ms | worst ms | worst integrate ms |\n"
         "|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    std::snprintf(line, sizeof line, "| %s | %s | %dx%d | %g mm | %.2f | %.2f | %.2f | %.2f |\n", DeviceName(r.device),
                  volume::VoxelEncodingName(r.encoding), r.c.width, r.c.height, r.c.voxel_mm, r.ms.total(), r.p99_ms,
                  r.worst_ms, r.worst_integrate_ms);
    out += line;
  }
  out += "\nEnd to end with the stages not timed (the device waited for only where a result is read back; the same "
         "frames again, the largest pose difference to the timed run):\n\n"
         "| device | voxel | size | voxel size | ms/frame timed | ms/frame not timed | frames/s not timed | pose difference m |\n"
         "|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    std::snprintf(line, sizeof line, "| %s | %s | %dx%d | %g mm | %.2f | %.2f | %.1f | %.3g |\n", DeviceName(r.device),
                  volume::VoxelEncodingName(r.encoding), r.c.width, r.c.height, r.c.voxel_mm, r.wall_ms,
                  r.untimed_wall_ms, r.untimed_wall_ms > 0 ? 1000.0 / r.untimed_wall_ms : 0.0, r.untimed_pose_diff_m);
    out += line;
  }
  return out;
}

}  // namespace hdrf::pipeline
