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
constexpr std::size_t kMinHistory = 5;
constexpr double kShiftM = 0.1;      // relocalisation: starts shifted this far along each camera axis...
constexpr double kTurnRad = 0.0873;  // ...and turned this far (5 degrees) about its x and y axes
constexpr double kRecoveringGrowth = 1.5;  // residual bound while recovering, times the usual
constexpr double kRelocalisedPhotoGrowth = 1.25;  // ...and a relocalised pose's radiance residual
// How far a relocalised pose may lie from the view it was tracked from, times the jump a
// tracked frame may make from its prediction (tracker.max_jump_m, max_jump_deg): that view is
// only where the search began; the verification judges the pose.
constexpr double kRelocalisedJumpScale = 4;
constexpr double kSpeedSlackM = 0.02;     // the speed check's allowance for a pose's own noise, metres
constexpr int kMaxExtrapolate = 30;  // frames the last motion is carried on while lost
constexpr double kMinColourShare = 0.1;    // recovering: colour terms per depth term to confirm a pose
constexpr double kMaxPriorSigmas = 5;      // a pose this many prior deviations from the prediction: refused
constexpr double kMinExposureShare = 0.03;  // exposure samples per sample point for a usable estimate
void Push(std::vector<double>& v, double x) {
  v.push_back(x);
  if (v.size() > kHistory) v.erase(v.begin());
}
bool UsesIcp(tracking::TrackerKind k) { return k == tracking::TrackerKind::kNrIcp || k == tracking::TrackerKind::kIcp; }
double Clamp01(double x) { return std::clamp(x, 0.0, 1.0); }
}  // namespace

double Pipeline::Median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}


bool UsesPhoto(tracking::TrackerKind k) { return k != tracking::TrackerKind::kIcp; }

// The residual of each term the tracker uses against the scan's usual: ratios (1: as usual;
// 0 where there is no history yet or the residual is under its floor).
struct ResidualRatios {
  double icp = 0, photo = 0;
  double worst() const { return std::max(icp, photo); }
};

