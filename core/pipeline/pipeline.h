// The per-frame HDRFusion system: convert, normalize, track, compensate exposure, integrate,
// ray cast. Owns the volume and the tracker state. A plain object with Process(): the CLI
// calls it directly, the studio will wrap it in a thread.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/cuda_runtime.h"
#include "common/image.h"
#include "common/se3.h"
#include "imaging/imaging.h"
#include "mesh/mesh.h"
#include "radiometry/pcf.h"
#include "radiometry/sensor.h"
#include "tracking/tracking.h"
#include "volume/volume.h"

namespace hdrf::pipeline {

class Backend;

struct PipelineOptions {
  volume::VolumeOptions volume;
  tracking::TrackerOptions tracker;
  imaging::NormalizedRadianceOptions nr;
  int pcf = 1;                  // PCF variant p0..p3 for tracking and fusion (paper: p1 best)
  bool bilateral = true;        // bilateral filter on depth before tracking
  Device device = Device::kCpu; // kCuda: the CUDA backend where a GPU is usable, else the CPU
  void Check() const;           // throws SettingError naming the setting
};

struct FrameInput {
  ColorImage color;
  DepthImage depth_m;
  double timestamp = 0;
  std::optional<double> exposure_ms;       // as reported by the sensor, if it does
  std::optional<Pose> T_world_camera_true; // ground truth, if known (reports only)
};

struct StageTimes {
  double convert = 0, normalize = 0, track = 0, compensate = 0, integrate = 0, raycast = 0;
  double total() const { return convert + normalize + track + compensate + integrate + raycast; }
};

struct FrameReport {
  int index = 0;
  double timestamp = 0;
  Pose T_world_camera = Pose::Identity();
  tracking::TrackResult tracking;
  bool fused = false;
  double exposure_ratio = 1;             // estimated t (model radiance / live radiance)
  std::optional<double> exposure_ratio_reported;  // e_0 / e_k from the sensor's exposures
  long exposure_samples = 0;
  StageTimes ms;
  std::size_t allocated_bricks = 0;
};

class Pipeline {
 public:
  Pipeline(const PipelineOptions& options, const PinholeCamera& camera, const SensorInfo& sensor);
  ~Pipeline();

  FrameReport Process(const FrameInput& frame);

  // The model (a host copy, refreshed on each call after new frames, on the CUDA backend).
  const volume::Volume& volume() const;
  std::size_t volume_bytes() const;
  // The surface, extracted on the device the model lives on; `progress(fraction)` returning
  // false cancels (throws hdrf::Cancelled).
  mesh::Mesh ExtractMesh(const std::function<bool(double)>& progress = {}) const;
  const PipelineOptions& options() const { return o_; }
  Device device() const { return device_; }  // where the engine actually runs
  // Why the engine runs elsewhere than asked ("" when it runs where asked).
  const std::string& device_note() const { return device_note_; }
  const Pose& pose() const { return pose_; }
  int frames() const { return index_; }
  // Renders the model from a pose (radiance, normals, depth, NR).
  volume::Volume::Rendering Render(const Pose& T_world_camera) const;
  Backend& backend() const;  // the stages, for tests that compare backends

 private:
  PipelineOptions o_;
  PinholeCamera cam_;
  radiometry::InverseResponse inverse_;
  radiometry::PcfTables pcf_;
  std::unique_ptr<Backend> backend_;
  Device device_ = Device::kCpu;
  std::string device_note_;
  Pose pose_ = Pose::Identity();
  Pose previous_pose_ = Pose::Identity();  // for the constant-velocity prediction
  Pose reference_pose_ = Pose::Identity();
  int index_ = 0;
  std::optional<double> first_exposure_ms_;
  bool have_reference_ = false;
  bool have_render_ = false;
};

}  // namespace hdrf::pipeline
