#include "engine_bench.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>
#include <vector>
#include <algorithm>

#include <omp.h>

#include <fstream>

#include "pipeline/scan_session.h"
#include "pipeline/frame_source.h"

namespace hdrf::pipeline {

std::vector<EngineBenchRow> RunEngineBench(const EngineBenchOptions& o,
                                           const std::function<void(const EngineBenchRow&)>& progress) {
  std::vector<EngineBenchRow> rows;
  constexpr int kWarmup = 5;
  // Each device's copy bandwidth, measured once for the whole table.
  double bandwidth[2] = {-1, -1}, bus = -1;
  std::array<double, 4> least_stage_ms{-1, -1, -1, -1};
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
        if (dev == Device::kCuda) {
          if (bus < 0) bus = CudaUploadBandwidth();
          if (least_stage_ms[0] < 0)
            for (std::size_t i = 0; i < least_stage_ms.size(); ++i)
              least_stage_ms[i] = 1e3 * CudaLeastStageSeconds(kLeastStageLaunches[i]);
          row.least_stage_ms = least_stage_ms;
          row.upload_bytes = UploadBytes(c.width, c.height);
          row.bus_bandwidth = bus;
        }
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

double UploadBytes(int width, int height) { return 7.0 * double(width) * double(height); }

StageTimes StageFloorMs(const EngineBenchRow& r) {
  StageTimes f;
  if (r.bandwidth <= 0) return f;
  const double per_byte = 1e3 / r.bandwidth;
  f.convert = r.bytes.convert * per_byte;
  if (r.upload_bytes > 0) f.convert = r.bus_bandwidth > 0 ? f.convert + 1e3 * r.upload_bytes / r.bus_bandwidth : 0;
  f.normalize = r.bytes.normalize * per_byte;
  f.track = r.bytes.track * per_byte;
  f.integrate = r.bytes.integrate * per_byte;
  f.raycast = r.bytes.raycast * per_byte;
  return f;
}

namespace {
// The stages the floor tables name, with a row's figure of each.
struct StageField {
  const char* name;
  double StageTimes::*field;
};
constexpr StageField kFloorStages[] = {{"convert", &StageTimes::convert},
                                       {"normalize", &StageTimes::normalize},
                                       {"track", &StageTimes::track},
                                       {"integrate", &StageTimes::integrate},
                                       {"raycast", &StageTimes::raycast}};
}  // namespace

std::string EngineMarginTable(const std::vector<EngineBenchRow>& rows) {
  std::string out;
  char line[512];
  std::vector<bool> done(rows.size(), false);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (done[i]) continue;
    // This row's device, encoding and voxel size: the smallest and the largest frame of them.
    const EngineBenchRow* lo = &rows[i];
    const EngineBenchRow* hi = &rows[i];
    auto pixels = [](const EngineBenchRow& r) { return double(r.c.width) * double(r.c.height); };
    for (std::size_t j = i; j < rows.size(); ++j) {
      const EngineBenchRow& r = rows[j];
      if (r.device != rows[i].device || r.encoding != rows[i].encoding || r.c.voxel_mm != rows[i].c.voxel_mm) continue;
      done[j] = true;
      if (pixels(r) < pixels(*lo)) lo = &r;
      if (pixels(r) > pixels(*hi)) hi = &r;
    }
    if (pixels(*hi) <= pixels(*lo)) continue;
    const StageTimes f_lo = StageFloorMs(*lo), f_hi = StageFloorMs(*hi);
    for (const StageField& s : kFloorStages) {
      const double m1 = lo->ms.*s.field, m2 = hi->ms.*s.field, f1 = f_lo.*s.field, f2 = f_hi.*s.field;
      if (!(f2 > f1)) continue;  // no floor, or one that does not grow with the frame
      const double k = (m2 - m1) / (f2 - f1), fixed = m2 - k * f2;
      std::snprintf(line, sizeof line, "| %s | %s | %dx%d -> %dx%d | %g mm | %s | %.3f / %.3f | %.4f / %.4f | %.3f | %.1f | %.0f %% |\n",
                    DeviceName(lo->device), volume::VoxelEncodingName(lo->encoding), lo->c.width, lo->c.height,
                    hi->c.width, hi->c.height, lo->c.voxel_mm, s.name, m1, m2, f1, f2, fixed, k,
                    m2 > 0 ? 100.0 * k * f2 / m2 : 0.0);
      out += line;
    }
  }
  if (out.empty()) return out;
  return "| device | voxel | sizes | voxel size | stage | ms | floor ms | fixed ms | x floor at the margin | "
         "share of the larger's time that grows with its bytes |\n|---|---|---|---|---|---|---|---|---|---|\n" + out;
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

std::string EngineLeastStageTable(const std::vector<EngineBenchRow>& rows) {
  std::string out;
  char line[512];
  std::array<double, 4> least{};
  for (const auto& r : rows) {
    if (r.least_stage_ms[0] <= 0) continue;
    least = r.least_stage_ms;  // (measured once a run: the same in every GPU row)
    const StageTimes floors = StageFloorMs(r);
    for (const StageField& s : kFloorStages) {
      const double five = 5 * (floors.*s.field);
      int fit = 0;  // the most launches (of kLeastStageLaunches) that take no longer than 5 x floor
      for (std::size_t i = 0; i < kLeastStageLaunches.size(); ++i)
        if (r.least_stage_ms[i] <= five) fit = kLeastStageLaunches[i];
      char fits[16];
      std::snprintf(fits, sizeof fits, fit == kLeastStageLaunches.back() ? "%d or more" : "%d", fit);
      std::snprintf(line, sizeof line, "| %s | %s | %dx%d | %s | %.3f | %.4f | %s |\n", DeviceName(r.device),
                    volume::VoxelEncodingName(r.encoding), r.c.width, r.c.height, s.name, r.ms.*s.field, five, fits);
      out += line;
    }
  }
  if (out.empty()) return out;
  std::snprintf(line, sizeof line,
                "\nThe least a stage takes as the stages are timed (the device waited for before and after) with 1, 2, 4 "
                "and 8 of the smallest operations queued one behind another: %.4f, %.4f, %.4f, %.4f ms. How many "
                "launches fit in 5x each stage's floor:\n\n",
                least[0], least[1], least[2], least[3]);
  return line + std::string("| device | voxel | size | stage | ms | 5 x floor ms | launches that fit in it |\n"
                            "|---|---|---|---|---|---|---|\n") + out;
}

std::string EngineFloorTable(const std::vector<EngineBenchRow>& rows) {
  std::string out =
      "| device | voxel | size | copy GB/s | bus GB/s | stage | ms | least MB moved | MB over the bus | floor ms | x floor |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n";
  char line[512];
  for (const auto& r : rows) {
    const StageTimes floors = StageFloorMs(r);
    const bool gpu = r.device == Device::kCuda;
    char bus[32] = "-";
    if (gpu) std::snprintf(bus, sizeof bus, "%.1f", r.bus_bandwidth / 1e9);
    for (const StageField& s : kFloorStages) {
      const double ms = r.ms.*s.field, floor_ms = floors.*s.field;
      const bool over_bus = gpu && s.field == &StageTimes::convert;
      char upload[32] = "-";
      if (gpu) std::snprintf(upload, sizeof upload, "%.2f", over_bus ? r.upload_bytes / 1e6 : 0.0);
      std::snprintf(line, sizeof line, "| %s | %s | %dx%d | %.0f | %s | %s | %.3f | %.2f | %s | %.4f | %.0f |\n",
                    DeviceName(r.device), volume::VoxelEncodingName(r.encoding), r.c.width, r.c.height, r.bandwidth / 1e9,
                    bus, s.name, ms, (r.bytes.*s.field) / 1e6, upload, floor_ms, floor_ms > 0 ? ms / floor_ms : 0.0);
      out += line;
    }
  }
  out += EngineLeastStageTable(rows);
  const std::string margins = EngineMarginTable(rows);
  if (!margins.empty())
    out += "\nHow each stage's time grows with its floor from the smaller frame to the larger (time = fixed + k x floor "
           "through the two; k = 1: each further byte at full bandwidth):\n\n" + margins;
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

std::string MarkdownHeading(const std::string& title, const std::string& command) {
  std::string cpu = "unknown CPU";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);)
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  std::string why;
  const std::string gpu = CudaAvailable(&why) ? "; GPU " + CudaDeviceDescription() : "; no GPU";
  return "## " + title + "\n\n`" + command + "` on " + cpu + ", " + std::to_string(omp_get_max_threads()) +
         " threads" + gpu + ".\n\n";
}

}  // namespace hdrf::pipeline