Pipeline::Verdict Pipeline::Verify(const tracking::TrackResult& r, const FrameInput& in, bool recovering,
                                   bool relocalised) {
  Verdict v;
  const tracking::TrackerOptions& t = o_.tracker;
  if (r.lost) {
    v.why = r.why;
    v.score = 1e30;
    return v;
  }
  // Residuals: each term against its own recent median. Recovering (the pose does not come
  // from the last one), the bound is tighter: a view whose geometry leaves a direction loose
  // has wrong poses with as small a point-to-surface error as the true one, and only the
  // radiance residual tells them apart.
  // A relocalised pose (tracked from a view of the scan's database, not from the last pose)
  // is held tighter still on its radiance: where a part of the room repeats its shapes, poses
  // far off fit the depth better than the usual frame, and after tracking degraded the usual
  // itself is inflated. Measured on the built-in room at 160x120 after such a loss: wrong
  // poses 47-87 cm off, their point-to-surface errors 0.2-0.85 of the scan's usual, their
  // radiance residuals 1.38-1.49 of it; the right ones at most 1.09.
  const double growth = recovering ? std::min(double(t.verify_growth), kRecoveringGrowth) : t.verify_growth;
  const double photo_growth = relocalised ? std::min(growth, kRelocalisedPhotoGrowth) : growth;
  auto check = [&](const std::vector<double>& hist, double res, double floor, bool icp, double* ratio) {
    if (hist.size() < kMinHistory) return;
    const double base = Median(hist);
    *ratio = base > 0 ? res / base : 0;
    if (!v.why.empty() || res <= floor || res <= (icp ? growth : photo_growth) * base) return;
    v.why = icp ? Say(words::kIcpResidualHigh, {Num(100 * res, 1), Num(res / base, 1), Num(100 * base, 1)})
                : Say(words::kPhotoResidualHigh, {Num(res, 3), Num(res / base, 1), Num(base, 3)});
  };
  ResidualRatios ratios;
  if (UsesIcp(t.kind)) check(icp_residuals_, r.rms_icp_m, t.verify_floor_m, true, &ratios.icp);
  if (UsesPhoto(t.kind)) check(photo_residuals_, r.rms_photo, t.verify_floor_photo, false, &ratios.photo);
  v.score = ratios.worst();
  v.residual_ratio = ratios.worst();
  if (!v.why.empty()) return v;
  // Speed since the last accepted pose, over the real time between them: a pose that slides
  // along a weakly constrained view carries the constant-velocity prediction with it (so the
  // jump check, against the prediction, passes), but soon implies a camera faster than a hand.
  // Relocalised poses too: a camera carried elsewhere while covered had the time to get there;
  // a recording spliced from two has timestamps that go back or jump, and is not bounded.
  if (pose_time_ && in.timestamp > *pose_time_) {
    const double dt = in.timestamp - *pose_time_;
    const double moved = (r.T_world_camera.translation() - pose_.translation()).norm();
    if (moved > t.max_speed_mps * dt + kSpeedSlackM) {
      v.why = Say(words::kTooFast, {Num(moved, 2), Num(1e3 * dt, 0), Num(moved / dt, 1), Num(t.max_speed_mps, 1)});
      return v;
    }
  }
  // Agreement with the motion prior the pose was solved with: a hand-held camera departs
  // from constant velocity by about 1 cm and 1 degree a frame; the pixel terms dragging the
  // pose several times that from the prediction is a view that fits a wrong pose (a striped
  // wall one stripe over, a nearly all-clipped frame), not a hand.
  if (r.prior_sigmas > kMaxPriorSigmas) {
    v.why = Say(words::kLeftPrediction,
                {Num(100 * r.prior_offset_m, 1), Num(r.prior_offset_rad * 180 / 3.14159265358979, 1),
                 Num(r.prior_sigmas, 1)});
    return v;
  }
  const double robust = UsesIcp(t.kind) ? r.icp_inliers : r.photo_inliers;
  if (robust < t.min_robust_inliers) {
    v.why = Say(words::kFewPixelsFit, {std::to_string(int(100 * robust))});
    return v;
  }
  // Recovering with depth and colour, a pose is told from the wrong ones by its radiance
  // (wrong poses along a flat wall fit the depth as well as the right one): a frame whose
  // colour is nearly all clipped or black cannot confirm one.
  if (recovering && t.kind == tracking::TrackerKind::kNrIcp && r.icp_matched > 0 &&
      r.photo_matched < kMinColourShare * r.icp_matched) {
    v.why = Say(words::kTooLittleColour, {std::to_string(int(100 * r.photo_matched / r.icp_matched))});
    return v;
  }
  Backend& b = *backend_;
  if (b.HasRender()) {
    v.exposure = b.EstimateExposure(r.T_world_camera);
    // An estimate from a few unclipped pixels of a frame otherwise clipped (a thin dark edge
    // in a white frame) measures those pixels, not the exposure: not used.
    const long grid = long(cam_.width / o_.exposure.stride) * long(cam_.height / o_.exposure.stride);
    if (v.exposure.samples < long(kMinExposureShare * double(grid))) v.exposure.valid = false;
    if (v.exposure.valid && in.exposure_ms && first_exposure_ms_ && *in.exposure_ms > 0 && v.exposure.ratio > 0) {
      v.drift = std::log(v.exposure.ratio / (*first_exposure_ms_ / *in.exposure_ms));
      if (exposure_drifts_.size() >= kMinHistory) {
        const double usual = Median(exposure_drifts_);
        if (std::fabs(v.drift - usual) > std::log1p(double(t.max_exposure_drift)))
          v.why = Say(words::kExposureDisagrees, {Num(std::exp(v.drift - usual), 2)});
      }
    }
  }
  return v;
}

