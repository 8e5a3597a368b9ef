// The per-frame HDRFusion system: convert, normalize, track, compensate exposure, integrate,
// ray cast. A plain object with Process(): ScanSession wraps it for the CLI, the studio (on
// its own thread), the benchmarks and the experiments.
#pragma once

#include <array>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/cuda_runtime.h"
#include "common/image.h"
#include "common/se3.h"
#include "imaging/imaging.h"
#include "mesh/mesh.h"
#include "pipeline/backend.h"
#include "pipeline/options.h"
#include "pipeline/relocaliser.h"
#include "radiometry/pcf.h"
#include "radiometry/sensor.h"
#include "tracking/tracking.h"
#include "volume/volume.h"

namespace hdrf::pipeline {

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
  StageTimes& operator+=(const StageTimes& o);
  StageTimes operator/(double n) const;
};

// What became of a frame's pose.
enum class FrameState {
  kWaiting,      // no frame has anchored the model yet, nor could this one (too little depth)
  kTracked,      // tracked and verified: fused
  kLost,         // no pose that verifies: not fused
  kConfirming,   // a pose that verifies after a loss, not yet confirmed by enough frames: not fused
  kRelocalised,  // found again from an earlier view of the scan (confirmed before it is fused)
};
const char* FrameStateName(FrameState s);  // "waiting", "tracked", "lost", "confirming", "relocalised"

struct FrameReport {
  int index = 0;
  FrameState state = FrameState::kTracked;
  // Tracking quality, 0..1, before the pose is judged: how close the frame came to the limits
  // (matched share, residual against the scan's usual, robust inliers, motion). Below about
  // 0.5 the operator should slow down; 0 when lost.
  double quality = 0;
  std::string why;  // why the frame was not fused (empty when it was)
  double depth_share = 0;  // share of pixels with depth (every 4th pixel in x and y)
  int reloc_entry = -1;    // the relocalisation entry whose view found the pose, or -1
  // While lost: the entry whose view looks most like this frame, or where the frame shows
  // nothing to compare (a covered camera) the one nearest the last known pose; else -1.
  int nearest_entry = -1;
  double timestamp = 0;
  Pose T_world_camera = Pose::Identity();
  tracking::TrackResult tracking;
  bool fused = false;
  double exposure_ratio = 1;             // estimated t (model radiance / live radiance)
  std::optional<double> exposure_ratio_reported;  // e_0 / e_k from the sensor's exposures
  long exposure_samples = 0;
  StageTimes ms;  // zero where the pipeline does not time its stages (Pipeline::set_stage_timing)
  std::size_t allocated_bricks = 0;
  // Set on the one frame at which the volume became full: why (its memory budget, or the
  // memory the system or GPU had free). From then on surfaces not yet in the model are not
  // added; tracking and fusion into the bricks it has go on.
  std::string volume_full;
  // Share of the frame's depth (every 4th pixel in each direction, of those with depth) that
  // lies beyond volume.raycast_far_m: surfaces fused into the model but beyond the ray cast
  // that tracking matches against and the model views show.
  double depth_beyond_far = 0;
};

struct VolumeStats {
  std::size_t allocated_bricks = 0, bytes = 0;
  bool full = false;  // allocation stopped at the memory limit
  std::string full_reason;
  std::array<Float3, 2> bounds{};  // world box of the allocated bricks (min, max; zeros when empty)
  StreamingStats streaming;        // with a GPU budget: bricks on the GPU and in host memory
};

// Where a scan stopped, beside its model: what Pipeline::Resume needs to go on exactly as
// if it had never stopped (project files hold it).
struct ResumePoint {
  int frames = 0;                               // frames processed so far
  Pose pose = Pose::Identity();                 // the last tracked pose...
  Pose previous_pose = Pose::Identity();        // ...and the one before (motion prediction)
  std::optional<double> first_exposure_ms;      // the exposure the model's units refer to
  // Frame-to-frame tracking only: the last tracked frame, the next frame's reference
  // (empty when the scan tracks against the model, whose ray cast is the reference).
  ColorImage reference_color;
  DepthImage reference_depth;
  // Where the last ray cast's rays started (Backend::RaycastGuide; empty: at near).
  Image<float> raycast_guide;
  // Pose verification and recovery: whether a frame anchored the model, whether the scan is
  // recovering from a loss (and how many frames have verified since), the recent residuals
  // and exposure drifts the next poses are judged against, and the relocalisation views.
  bool anchored = false;
  bool recovering = false;
  int confirmed = 0;
  std::vector<double> residuals, photo_residuals, exposure_drifts;  // residuals: point-to-surface
  int lost_run = 0;  // frames since the last accepted pose
  std::vector<RelocEntry> reloc;
};

