// The frame's pose: tracked from the motion prediction, searched for after a loss (from the
// last pose carried on and from the last pose), relocalised over the scan's earlier views
// where that fails or the scan is recovering, verified against the scan's usual residuals,
// speed, motion prior and exposure, and settled into the frame's state (tracked, lost,
// confirming, relocalised). Pipeline::Process makes one call here (FindPose).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/message.h"
#include "pipeline/backend.h"
#include "pipeline/pipeline.h"

namespace hdrf::pipeline {

namespace {
constexpr std::size_t kMinHistory = 5;  // fused frames before the verification judges residuals
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
double Clamp01(double x) { return std::clamp(x, 0.0, 1.0); }
using tracking::UsesIcp;
using tracking::UsesPhoto;
}  // namespace

Pipeline::PoseFound Pipeline::FindPose(const FrameInput& in, const Float3& clip, FrameReport* rep) {
  if (!anchored_) return Anchor(in, rep);
  PoseFound f;
  const tracking::TrackerOptions topt = TrackerNow();
  if (lost_run_ == 0 || !reference_from_model_) TrackFromPrediction(in, topt, &f);  // (frame to frame: always)
  else SearchAfterLoss(in, clip, topt, &f);
  if ((recovering_ || !f.verdict.why.empty()) && o_.reloc.enabled && reference_from_model_ && HasRelocEntries())
    Relocalise(in, clip, topt, &f, rep);
  Settle(in, &f, rep);
  return f;
}

// The first frame with enough depth defines the world at the pose the scan starts from.
Pipeline::PoseFound Pipeline::Anchor(const FrameInput& in, FrameReport* rep) {
  anchored_ = true;
  previous_pose_ = pose_;
  pose_time_ = previous_time_ = in.timestamp;
  first_exposure_ms_ = in.exposure_ms;
  last_ratio_ = 1;
  rep->tracking.T_world_camera = pose_;
  rep->tracking.inlier_share = 1;
  rep->quality = 1;
  PoseFound f;
  f.accepted = f.fuse = true;
  return f;
}

tracking::TrackResult Pipeline::Track(const Pose& from, const tracking::TrackerOptions& topt,
                                      const tracking::MotionPrior* prior, const tracking::TrackerOptions* judge) {
  // The run first: its counts of valid pixels are the ones LiveValid / ReferenceValid give
  // (the order a call's arguments are evaluated in is the compiler's choice). The inlier
  // share counts matches against what both sides can offer: where the model covers only
  // part of the view (an area not scanned yet), matching all of that part is a success.
  Backend& b = *backend_;
  const tracking::GaussNewtonRun run = b.RunTracker(from, topt, prior);
  return tracking::JudgeTrack(run, from, std::min(b.LiveValid(), b.ReferenceValid()), judge ? *judge : topt, prior);
}

// Tracking on from an accepted pose starts from a constant-velocity prediction (the last
// inter-frame motion, repeated), carried on over the time since the last pose: frames the
// sensor dropped (or the caller skipped) leave a longer step to predict, and a looser prior.
void Pipeline::TrackFromPrediction(const FrameInput& in, const tracking::TrackerOptions& topt, PoseFound* f) {
  Backend& b = *backend_;
  const Pose velocity = previous_pose_.inverse() * pose_;
  const double steps = Steps(in);
  const Pose predicted = se3::Orthonormalized(pose_ * se3::Exp(steps * se3::Log(velocity)));
  const tracking::MotionPrior prior{predicted, steps};
  if (b.HasRender()) b.EstimateExposureWithNextRun();  // (Verify estimates it at the pose found)
  f->r = Track(predicted, topt, &prior);
  if (topt.kind == tracking::TrackerKind::kNrIcp && topt.photo_agreement && !f->r.lost)
    WeighPhotometric(b, topt, predicted, prior, &f->r);
  f->verdict = Verify(f->r, in, recovering_);
}

// Lost: from the last pose carried on with its last motion (a camera that went on moving
// while it was covered), and from the last pose itself (one that stopped), each against the
// model ray cast from there.
void Pipeline::SearchAfterLoss(const FrameInput& in, const Float3& clip, const tracking::TrackerOptions& topt,
                               PoseFound* f) {
  const Pose velocity = previous_pose_.inverse() * pose_;
  Pose carried = pose_;
  for (int k = 0; k <= std::min(lost_run_, kMaxExtrapolate); ++k) carried = se3::Orthonormalized(carried * velocity);
  f->searched = true;
  bool first = true;
  for (const Pose& start : {carried, pose_}) {
    backend_->Raycast(start, Backend::RaycastStart::kNear);
    ReferenceFromModel(clip);
    const tracking::TrackResult rc = Track(start, topt);
    const Verdict vc = Verify(rc, in, true);
    if (first || (vc.why.empty() && (!f->verdict.why.empty() || vc.score < f->verdict.score))) {
      f->r = rc;
      f->verdict = vc;
    }
    first = false;
  }
}

// Each candidate view of the scan's database is tracked from its own pose; the nearest one
// also from poses shifted along and turned about the camera's axes, which reach a camera
// beyond the tracker's reach of that view. Their poses are judged as strictly as while
// recovering; the best that verifies replaces the frame's own.
void Pipeline::Relocalise(const FrameInput& in, const Float3& clip, const tracking::TrackerOptions& topt,
                          PoseFound* f, FrameReport* rep) {
  f->searched = true;
  f->code = MakeRelocCode(in.color, in.depth_m, inverse_);
  const std::vector<const RelocEntry*> candidates = reloc_.Candidates(f->code);
  tracking::TrackerOptions reloc_judge = topt;
  reloc_judge.max_jump_m = float(topt.max_jump_m * kRelocalisedJumpScale);
  reloc_judge.max_jump_deg = float(std::min(180.0, topt.max_jump_deg * kRelocalisedJumpScale));
  if (!candidates.empty()) {
    rep->nearest_entry = int(candidates[0] - reloc_.entries().data());
  } else {  // nothing to compare (a covered camera): the view nearest the last known pose
    double best = 1e30;
    for (std::size_t k = 0; k < reloc_.entries().size(); ++k) {
      const Pose d = reloc_.entries()[k].T_world_camera.inverse() * pose_;
      const double cost = se3::TranslationNorm(d) + 0.5 * se3::RotationAngle(d);  // 0.5 m per radian
      if (cost < best) best = cost, rep->nearest_entry = int(k);
    }
  }
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const RelocEntry* e = candidates[c];
    backend_->Raycast(e->T_world_camera, Backend::RaycastStart::kNear);
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
      const tracking::TrackResult rc = Track(start, topt, nullptr, &reloc_judge);
      const Verdict vc = Verify(rc, in, true, true);
      if (vc.why.empty() && (!f->verdict.why.empty() || vc.score < f->verdict.score)) {
        f->r = rc;
        f->verdict = vc;
        rep->reloc_entry = int(e - reloc_.entries().data());
      }
    }
  }
}