double Pipeline::Quality(const tracking::TrackResult& r, const Verdict& v) const {
  if (r.lost || !v.why.empty()) return 0;
  const tracking::TrackerOptions& t = o_.tracker;
  const double share = Clamp01((r.inlier_share - t.min_inlier_share) / std::max(1e-6, 0.6 - double(t.min_inlier_share)));
  const double robust_v = UsesIcp(t.kind) ? r.icp_inliers : r.photo_inliers;
  const double robust = Clamp01((robust_v - t.min_robust_inliers) / std::max(1e-6, 0.9 - double(t.min_robust_inliers)));
  // 1 up to the usual residual, 0 at the verification's bound.
  const double residual = v.residual_ratio <= 1 ? 1 : Clamp01((t.verify_growth - v.residual_ratio) / (t.verify_growth - 1 + 1e-9));
  const Pose step = pose_.inverse() * r.T_world_camera;
  const double motion = Clamp01(1 - std::max(se3::TranslationNorm(step) / t.max_jump_m,
                                             se3::RotationAngle(step) / (t.max_jump_deg * 3.14159265358979 / 180)));
  return std::min({share, robust, residual, motion});
}

tracking::TrackerOptions Pipeline::TrackerNow() const {
  tracking::TrackerOptions t = o_.tracker;
  // With tracker.depth_noise_scaling, the point-to-plane scale holds at the frame's median
  // depth and grows with the depth squared (a triangulating sensor's noise), so that far,
  // noisy surfaces weigh less than near ones instead of pulling the pose with their noise.
  if (UsesIcp(t.kind) && t.depth_noise_scaling) t.icp_depth_ref_m = float(depth_median_m_);
  if (!t.adaptive_scales) return t;
  if (icp_residuals_.size() >= kMinHistory)
    t.icp_sigma_m = float(std::max(double(t.icp_sigma_floor_m), Median(icp_residuals_)));
  if (photo_residuals_.size() >= kMinHistory)
    t.photo_sigma = float(std::max(double(t.photo_sigma_floor), Median(photo_residuals_)));
  return t;
}