// The per-frame system. Owns the backend (the frame's images, the model and the tracking
// reference, wherever they are computed) and the camera's pose; a scan's history (poses,
// reports, timings) is ScanSession's.
class Pipeline {
 public:
  Pipeline(const PipelineOptions& options, const PinholeCamera& camera, const SensorInfo& sensor);
  ~Pipeline();

  FrameReport Process(const FrameInput& frame);
  // Whether Process() times its stages (FrameReport::ms; on by default): it then waits for
  // the device at the end of each stage. Off, the device is waited for only where the frame
  // reads a result back (the tracker's run, the exposure estimate, the new bricks), so the
  // frame's last ray cast runs beside the next frame's upload; the results are the same.
  void set_stage_timing(bool on) { stage_timing_ = on; }
  // Waits until the device has done all the work queued so far (a no-op on the CPU).
  void Synchronize() { backend_->Synchronize(); }

  const PipelineOptions& options() const { return o_; }
  Device device() const { return device_; }  // where the engine actually runs
  // Why the engine runs elsewhere than asked ("" when it runs where asked).
  const std::string& device_note() const { return device_note_; }
  // A setting the frames' size made the pipeline change (empty if none), said once.
  const std::string& settings_note() const { return settings_note_; }
  const Pose& pose() const { return pose_; }
  int frames() const { return index_; }
  VolumeStats volume_stats() const;
  // Bricks the last fused frame updated (on CUDA a read-back: for benchmarks, not per frame).
  std::size_t last_visible_bricks() const { return backend_->LastVisibleBricks(); }

  // Copies out of the backend (downloads on CUDA):
  // the model ray cast from a pose (radiance, normals, depth, NR);
  volume::Volume::Rendering Render(const Pose& T_world_camera);
  // the surface, extracted on the device the model lives on; `progress(fraction)` returning
  // false cancels (throws hdrf::Cancelled);
  mesh::Mesh ExtractMesh(const std::function<bool(double)>& progress = {});
  // what the studio's views show of the last frame (those in `which`);
  FrameViews DownloadViews(const ViewSet& which = ViewSet{});
  // the model's bricks changed since the last call (all of them on the first), for a mesher
  // on another thread (mesh/incremental_mesh.h);
  volume::BrickSet ChangedBricks();
  // the whole model (every allocated brick).
  const volume::Volume& DownloadVolume();
  // Where the scan stands now (copies; the model is DownloadVolume()).
  ResumePoint resume_point() const;
  // Goes on from a saved model and resume point: the next Process() continues the scan in
  // the same coordinates as if it had never stopped. Throws hdrf::Error where the model's
  // voxel size, truncation or encoding differ from the options, or where a frame-to-frame
  // scan's point has no reference frame. Call on a fresh Pipeline.
  void Resume(const volume::Volume& model, const ResumePoint& point);
  // The stages themselves, for the backend parity tests (the reference made first where
  // the last frame left it to the next).
  Backend& backend();

 private:
  PipelineOptions o_;
  PinholeCamera cam_;
  radiometry::InverseResponse inverse_;
  radiometry::PcfTables pcf_;
  std::unique_ptr<Backend> backend_;
  Device device_ = Device::kCpu;
  std::string device_note_, settings_note_;
  bool reference_from_model_ = true;       // else the previous tracked frame
  bool stage_timing_ = true;
  Pose pose_ = Pose::Identity();
  Pose previous_pose_ = Pose::Identity();  // for the constant-velocity prediction
  std::optional<double> pose_time_;         // the timestamp of pose_ (none after a resume)
  std::optional<double> previous_time_;     // ... and of previous_pose_
  double Steps(const FrameInput& in) const;  // last motions since pose_ for the prediction
  int index_ = 0;
  std::optional<double> first_exposure_ms_;
  bool full_reported_ = false;
  ColorImage reference_color_;  // frame to frame: the last tracked frame (resume points)
  DepthImage reference_depth_;
  // Verification and recovery (see ResumePoint).
  bool anchored_ = false;
  bool recovering_ = false;
  int confirmed_ = 0;
  std::vector<double> icp_residuals_, photo_residuals_, exposure_drifts_;  // of the last fused frames, newest last
  int lost_run_ = 0;  // frames since the last accepted pose
  Relocaliser reloc_;
  // A keyframe's relocalisation entry being made on another thread (CUDA engine), and its
  // pose; SettleKeyframe() waits for it and adds it. (Declared after backend_: destroyed
  // first, it waits for the thread, which reads the backend's read-back memory.)
  std::shared_future<RelocEntry> keyframe_;
  Pose keyframe_pose_ = Pose::Identity();
  void SettleKeyframe();
  bool HasRelocEntries();              // (settles the keyframe first)
  bool WantsKeyframe(const Pose& T);   // Relocaliser::Wants, with the keyframe being made
  // Clipping: the radiance at which the live frame reads 255, per channel (live units), the
  // last accepted frame's exposure ratio, and the clipping level (model units) the current
  // reference was normalized with (infinite: none).
  Float3 live_clip_{};
  double last_ratio_ = 0;
  Float3 ref_clip_{};
  // The clipping level of the reference the last frame's ray cast is to become, made when
  // the next frame's own level is known (none: the reference is up to date).
  std::optional<Float3> ref_pending_;
  double PredictedRatio(const FrameInput& in) const;  // model / live radiance before tracking (0: unknown)
  Float3 ReferenceClip(const FrameInput& in) const;   // the live frame's clipping level, model units
  void ReferenceFromModel(const Float3& clip);         // the reference from the ray cast, for `clip`