// The frame's state from its verdict. A pose that verifies after a loss is followed, and
// fused once enough frames in a row have confirmed it.
void Pipeline::Settle(const FrameInput& in, PoseFound* f, FrameReport* rep) {
  rep->tracking = f->r;
  rep->quality = Quality(f->r, f->verdict);
  if (!f->verdict.why.empty()) {
    rep->state = FrameState::kLost;
    rep->tracking.lost = true;
    if (rep->tracking.why.empty()) rep->tracking.why = f->verdict.why;
    rep->why = rep->tracking.why;
    rep->quality = 0;
    recovering_ = true;
    confirmed_ = 0;
    ++lost_run_;
    return;
  }
  f->accepted = true;
  const bool after_loss = lost_run_ > 0;
  lost_run_ = 0;
  // A pose found by relocalisation after this frame's own tracking failed is a loss too:
  // it is followed, and fused once confirmed like any other recovery.
  if (rep->reloc_entry >= 0 && !recovering_) recovering_ = true, confirmed_ = 0;
  // After a loss the last accepted pose is frames old: its motion to this one is no one
  // frame's. The next prediction starts from rest, as after a relocalisation.
  const bool restart = rep->reloc_entry >= 0 || after_loss;
  previous_pose_ = restart ? f->r.T_world_camera : pose_;
  previous_time_ = restart ? std::optional<double>(in.timestamp) : pose_time_;
  pose_ = f->r.T_world_camera;
  pose_time_ = in.timestamp;
  if (recovering_ && ++confirmed_ < o_.tracker.confirm_frames) {
    rep->state = rep->reloc_entry >= 0 ? FrameState::kRelocalised : FrameState::kConfirming;
    rep->why = Say(words::kConfirmingPose, {std::to_string(confirmed_), std::to_string(o_.tracker.confirm_frames)});
  } else {
    rep->state = rep->reloc_entry >= 0 ? FrameState::kRelocalised : FrameState::kTracked;
    recovering_ = false;
    confirmed_ = 0;
    f->fuse = true;
  }
}

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

}  // namespace hdrf::pipeline
