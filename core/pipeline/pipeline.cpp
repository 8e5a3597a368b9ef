#include "pipeline/pipeline.h"

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "common/error.h"
#include "pipeline/backend.h"

namespace hdrf::pipeline {

namespace {
using Clock = std::chrono::steady_clock;
double Ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}
}  // namespace

#if !HDRF_HAS_CUDA
std::unique_ptr<Backend> MakeCudaBackend(const BackendSetup&) { ThrowNoCudaBackend(); }
#endif

StageTimes& StageTimes::operator+=(const StageTimes& o) {
  convert += o.convert;
  normalize += o.normalize;
  track += o.track;
  compensate += o.compensate;
  integrate += o.integrate;
  raycast += o.raycast;
  return *this;
}
StageTimes StageTimes::operator/(double n) const {
  return {convert / n, normalize / n, track / n, compensate / n, integrate / n, raycast / n};
}

Pipeline::Pipeline(const PipelineOptions& options, const PinholeCamera& camera,
                   const SensorInfo& sensor)
    : o_((options.Check(), options)), cam_(camera) {
  if (!camera.Valid()) throw SettingError("camera", "intrinsics must be positive");
  if (!sensor.response)
    throw Error("the sensor has no response calibration (sensor.json 'response'); calibrate it "
                "with hdrfusion calibrate, or pass --response srgb to assume an sRGB camera");
  inverse_ = *sensor.response;
  inverse_.Check("sensor response");
  pcf_ = radiometry::ComputePcf(inverse_, sensor.noise ? *sensor.noise : radiometry::DefaultNoise(inverse_));
  const auto inverse = inverse_.Flat();
  std::vector<float> p(768);
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 256; ++i) p[std::size_t(c * 256 + i)] = pcf_[o_.pcf][c][i];
  // The brightness-constancy tracker compares raw frames: it always tracks frame to frame.
  reference_from_model_ = o_.tracker.frame_to_model && o_.tracker.kind != tracking::TrackerKind::kIntensity;
  const BackendSetup setup{o_, cam_, inverse.data(), p.data()};
  if (o_.device == Device::kCuda) {
    std::string why;
    if (CudaAvailable(&why)) {
      backend_ = MakeCudaBackend(setup);
      device_ = Device::kCuda;
    } else {
      device_note_ = "CUDA requested but not usable (" + why + "); running on the CPU";
    }
  }
  if (!backend_) backend_ = MakeCpuBackend(setup);
}

Pipeline::~Pipeline() = default;

volume::Volume::Rendering Pipeline::Render(const Pose& T) { return backend_->Render(T); }
const volume::Volume& Pipeline::DownloadVolume() { return backend_->DownloadVolume(); }
mesh::Mesh Pipeline::ExtractMesh(const std::function<bool(double)>& progress) {
  return backend_->ExtractMesh(progress);
}
VolumeStats Pipeline::volume_stats() const {
  return {backend_->AllocatedBricks(), backend_->VolumeBytes(), backend_->VolumeFull(), backend_->VolumeFullReason(),
          backend_->VolumeBounds(), backend_->Streaming()};
}
FrameViews Pipeline::DownloadViews() { return backend_->DownloadViews(); }