  struct Verdict {
    std::string why;  // empty: verified
    double score = 0; // residual over the scan's usual (lower is better)
    double drift = 0; // log(estimated / reported exposure ratio), 0 where not known
    double residual_ratio = 0;  // the worst term's residual over its usual (0: no history)
    exposure::ExposureEstimate exposure;
  };
  // `recovering`: the pose does not come from the last one; `relocalised`: it comes from a
  // relocalisation entry (a jump, held to a tighter radiance bound).
  Verdict Verify(const tracking::TrackResult& r, const FrameInput& in, bool recovering, bool relocalised = false);
  double Quality(const tracking::TrackResult& r, const Verdict& v) const;
  tracking::TrackerOptions TrackerNow() const;  // the settings, with measured scales

  // The frame's stages around the pose (pipeline.cpp).
  FrameReport Wait(FrameReport rep);  // no frame has anchored the model, and this one cannot
  void RefreshReference(const Float3& clip);  // the last ray cast as this frame's reference
  double CompensateExposure(const FrameInput& in, bool accepted, const exposure::ExposureEstimate& e, FrameReport* rep);
  void Fuse(double t_ratio, double drift, FrameReport* rep);
  void OfferKeyframe(const FrameInput& in, RelocCode code, const FrameReport& rep);
  void LeaveReference(const FrameInput& in, const Float3& clip, bool accepted);

  // The pose search (pose_search.cpp): the frame's pose found, verified and settled.
  struct PoseFound {
    tracking::TrackResult r;
    Verdict verdict;
    bool accepted = false;  // a pose that verifies: the camera's pose now
    bool fuse = false;      // ...and confirmed: the frame is fused
    bool searched = false;  // the model was ray cast from poses other than the last one
    RelocCode code;         // the frame's relocalisation code, where the search made it
  };
  PoseFound FindPose(const FrameInput& in, const Float3& clip, FrameReport* rep);
  PoseFound Anchor(const FrameInput& in, FrameReport* rep);
  // Tracked from `from` (with the motion prior, if any) and judged with `judge` (else `topt`).
  tracking::TrackResult Track(const Pose& from, const tracking::TrackerOptions& topt,
                              const tracking::MotionPrior* prior = nullptr, const tracking::TrackerOptions* judge = nullptr);
  void TrackFromPrediction(const FrameInput& in, const tracking::TrackerOptions& topt, PoseFound* f);
  void SearchAfterLoss(const FrameInput& in, const Float3& clip, const tracking::TrackerOptions& topt, PoseFound* f);
  void Relocalise(const FrameInput& in, const Float3& clip, const tracking::TrackerOptions& topt, PoseFound* f,
                  FrameReport* rep);
  void Settle(const FrameInput& in, PoseFound* f, FrameReport* rep);  // the frame's state from its verdict
  double depth_median_m_ = 0;  // this frame's median depth (the sampled pixels with depth)
  // Every 4th pixel in x and y: the share with depth, the share of those beyond `far_m`, and
  // their median depth (0: none).
  struct DepthSamples {
    double share = 0, beyond_far = 0, median_m = 0;
  };
  static DepthSamples SampleDepth(const DepthImage& depth_m, float far_m);
  // nr+icp: the photometric term weighed by how well it agrees with the depth at the pose
  // found (see the definition); the pose solved again with its share where it does not.
  void WeighPhotometric(Backend& b, const tracking::TrackerOptions& topt, const Pose& start,
                        const tracking::MotionPrior& prior, tracking::TrackResult* r);
  static double Median(std::vector<double> v);

 public:
  // The relocalisation entries (with a keyframe still being made added first).
  const Relocaliser& relocaliser() {
    SettleKeyframe();
    return reloc_;
  }
};

}  // namespace hdrf::pipeline
