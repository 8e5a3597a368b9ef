// The engine benchmark: per-stage milliseconds and end-to-end frames per second on the
// synthetic sensor, per device and size, with the memory the model takes. Used by
// `hdrfusion bench --suite engine` and by `hdrfusion-bench` (core-only builds, GPU machine).
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "common/cuda_runtime.h"
#include "pipeline/pipeline.h"

namespace hdrf::pipeline {

struct BenchCase {
  int width, height;
  double voxel_mm;
};

struct EngineBenchOptions {
  int frames = 60;                 // timed frames, after 5 warm-up frames
  std::vector<Device> devices = {Device::kCpu};
  std::vector<BenchCase> cases = {{320, 240, 20}, {640, 480, 10}};
  tracking::TrackerKind tracker = tracking::TrackerKind::kNrIcp;
  std::vector<volume::VoxelEncoding> encodings = {volume::VoxelEncoding::kCompact};
};

struct EngineBenchRow {
  Device device = Device::kCpu;
  BenchCase c{};
  volume::VoxelEncoding encoding = volume::VoxelEncoding::kCompact;
  StageTimes ms;                   // mean per frame
  double wall_ms = 0;              // mean wall time per frame, end to end
  double fps = 0;                  // 1000 / wall_ms
  std::size_t bricks = 0;          // allocated at the end
  double visible_bricks = 0;       // mean bricks integrated per frame
  double volume_mib = 0;           // hash tables + allocated voxels
  double bytes_per_voxel = 0;      // volume bytes / allocated voxels
  double gpu_mib = 0;              // GPU memory taken by the pipeline (CUDA rows)
  double ate_cm = 0;               // RMS error of the trajectory against the truth
  double mesh_ms = 0;              // surface extraction of the final model, once
  std::size_t triangles = 0;
  int lost = 0;
  // The least data each stage must move per frame (bytes; StageFloorBytes below) and the
  // device's measured copy bandwidth (bytes/s): the stage's floor is their quotient.
  StageTimes bytes;
  double bandwidth = 0;
  // On the GPU the frame crosses the bus first (convert): its bytes (UploadBytes) and the
  // measured upload bandwidth from pinned memory (bytes/s); 0 on the CPU.
  double upload_bytes = 0, bus_bandwidth = 0;
  std::array<double, 4> level_iterations{};  // mean Gauss-Newton iterations a frame, finest level first
  // The slow frames a mean hides (a stall while the model grows, say): the stages' sum of
  // the timed frames at the 99th percentile and the largest, and the largest integrate stage.
  double p99_ms = 0, worst_ms = 0, worst_integrate_ms = 0;
  // The same frames again with the stages not timed (Pipeline::set_stage_timing off: the
  // device waited for only where a result is read back): the mean wall time per frame, and
  // the largest distance between the two runs' poses (0: the same scan).
  double untimed_wall_ms = 0, untimed_pose_diff_m = 0;
  // On the GPU: the least time a stage of 1, 2, 4 and 8 launches takes as the stages are
  // timed (CudaLeastStageSeconds), ms; 0 on the CPU.
  std::array<double, 4> least_stage_ms{};
};
// The launch counts of EngineBenchRow::least_stage_ms.
inline constexpr std::array<int, 4> kLeastStageLaunches = {1, 2, 4, 8};

// Runs every device x case; `progress` is told each finished row.
std::vector<EngineBenchRow> RunEngineBench(const EngineBenchOptions& o,
                                           const std::function<void(const EngineBenchRow&)>& progress = {});
// Markdown table of the rows.
std::string EngineBenchTable(const std::vector<EngineBenchRow>& rows);
// Markdown table of each row's stages against their memory-bandwidth floors: the least
// bytes the stage must read and write per frame, the time they take at the device's
// measured copy bandwidth, and how many times that the stage takes.
std::string EngineFloorTable(const std::vector<EngineBenchRow>& rows);
// Markdown table, GPU rows only (empty without): how many of the smallest launches, timed as
// the stages are, fit in five times each stage's floor (EngineBenchRow::least_stage_ms).
std::string EngineLeastStageTable(const std::vector<EngineBenchRow>& rows);

// The least bytes each stage moves for one frame of `width` x `height` pixels: convert reads
// colour and depth and writes radiance, confidence and depth (27 B a pixel); normalize reads
// radiance and writes normalized radiance (16 B); track reads the live and reference views
// once per Gauss-Newton iteration at each level (68 B a pixel of that level) and writes the
// live pyramid once (40 B a pixel of every level); integrate reads and writes every visible
// brick once and reads the frame's depth, radiance and confidence (20 B a pixel); ray casting
// reads every visible brick once and writes vertices, normals and radiance (36 B a pixel).
StageTimes StageFloorBytes(int width, int height, const std::array<double, 4>& level_iterations,
                           double visible_bricks, double brick_bytes);
// The frame as the engine takes it, in bytes: 8-bit colour and depth in float metres (7 B a
// pixel), what a GPU's convert stage must bring over the bus.
double UploadBytes(int width, int height);
// Each stage's floor in ms: its least bytes at the row's copy bandwidth, plus for the GPU's
// convert stage the frame's upload at the bus's bandwidth. 0 where a bandwidth is unknown.
StageTimes StageFloorMs(const EngineBenchRow& r);
// Markdown table of how each stage's time grows with its floor, between the smallest and the
// largest frame run for one device, voxel encoding and voxel size: time = fixed + k x floor
// through the two, so k is the cost of the stage's further bytes in floors (1: at full
// bandwidth) and fixed is what does not grow with them (launches, waits, chains of dependent
// steps). Empty where no device, encoding and voxel size was run at two frame sizes.
std::string EngineMarginTable(const std::vector<EngineBenchRow>& rows);
// Bytes per second a parallel memcpy of 256 MiB achieves on the CPU threads (read plus write).
double CpuCopyBandwidth();

// The heading a suite's table gets in docs/performance.md (`--markdown`): the title, the
// command that made it, and the machine it ran on (CPU model and threads, the GPU if one is
// usable), so that every figure says where it comes from.
std::string MarkdownHeading(const std::string& title, const std::string& command);

}  // namespace hdrf::pipeline
