#include "pipeline/pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/message.h"
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
    : o_((options.Check(), options)), cam_(camera), reloc_(options.reloc) {
  if (!camera.Valid()) throw SettingError("camera", "intrinsics must be positive");
  if (const int usable = tracking::UsableLevels(o_.tracker.levels, camera.width, camera.height); usable < o_.tracker.levels) {
    settings_note_ = Say(words::kLevelsLowered,
                         {std::to_string(o_.tracker.levels), std::to_string(usable), std::to_string(camera.width),
                          std::to_string(camera.height), std::to_string(tracking::kMinCoarsestWidth),
                          std::to_string(tracking::kMinCoarsestHeight)});
    o_.tracker.levels = usable;
  }
  if (!sensor.response)
    throw Error("the sensor has no response calibration (sensor.json 'response'); calibrate it "
                "with hdrfusion calibrate, or pass --response srgb to assume an sRGB camera");
  inverse_ = *sensor.response;
  inverse_.Check("sensor response");
  pcf_ = radiometry::ComputePcf(inverse_, sensor.noise ? *sensor.noise : radiometry::DefaultNoise(inverse_));
  const auto inverse = inverse_.Flat();
  // A channel reads 255 from halfway between the radiances of levels 254 and 255 on.
  const auto clip = [&](int c) { return 0.5f * (inverse[std::size_t(c * 256 + 254)] + inverse[std::size_t(c * 256 + 255)]); };
  live_clip_ = {clip(0), clip(1), clip(2)};
  ref_clip_ = kNoClip;
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
      device_note_ = Say(words::kCudaNotUsable, {why});
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
FrameViews Pipeline::DownloadViews(const ViewSet& which) { return backend_->DownloadViews(which); }
volume::BrickSet Pipeline::ChangedBricks() { return backend_->ChangedBricks(); }

const char* FrameStateName(FrameState s) {
  switch (s) {
    case FrameState::kWaiting: return "waiting";
    case FrameState::kTracked: return "tracked";
    case FrameState::kLost: return "lost";
    case FrameState::kConfirming: return "confirming";
    case FrameState::kRelocalised: return "relocalised";
  }
  return "?";
}

namespace {
constexpr std::size_t kHistory = 30;  // fused frames the verification judges against
void Push(std::vector<double>& v, double x) {
  v.push_back(x);
  if (v.size() > kHistory) v.erase(v.begin());
}
}  // namespace

double Pipeline::Median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double Pipeline::PredictedRatio(const FrameInput& in) const {
  // The live frame's exposure against the model's: the sensor's reported exposure with the
  // bias the scan has measured against it, else the last accepted frame's estimate.
  double ratio = last_ratio_;
  if (in.exposure_ms && first_exposure_ms_ && *in.exposure_ms > 0 && *first_exposure_ms_ > 0)
    ratio = *first_exposure_ms_ / *in.exposure_ms * std::exp(exposure_drifts_.empty() ? 0.0 : Median(exposure_drifts_));
  return ratio > 0 && std::isfinite(ratio) ? ratio : 0;
}

void Pipeline::ReferenceFromModel(const Float3& clip) {
  backend_->ReferenceFromRender(clip);
  ref_clip_ = clip;
  ref_pending_.reset();
}

void Pipeline::SettleKeyframe() {
  if (!keyframe_.valid()) return;
  RelocEntry e = keyframe_.get();
  keyframe_ = {};
  reloc_.Add(std::move(e));
}

bool Pipeline::HasRelocEntries() {
  SettleKeyframe();
  return !reloc_.entries().empty();
}

bool Pipeline::WantsKeyframe(const Pose& T) {
  // Near the entry still being made: not wanted, as if it were in (unless adding it thins
  // the entries, which may drop it or the one near).
  if (keyframe_.valid() && !reloc_.Full() && reloc_.Near(keyframe_pose_, T)) return false;
  SettleKeyframe();
  return reloc_.Wants(T);
}

Backend& Pipeline::backend() {
  if (ref_pending_) ReferenceFromModel(*ref_pending_);
  return *backend_;
}

Float3 Pipeline::ReferenceClip(const FrameInput& in) const {
  const double ratio = PredictedRatio(in);
  return ratio > 0 ? live_clip_ * float(ratio) : kNoClip;
}

namespace {
// Whether a reference normalized with clipping level `a` must be normalized again for `b`.
bool ClipChanged(const Float3& a, const Float3& b) {
  if (std::isinf(a.x) || std::isinf(b.x)) return std::isinf(a.x) != std::isinf(b.x);
  return std::fabs(a.x - b.x) > 0.02f * b.x;
}
}  // namespace

FrameReport Pipeline::Process(const FrameInput& in) {
  if (in.color.width() != cam_.width || in.color.height() != cam_.height ||
      in.depth_m.width() != cam_.width || in.depth_m.height() != cam_.height)
    throw Error("frame " + std::to_string(index_) + ": colour or depth size differs from the camera (" +
                std::to_string(cam_.width) + "x" + std::to_string(cam_.height) + ")");
  FrameReport rep;
  rep.index = index_;
  rep.timestamp = in.timestamp;
  const DepthSamples depth = SampleDepth(in.depth_m, o_.volume.raycast_far_m);
  depth_median_m_ = depth.median_m;
  rep.depth_beyond_far = depth.beyond_far;
  rep.depth_share = depth.share;
  // 0. Until a frame has anchored the model, only a frame with enough depth can.
  if (!anchored_ && rep.depth_share < o_.tracker.min_anchor_depth) return Wait(std::move(rep));
  Backend& b = *backend_;
  std::array<Clock::time_point, 7> t;  // the stages' ends (t[0]: the start)
  auto mark = [&](int stage) {
    if (stage_timing_) b.Synchronize();  // (a stage's time is its device work's)
    t[std::size_t(stage)] = Clock::now();
  };
  mark(0);
  // 1. Convert: radiance and confidence; depth filtering.
  b.Convert(in.color, in.depth_m);
  mark(1);
  // 2. Normalize.
  b.Normalize();
  mark(2);
  // 3. Track against the reference and verify the pose; when lost or recovering, the scan's
  // earlier views are tried too (pose_search.cpp). The anchoring frame defines the world.
  b.BuildLive();
  // The model's radiance the live frame would clip is left out of the reference's normalized
  // radiance as the live frame's clipped pixels are left out of its own.
  const Float3 clip = reference_from_model_ ? ReferenceClip(in) : kNoClip;
  RefreshReference(clip);
  PoseFound found = FindPose(in, clip, &rep);
  rep.T_world_camera = pose_;
  mark(3);
  // 4. Exposure compensation against the model (estimated while verifying the pose).
  const double t_ratio = CompensateExposure(in, found.accepted, found.verdict.exposure, &rep);
  mark(4);
  // 5. Integrate (only verified, confirmed poses are fused).
  if (found.fuse) Fuse(t_ratio, found.verdict.drift, &rep);
  mark(5);
  // 6. Ray cast the model from the pose, and the next frame's reference: the ray cast (frame
  // to model) or this frame where its pose was accepted (frame to frame).
  // A fused frame's depth was taken at this pose: the rays start near the surface it shows.
  if (rep.fused || found.accepted || found.searched || !b.HasRender())
    b.Raycast(pose_, rep.fused ? Backend::RaycastStart::kDepth : Backend::RaycastStart::kNear);
  if (rep.fused && o_.reloc.enabled && WantsKeyframe(pose_)) OfferKeyframe(in, std::move(found.code), rep);
  // The model's counts once the ray cast is queued (the GPU's integration may still be
  // running: the host waits for it here, with the ray cast queued behind it).
  rep.allocated_bricks = b.AllocatedBricks();
  if (!full_reported_ && rep.fused && b.VolumeFull()) {
    rep.volume_full = b.VolumeFullReason();
    full_reported_ = true;
  }
  LeaveReference(in, clip, found.accepted);
  mark(6);
  if (stage_timing_) rep.ms = {Ms(t[0], t[1]), Ms(t[1], t[2]), Ms(t[2], t[3]), Ms(t[3], t[4]), Ms(t[4], t[5]), Ms(t[5], t[6])};
  ++index_;
  return rep;
}

FrameReport Pipeline::Wait(FrameReport rep) {
  rep.state = FrameState::kWaiting;
  rep.tracking.lost = true;
  rep.why = rep.tracking.why =
      Say(words::kWaitingForAnchor, {std::to_string(int(100 * rep.depth_share)),
                                     std::to_string(int(std::ceil(100 * o_.tracker.min_anchor_depth)))});
  rep.T_world_camera = pose_;
  rep.allocated_bricks = backend_->AllocatedBricks();
  ++index_;
  return rep;
}

void Pipeline::RefreshReference(const Float3& clip) {
  // The last frame's ray cast becomes the reference here, once this frame's clipping level
  // is known (made at the end of the last frame, it was made again here whenever the
  // exposure moved the level: every frame of an auto-exposure camera).
  if (!anchored_ || !reference_from_model_ || lost_run_ != 0 || !backend_->HasRender()) return;
  if (ref_pending_) ReferenceFromModel(ClipChanged(*ref_pending_, clip) ? clip : *ref_pending_);
  else if (ClipChanged(ref_clip_, clip)) ReferenceFromModel(clip);
}

double Pipeline::CompensateExposure(const FrameInput& in, bool accepted, const exposure::ExposureEstimate& e,
                                    FrameReport* rep) {
  // Where the frame has too few unclipped pixels over the model to measure it (a frame all
  // white), the exposure is the one predicted from the sensor's report or the last frames.
  double t_ratio = 1;
  if (accepted && e.valid) t_ratio = last_ratio_ = e.ratio;
  else if (const double predicted = PredictedRatio(in); accepted && predicted > 0) t_ratio = predicted;
  rep->exposure_samples = e.samples;
  rep->exposure_ratio = t_ratio;
  if (in.exposure_ms && first_exposure_ms_) rep->exposure_ratio_reported = *first_exposure_ms_ / *in.exposure_ms;
  return t_ratio;
}

void Pipeline::Fuse(double t_ratio, double drift, FrameReport* rep) {
  backend_->Integrate(pose_, float(t_ratio));
  rep->fused = true;
  // The residuals and exposure drift the next poses are judged against.
  if (rep->tracking.iterations > 0) {
    if (tracking::UsesIcp(o_.tracker.kind)) Push(icp_residuals_, rep->tracking.rms_icp_m);
    if (tracking::UsesPhoto(o_.tracker.kind)) Push(photo_residuals_, rep->tracking.rms_photo);
  }
  if (drift != 0) Push(exposure_drifts_, drift);
}

// A fused frame may become a relocalisation entry: made once the ray cast is queued, so that
// on the GPU this thread's part runs beside the ray cast rather than holding it back (timed
// with the ray cast's stage). (The entry being made before, if any, is in now.)
void Pipeline::OfferKeyframe(const FrameInput& in, RelocCode code, const FrameReport& rep) {
  Backend::FrameReadback frame;
  if (code.empty() && device_ == Device::kCuda && backend_->ReadBackFrame(&frame)) {
    // The GPU runs the frame; the CPU's cores are free: the entry is made beside the
    // next frames (the same entry, added before any other and before it is looked up),
    // from the frame read back from the GPU (this thread neither waits nor copies: a
    // copy of a 640x480 frame here took longer than the GPU's whole frame). The read-back
    // memory is reused at the next entry, made only once this one is settled.
    keyframe_pose_ = pose_;
    keyframe_ = std::async(std::launch::async, [index = rep.index, T = pose_, frame, w = cam_.width,
                                                h = cam_.height, inverse = &inverse_] {
                  frame.wait();
                  ColorImage color(w, h);
                  DepthImage depth(w, h);
                  std::copy_n(frame.color, color.size(), color.data());
                  std::copy_n(frame.depth, depth.size(), depth.data());
                  return RelocEntry(index, T, MakeRelocCode(color, depth, *inverse), Thumbnail(color));
                }).share();
  } else {
    reloc_.Add({rep.index, pose_, code.empty() ? MakeRelocCode(in.color, in.depth_m, inverse_) : std::move(code),
                Thumbnail(in.color)});
  }
}

void Pipeline::LeaveReference(const FrameInput& in, const Float3& clip, bool accepted) {
  if (reference_from_model_) {
    ref_pending_ = clip;  // made when the next frame needs it (or the backend is looked at)
  } else if (accepted || !backend_->HasReference()) {
    backend_->ReferenceFromLive(pose_);
    reference_color_ = in.color.Clone();
    reference_depth_ = in.depth_m.Clone();
  }
}

}  // namespace hdrf::pipeline