double Pipeline::Steps(const FrameInput& in) const {
  // Timestamps jitter by a few milliseconds, and frames delivered in a burst after a stall
  // carry the times they were read at: only a gap half again as long as the last one
  // (frames dropped) lengthens the step, and none shortens it.
  if (!pose_time_ || !previous_time_) return 1;
  const double last = *pose_time_ - *previous_time_, now = in.timestamp - *pose_time_;
  if (!(last > 0) || !(now > 0)) return 1;
  const double steps = now / last;
  return steps < 1.5 ? 1.0 : std::min(steps, double(kMaxExtrapolate));
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
  Backend& b = *backend_;
  {
    const DepthSamples d = SampleDepth(in.depth_m, o_.volume.raycast_far_m);
    depth_median_m_ = d.median_m;
    rep.depth_beyond_far = d.beyond_far;
    rep.depth_share = d.share;
  }
  // 0. Until a frame has anchored the model, only a frame with enough depth can.
  if (!anchored_ && rep.depth_share < o_.tracker.min_anchor_depth) {
    rep.state = FrameState::kWaiting;
    rep.tracking.lost = true;
    rep.why = rep.tracking.why =
        Say(words::kWaitingForAnchor, {std::to_string(int(100 * rep.depth_share)),
                                       std::to_string(int(std::ceil(100 * o_.tracker.min_anchor_depth)))});
    rep.T_world_camera = pose_;
    rep.allocated_bricks = b.AllocatedBricks();
    ++index_;
    return rep;
  }
  auto now = [&] {
    if (stage_timing_) b.Synchronize();  // (a stage's time is its device work's)
    return Clock::now();
  };
  const auto t0 = now();
  // 1. Convert: radiance and confidence; depth filtering.
  b.Convert(in.color, in.depth_m);
  const auto t1 = now();
  // 2. Normalize.
  b.Normalize();
  const auto t2 = now();
  // 3. Track against the reference and verify the pose; when lost or recovering, the scan's
  // earlier views are tried too. The anchoring frame has no reference and defines the world.
  b.BuildLive();
  // The model's radiance the live frame would clip is left out of the reference's normalized
  // radiance as the live frame's clipped pixels are left out of its own.
  const Float3 clip = reference_from_model_ ? ReferenceClip(in) : kNoClip;
  // The last frame's ray cast becomes the reference here, once this frame's clipping level
  // is known (made at the end of the last frame, it was made again here whenever the
  // exposure moved the level: every frame of an auto-exposure camera).
  if (anchored_ && reference_from_model_ && lost_run_ == 0 && b.HasRender()) {
    if (ref_pending_) ReferenceFromModel(ClipChanged(*ref_pending_, clip) ? clip : *ref_pending_);
    else if (ClipChanged(ref_clip_, clip)) ReferenceFromModel(clip);
  }
  bool fuse = false, accepted = false, searched = false;
  Verdict verdict;
  RelocCode code;  // the frame's relocalisation code, made once where it is needed
  if (!anchored_) {
    anchored_ = true;
    previous_pose_ = pose_;
    pose_time_ = previous_time_ = in.timestamp;
    first_exposure_ms_ = in.exposure_ms;
    last_ratio_ = 1;
    rep.tracking.T_world_camera = pose_;
    rep.tracking.inlier_share = 1;
    rep.quality = 1;
    fuse = accepted = true;
  } else {
    // Tracking on from an accepted pose starts from a constant-velocity prediction (the
    // last inter-frame motion, repeated). The inlier share counts matches against what both
    // sides can offer: where the model covers only part of the view (an area not scanned
    // yet), matching all of that part is a success, not a loss.
    const tracking::TrackerOptions topt = TrackerNow();
    // `judge`: the options the run is judged with (topt, or the relocalisation's wider jump).
    auto track = [&](const Pose& from, const tracking::MotionPrior* prior = nullptr,
                     const tracking::TrackerOptions* judge = nullptr) {
      // The run first: its counts of valid pixels are the ones LiveValid / ReferenceValid
      // give (the order a call's arguments are evaluated in is the compiler's choice).
      const tracking::GaussNewtonRun run = b.RunTracker(from, topt, prior);
      return tracking::JudgeTrack(run, from, std::min(b.LiveValid(), b.ReferenceValid()), judge ? *judge : topt, prior);
    };
    const Pose velocity = previous_pose_.inverse() * pose_;
    tracking::TrackResult r;
    if (lost_run_ == 0 || !reference_from_model_) {  // (frame to frame: the reference is the last tracked frame)
      // The last motion carried on over the time since the last pose: frames the sensor
      // dropped (or the caller skipped) leave a longer step to predict, and a looser prior.
      const double steps = Steps(in);
      const Pose predicted = se3::Orthonormalized(pose_ * se3::Exp(steps * se3::Log(velocity)));
      const tracking::MotionPrior prior{predicted, steps};
      if (b.HasRender()) b.EstimateExposureWithNextRun();  // (Verify estimates it at the pose found)
      r = track(predicted, &prior);
      if (topt.kind == tracking::TrackerKind::kNrIcp && topt.photo_agreement && !r.lost)
        WeighPhotometric(b, topt, predicted, prior, &r);
      verdict = Verify(r, in, recovering_);
    } else {
      // Lost: from the last pose carried on with its last motion (a camera that went on
      // moving while it was covered), and from the last pose itself (one that stopped),
      // each against the model ray cast from there.
      Pose carried = pose_;
      for (int k = 0; k <= std::min(lost_run_, kMaxExtrapolate); ++k) carried = se3::Orthonormalized(carried * velocity);
      searched = true;
      bool first = true;
      for (const Pose& start : {carried, pose_}) {
        b.Raycast(start, Backend::RaycastStart::kNear);
        ReferenceFromModel(clip);
        const tracking::TrackResult rc = track(start);
        const Verdict vc = Verify(rc, in, true);
        if (first || (vc.why.empty() && (!verdict.why.empty() || vc.score < verdict.score))) {
          r = rc;
          verdict = vc;
        }
        first = false;
      }
    }
    if ((recovering_ || !verdict.why.empty()) && o_.reloc.enabled && reference_from_model_ && HasRelocEntries()) {
      searched = true;
      code = MakeRelocCode(in.color, in.depth_m, inverse_);
      // Each candidate view is tracked from its own pose; the nearest one also from poses
      // shifted along and turned about the camera's axes, which reach a camera beyond the
      // tracker's reach of that view. Their poses are judged as strictly as while recovering.
      const std::vector<const RelocEntry*> candidates = reloc_.Candidates(code);
      tracking::TrackerOptions reloc_judge = topt;
      reloc_judge.max_jump_m = float(topt.max_jump_m * kRelocalisedJumpScale);
      reloc_judge.max_jump_deg = float(std::min(180.0, topt.max_jump_deg * kRelocalisedJumpScale));
      if (!candidates.empty()) {
        rep.nearest_entry = int(candidates[0] - reloc_.entries().data());
      } else {  // nothing to compare (a covered camera): the view nearest the last known pose
        double best = 1e30;
        for (std::size_t k = 0; k < reloc_.entries().size(); ++k) {
          const Pose d = reloc_.entries()[k].T_world_camera.inverse() * pose_;
          const double cost = se3::TranslationNorm(d) + 0.5 * se3::RotationAngle(d);  // 0.5 m per radian
          if (cost < best) best = cost, rep.nearest_entry = int(k);
        }
      }
      for (std::size_t c = 0; c < candidates.size(); ++c) {
        const RelocEntry* e = candidates[c];
        b.Raycast(e->T_world_camera, Backend::RaycastStart::kNear);
        ReferenceFromModel(clip);
        std::vector<Pose> starts = {e->T_world_camera};
        if (c == 0) {
          for (int axis = 0; axis < 3; ++axis)
            for (double d : {-kShiftM, kShiftM}) {
              Vec6 xi = Vec6::Zero();
              xi[axis] = d;
              starts.push_back(e->T_world_camera * se3::Exp(xi));
            }
          for (int axis = 3; axis < 5; ++axis)
            for (double d : {-kTurnRad, kTurnRad}) {
              Vec6 xi = Vec6::Zero();
              xi[axis] = d;
              starts.push_back(e->T_world_camera * se3::Exp(xi));
            }
        }
        for (const Pose& start : starts) {
          const tracking::TrackResult rc = track(start, nullptr, &reloc_judge);
          const Verdict vc = Verify(rc, in, true, true);
          if (vc.why.empty() && (!verdict.why.empty() || vc.score < verdict.score)) {
            r = rc;
            verdict = vc;
            rep.reloc_entry = int(e - reloc_.entries().data());
          }
        }
      }
    }
    rep.tracking = r;
    rep.quality = Quality(r, verdict);
    if (!verdict.why.empty()) {
      rep.state = FrameState::kLost;
      rep.tracking.lost = true;
      if (rep.tracking.why.empty()) rep.tracking.why = verdict.why;
      rep.why = rep.tracking.why;
      rep.quality = 0;
      recovering_ = true;
      confirmed_ = 0;
      ++lost_run_;
    } else {
      accepted = true;
      const bool after_loss = lost_run_ > 0;
      lost_run_ = 0;
      // A pose found by relocalisation after this frame's own tracking failed is a loss too:
      // it is followed, and fused once confirmed like any other recovery.
      if (rep.reloc_entry >= 0 && !recovering_) recovering_ = true, confirmed_ = 0;
      // After a loss the last accepted pose is frames old: its motion to this one is no one
      // frame's. The next prediction starts from rest, as after a relocalisation.
      const bool restart = rep.reloc_entry >= 0 || after_loss;
      previous_pose_ = restart ? r.T_world_camera : pose_;
      previous_time_ = restart ? std::optional<double>(in.timestamp) : pose_time_;
      pose_ = r.T_world_camera;
      pose_time_ = in.timestamp;
      if (recovering_ && ++confirmed_ < o_.tracker.confirm_frames) {
        rep.state = rep.reloc_entry >= 0 ? FrameState::kRelocalised : FrameState::kConfirming;
        rep.why = Say(words::kConfirmingPose,
                      {std::to_string(confirmed_), std::to_string(o_.tracker.confirm_frames)});
      } else {
        rep.state = rep.reloc_entry >= 0 ? FrameState::kRelocalised : FrameState::kTracked;
        recovering_ = false;
        confirmed_ = 0;
        fuse = true;
      }
    }
  }
  rep.T_world_camera = pose_;
  const auto t3 = now();
  // 4. Exposure compensation against the model (estimated while verifying the pose).
  // Where the frame has too few unclipped pixels over the model to measure it (a frame all
  // white), the exposure is the one predicted from the sensor's report or the last frames.
  double t_ratio = 1;
  if (accepted && verdict.exposure.valid) t_ratio = last_ratio_ = verdict.exposure.ratio;
  else if (const double predicted = PredictedRatio(in); accepted && predicted > 0) t_ratio = predicted;
  rep.exposure_samples = verdict.exposure.samples;
  rep.exposure_ratio = t_ratio;
  if (in.exposure_ms && first_exposure_ms_) rep.exposure_ratio_reported = *first_exposure_ms_ / *in.exposure_ms;
  const auto t4 = now();
  // 5. Integrate (only verified, confirmed poses are fused).
  if (fuse) {
    b.Integrate(pose_, float(t_ratio));
    rep.fused = true;
    if (rep.tracking.iterations > 0) {
      if (UsesIcp(o_.tracker.kind)) Push(icp_residuals_, rep.tracking.rms_icp_m);
      if (UsesPhoto(o_.tracker.kind)) Push(photo_residuals_, rep.tracking.rms_photo);
    }
    if (verdict.drift != 0) Push(exposure_drifts_, verdict.drift);
  }
  const auto t5 = now();
  // 6. Ray cast the model from the pose, and the next frame's reference: the ray cast (frame
  // to model) or this frame where its pose was accepted (frame to frame).
  // A fused frame's depth was taken at this pose: the rays start near the surface it shows.
  if (rep.fused || accepted || searched || !b.HasRender())
    b.Raycast(pose_, rep.fused ? Backend::RaycastStart::kDepth : Backend::RaycastStart::kNear);
  // A fused frame may become a relocalisation entry: made once the ray cast is queued, so that
  // on the GPU this thread's part runs beside the ray cast rather than holding it back (timed
  // with the ray cast's stage).
  if (rep.fused && o_.reloc.enabled && WantsKeyframe(pose_)) {  // (the entry being made, if any, is in now)
    Backend::FrameReadback frame;
    if (code.empty() && device_ == Device::kCuda && b.ReadBackFrame(&frame)) {
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
  // The model's counts once the ray cast is queued (the GPU's integration may still be
  // running: the host waits for it here, with the ray cast queued behind it).
  rep.allocated_bricks = b.AllocatedBricks();
  if (!full_reported_ && rep.fused && b.VolumeFull()) {
    rep.volume_full = b.VolumeFullReason();
    full_reported_ = true;
  }
  if (reference_from_model_) {
    ref_pending_ = clip;  // made when the next frame needs it (or the backend is looked at)
  } else if (accepted || !b.HasReference()) {
    b.ReferenceFromLive(pose_);
    reference_color_ = in.color.Clone();
    reference_depth_ = in.depth_m.Clone();
  }
  const auto t6 = now();
  if (stage_timing_) rep.ms = {Ms(t0, t1), Ms(t1, t2), Ms(t2, t3), Ms(t3, t4), Ms(t4, t5), Ms(t5, t6)};
  ++index_;
  return rep;
}

}  // namespace hdrf::pipeline