FrameReport Pipeline::Process(const FrameInput& in) {
  if (in.color.width() != cam_.width || in.color.height() != cam_.height ||
      in.depth_m.width() != cam_.width || in.depth_m.height() != cam_.height)
    throw Error("frame " + std::to_string(index_) + ": colour or depth size differs from the camera (" +
                std::to_string(cam_.width) + "x" + std::to_string(cam_.height) + ")");
  FrameReport rep;
  rep.index = index_;
  rep.timestamp = in.timestamp;
  {
    long with_depth = 0, beyond = 0;
    for (int y = 0; y < in.depth_m.height(); y += 4)
      for (int x = 0; x < in.depth_m.width(); x += 4) {
        const float z = in.depth_m(x, y);
        with_depth += z > 0;
        beyond += z > o_.volume.raycast_far_m;
      }
    rep.depth_beyond_far = with_depth > 0 ? double(beyond) / double(with_depth) : 0.0;
  }
  Backend& b = *backend_;
  auto now = [&] {
    b.Synchronize();
    return Clock::now();
  };
  const auto t0 = now();
  // 1. Convert: radiance and confidence; depth filtering.
  b.Convert(in.color, in.depth_m);
  const auto t1 = now();
  // 2. Normalize.
  b.Normalize();
  const auto t2 = now();
  // 3. Track against the reference (the first frame has none and defines the world).
  b.BuildLive();
  if (!b.HasReference()) {
    previous_pose_ = pose_;
    rep.tracking.T_world_camera = pose_;
    rep.tracking.inlier_share = 1;
  } else {
    // Start from a constant-velocity prediction (the last inter-frame motion, repeated). The
    // inlier share counts matches against what both sides can offer: where the model covers
    // only part of the view (an area not scanned yet, or beyond the volume), matching all of
    // that part is a success, not a loss.
    const Pose predicted = se3::Orthonormalized(pose_ * (previous_pose_.inverse() * pose_));
    rep.tracking = tracking::Track([&](int l, const Pose& T) { return b.Accumulate(l, T); }, o_.tracker.levels,
                                   std::min(b.LiveValid(), b.ReferenceValid()), predicted, o_.tracker);
    if (!rep.tracking.lost) {
      previous_pose_ = pose_;
      pose_ = rep.tracking.T_world_camera;
    }
  }
  rep.T_world_camera = pose_;
  const auto t3 = now();
  // 4. Exposure compensation against the model as seen from the last pose.
  double t_ratio = 1;
  if (b.HasRender() && !rep.tracking.lost) {
    const auto est = b.EstimateExposure(pose_);
    rep.exposure_samples = est.samples;
    if (est.valid) t_ratio = est.ratio;
  }
  rep.exposure_ratio = t_ratio;
  if (in.exposure_ms) {
    if (index_ == 0) first_exposure_ms_ = in.exposure_ms;
    if (first_exposure_ms_) rep.exposure_ratio_reported = *first_exposure_ms_ / *in.exposure_ms;
  }
  const auto t4 = now();
  // 5. Integrate (lost frames are not fused).
  if (!rep.tracking.lost) {
    b.Integrate(pose_, float(t_ratio));
    rep.fused = true;
  }
  rep.allocated_bricks = b.AllocatedBricks();
  if (!full_reported_ && rep.fused && b.VolumeFull()) {
    rep.volume_full = b.VolumeFullReason();
    full_reported_ = true;
  }
  const auto t5 = now();
  // 6. Ray cast the model from the new pose, and the next frame's reference: the ray cast
  // (frame to model) or this frame where it was tracked (frame to frame).
  if (rep.fused || !b.HasRender()) b.Raycast(pose_);
  if (reference_from_model_) {
    b.ReferenceFromRender();
  } else if (!rep.tracking.lost || !b.HasReference()) {
    b.ReferenceFromLive(pose_);
    reference_color_ = in.color.Clone();
    reference_depth_ = in.depth_m.Clone();
  }
  const auto t6 = now();
  rep.ms = {Ms(t0, t1), Ms(t1, t2), Ms(t2, t3), Ms(t3, t4), Ms(t4, t5), Ms(t5, t6)};
  ++index_;
  return rep;
}

ResumePoint Pipeline::resume_point() const {
  ResumePoint p;
  p.frames = index_;
  p.pose = pose_;
  p.previous_pose = previous_pose_;
  p.first_exposure_ms = first_exposure_ms_;
  if (!reference_from_model_) {
    p.reference_color = reference_color_.Clone();
    p.reference_depth = reference_depth_.Clone();
  }
  return p;
}

void Pipeline::Resume(const volume::Volume& model, const ResumePoint& p) {
  if (index_ != 0) throw Error("a scan can only be resumed on a fresh pipeline (this one has run " +
                               std::to_string(index_) + " frames)");
  const volume::VolumeOptions& m = model.options();
  const volume::VolumeOptions& v = o_.volume;
  if (m.voxel_m != v.voxel_m || m.truncation_voxels != v.truncation_voxels || m.encoding != v.encoding)
    throw Error("the saved model has " + std::to_string(1000 * m.voxel_m) + " mm voxels, truncation " +
                std::to_string(m.truncation_voxels) + " voxels, " + volume::VoxelEncodingName(m.encoding) +
                " encoding; the settings ask for " + std::to_string(1000 * v.voxel_m) + " mm, " +
                std::to_string(v.truncation_voxels) + ", " + volume::VoxelEncodingName(v.encoding) +
                ": resume with the project's own settings");
  if (p.frames < 0) throw Error("a resume point cannot have a negative frame count");
  const bool need_frame = !reference_from_model_ && p.frames > 0;
  if (need_frame && (p.reference_color.width() != cam_.width || p.reference_color.height() != cam_.height ||
                     p.reference_depth.width() != cam_.width || p.reference_depth.height() != cam_.height))
    throw Error("this scan tracks frame to frame, and its resume point has no " + std::to_string(cam_.width) + "x" +
                std::to_string(cam_.height) + " reference frame");
  Backend& b = *backend_;
  b.LoadVolume(model);
  pose_ = p.pose;
  previous_pose_ = p.previous_pose;
  index_ = p.frames;
  first_exposure_ms_ = p.first_exposure_ms;
  full_reported_ = model.full();
  if (p.frames == 0) return;
  // The state the last Process() left: the ray cast from the last pose, and the reference.
  if (model.allocated_bricks() > 0) b.Raycast(pose_);
  if (reference_from_model_) {
    if (b.HasRender()) b.ReferenceFromRender();
  } else {
    b.Convert(p.reference_color, p.reference_depth);
    b.Normalize();
    b.BuildLive();
    b.ReferenceFromLive(pose_);
    reference_color_ = p.reference_color.Clone();
    reference_depth_ = p.reference_depth.Clone();
  }
}

}  // namespace hdrf::pipeline
