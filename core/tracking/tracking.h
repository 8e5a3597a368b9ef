// Camera tracking: Gauss-Newton on SE(3), coarse to fine, on the normalized-radiance
// residual weighted by the pixel confidence (the paper's error function), point-to-plane
// ICP, or both; the brightness-constancy baseline on raw intensity; tracking health.
// (Exposure compensation after tracking: exposure/exposure.h.)
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "common/camera.h"
#include "common/image.h"
#include "common/se3.h"
#include "tracking/gn_step.h"
#include "tracking/tracking_impl.h"

namespace hdrf::tracking {

enum class TrackerKind {
  kNr,         // normalized radiance (photometric), PCF-weighted
  kNrIcp,      // normalized radiance + point-to-plane ICP
  kIcp,        // point-to-plane ICP only
  kIntensity,  // raw 8-bit intensity, brightness constancy: the baseline the paper beats
};
TrackerKind ParseTrackerKind(const std::string& s);  // "nr", "nr+icp", "icp", "intensity"
const char* TrackerName(TrackerKind k);
// Whether a tracker matches depth (point-to-plane ICP) and whether it matches colour.
inline bool UsesIcp(TrackerKind k) { return k == TrackerKind::kNrIcp || k == TrackerKind::kIcp; }
inline bool UsesPhoto(TrackerKind k) { return k != TrackerKind::kIcp; }

struct TrackerOptions {
  TrackerKind kind = TrackerKind::kNrIcp;
  bool frame_to_model = true;             // false: align to the previous frame instead
  int levels = 3;                         // pyramid levels (each half the size)
  std::array<int, 4> iterations = {10, 10, 8, 8};  // per level, coarsest first
  // Combination: each residual is divided by its expected scale before the robust kernel,
  // so that 1 cm of point-to-plane distance weighs as much as 0.25 of normalized radiance.
  float icp_sigma_m = 0.01f;
  float photo_sigma = 0.25f;
  // Measured scales: once the scan has fused a few frames, each term's scale is the median
  // of its recent residuals (never below the floors), so that the terms are combined by how
  // well each actually fits this sensor (a recording whose colour and depth are not
  // registered, say) rather than by the fixed guesses above.
  bool adaptive_scales = true;
  // A triangulating sensor's depth noise grows with the depth squared (a Kinect: 1.5 mm at
  // 1 m, 2 cm at 3.5 m): with this on, the point-to-plane scale holds at the frame's median
  // depth and each residual is scaled by its depth squared (icp_depth_ref_m below). On 500
  // real Kinect frames it takes the drift from 6.2 to 1.85 cm; on the simulator's rooms it
  // drifts more than without (docs/engine.md, "Real sensors"), so it is off by default.
  bool depth_noise_scaling = false;
  // nr+icp: after each frame's solve, how far the photometric term pulled the pose off the
  // depth's own optimum; where it pulled, its share of the solve is cut and the finest level
  // solved again (Pipeline::WeighPhotometric). For colour that is not registered to the
  // depth; off by default (it costs one more sum a frame, and a solve where it cuts).
  bool photo_agreement = false;
  float icp_sigma_floor_m = 0.0005f, photo_sigma_floor = 0.02f;
  float huber_k = 1.345f;                 // Huber threshold, in units of the scales above
  float icp_max_dist_m = 0.10f;           // ICP association gates
  float icp_max_angle_deg = 35.f;
  // Health: a frame is lost (not fused) when fewer than this share of live pixels has a
  // correspondence, the system is this ill-conditioned, or the pose jumps this far.
  float min_inlier_share = 0.2f;
  double max_condition = 1e8;
  // Directions the pixel terms hardly fix (a flat wall slid along, a view mostly clipped)
  // are held to the motion prior: along any direction whose information (in units of the
  // prior's 1 cm and 1 degree) is under this share of the strongest direction's, the prior
  // is raised to make up the difference. 0 turns it off.
  double weak_info_floor = 1e-3;
  float max_jump_m = 0.25f, max_jump_deg = 25.f;
  // Fastest a hand-held camera moves (pipeline verification: a pose farther from the last
  // accepted one than this speed over the time between them, plus 2 cm, is not fused).
  float max_speed_mps = 2.f;
  // Verification (the pipeline's, after tracking): a pose is fused only when its residual
  // (point-to-surface where ICP takes part, else normalized radiance) is within
  // verify_growth times the scan's recent median, or below the floor; when its terms' mean
  // robust weight is at least min_robust_inliers; and when its exposure estimate keeps to
  // the sensor's reported exposure as it did (within max_exposure_drift, relative).
  float verify_growth = 3.f;
  float verify_floor_m = 0.004f, verify_floor_photo = 0.05f;
  float min_robust_inliers = 0.5f;
  float max_exposure_drift = 0.35f;
  // After any lost frame, fusion resumes only once this many frames in a row verify.
  int confirm_frames = 3;
  // The model is anchored by the first frame with at least this share of pixels with depth.
  float min_anchor_depth = 0.25f;
  // Set frame by frame by the pipeline (not settings), with depth_noise_scaling: the depth at which a point-to-plane
  // residual has the scale icp_sigma_m: a residual nearer or farther is scaled with the depth
  // squared, as the noise of a triangulating depth sensor (structured light, stereo) grows;
  // 0: one scale at every depth.
  float icp_depth_ref_m = 0;
  // The photometric term's weight in the solve, 0..1 (its health sums count it whole).
  float photo_share = 1;
  void Check() const;
};

// Views of one pyramid level, as the per-pixel terms see it (host or device memory).
struct ReferenceView {
  PinholeCamera cam;
  ImageView<const Float3> vertex_w, normal_w;
  ImageView<const float> intensity;
};
struct LiveView {
  PinholeCamera cam;
  ImageView<const Float3> vertex_c, normal_c;
  ImageView<const float> intensity, grad_x, grad_y, weight;
};

// One pyramid level of what is tracked against.
struct ReferenceLevel {
  PinholeCamera cam;
  Image<Float3> vertex_w, normal_w;  // world frame; zero = none
  Image<float> intensity;            // NR (or raw intensity for the baseline)
  ReferenceView view() const;
};
struct Reference {
  std::vector<ReferenceLevel> levels;  // finest first
  Pose T_world_camera;                 // the pose it was rendered / captured from
};

// One pyramid level of the live frame.
struct LiveLevel {
  PinholeCamera cam;
  DepthImage depth;                  // metres (halved from the level above)
  Image<Float3> vertex_c, normal_c;  // camera frame
  Image<float> intensity, grad_x, grad_y;
  Image<float> weight;               // PCF confidence (1 for the baseline)
  LiveView view() const;
};
struct Live {
  std::vector<LiveLevel> levels;  // finest first
};

// The most pyramid levels, at most `requested`, whose coarsest image is still at least
// kMinCoarsestWidth x kMinCoarsestHeight pixels (at least one level). A coarser one has too
// few pixels for the local statistics of normalized radiance and the depth it needs: at
// 160x120 a third level (40x30) lost the built-in room from frame 610 on (884 of 2000 frames
// lost, against none with two levels). Cautious: 320x240 with a fourth level (also 40x30)
// fused all of 800 frames; the pipeline says when it lowers the setting.
inline constexpr int kMinCoarsestWidth = 80, kMinCoarsestHeight = 60;
int UsableLevels(int requested, int width, int height);

// Builds pyramid levels: depth halved by DownsampleDepth, intensity and weight by 2x2 means;
// normals undefined across depth jumps above max_normal_jump_m.
Live MakeLive(const DepthImage& depth_m, const Image<float>& intensity, const Image<float>& weight,
              const PinholeCamera& cam, int levels, float max_normal_jump_m = 0.1f);
Reference MakeReference(const Image<Float3>& vertex_w, const Image<Float3>& normal_w,
                        const Image<float>& intensity, const PinholeCamera& cam, int levels,
                        const Pose& T_world_camera);

struct TrackResult {
  Pose T_world_camera = Pose::Identity();
  double rms_icp_m = 0;        // robust-weighted RMS residuals at the finest level
  double rms_photo = 0;         // of the confidence-weighted normalized-radiance difference
  double inlier_share = 0;     // live pixels with a correspondence, finest level
  // Mean robust (Huber) weight of the matched terms at the finest level, 0..1: 1 when every
  // residual is within the kernel's threshold; a pose that only half fits pulls it down.
  double icp_inliers = 0, photo_inliers = 0;
  double icp_matched = 0, photo_matched = 0;  // terms of each kind at the finest level
  // With a motion prior: how far the pixel terms took the pose from the prediction, in the
  // prior's own deviations (the larger of translation and rotation); 0 without one.
  double prior_sigmas = 0;
  double prior_offset_m = 0, prior_offset_rad = 0;
  double condition = 0;        // of J^T J at the finest level
  // The pixel terms' information at the finest level along their weakest direction, in
  // units of (1 cm, 1 degree) (whitened J^T J's smallest eigenvalue), and the largest.
  double weakest_info = 0, strongest_info = 0;
  double weak_offset = 0;      // the pose's offset from the prediction along that direction (whitened)
  int iterations = 0;
  std::array<int, 4> level_iterations{};  // of which at each pyramid level (0 = finest)
  // The photometric term's weight in the solve (0: depth alone; TrackerOptions::photo_share),
  // and how far the pose found with it whole lay from where the depth alone would take it.
  double photo_share = 0;
  double photo_pull_m = 0, photo_pull_rad = 0;
  double icp_depth_ref_m = 0;  // the depth the point-to-plane scale held at (0: every depth)
  bool lost = false;
  std::string why;             // why it was judged lost
};

TrackResult Track(const Reference& ref, const Live& live, const Pose& initial,
                  const TrackerOptions& o);

// The Gauss-Newton loop itself, for any backend: `accumulate(level, T_world_live)` returns
// the summed normal equations at that pyramid level (0 = finest) and pose; `live_valid` is
// the number of pixels that could match at the finest level (for the inlier share): the
// live pixels with depth, or fewer where the reference covers less.
using Accumulator = std::function<GnSystem(int level, const Pose& T_world_live)>;
// With `prior`, each step also weighs a weak motion prior: the pose's offset from the
// constant-velocity prediction against a hand-held camera's deviation from constant velocity
// (1 cm and 1 degree per frame interval the prediction spans). Against thousands of pixel
// terms it is negligible wherever the view constrains the pose; where it does not (a flat
// wall with no usable texture, a frame whose colour is all clipped), the pose keeps to the
// prediction there instead of drifting with the noise.
struct MotionPrior {
  Pose T_world_camera = Pose::Identity();  // the predicted pose
  double frames = 1;                       // frame intervals the prediction spans (> 0)
};
TrackResult Track(const Accumulator& accumulate, int levels, long live_valid, const Pose& initial,
                  const TrackerOptions& o, const MotionPrior* prior = nullptr);

// Track in two parts, for a backend that runs the iterations where its sums are (the CUDA
// backend: on the device, gn_step.h): the iterations, coarse to fine, each level's stopping
// when a step moves the pose less than 0.1 mm and 0.006 degrees, has fewer than 12 terms or
// fails; then the result and its health from where they ended.
struct GaussNewtonRun {
  Pose T_world_camera = Pose::Identity();
  GnSystem last;  // the finest level's last system a step was taken with (zeros: none)
  int iterations = 0;
  std::array<int, 4> level_iterations{};
};
StepPrior MakeStepPrior(const TrackerOptions& o, const MotionPrior* prior);
GaussNewtonRun RunGaussNewton(const Accumulator& accumulate, int levels, const Pose& initial, const TrackerOptions& o,
                              const MotionPrior* prior = nullptr);
TrackResult JudgeTrack(const GaussNewtonRun& run, const Pose& initial, long live_valid, const TrackerOptions& o,
                       const MotionPrior* prior = nullptr);
PoseD ToPoseD(const Pose& T);
Pose FromPoseD(const PoseD& T);
// For tests: the most blocks the CUDA backend's tracker run may use (0: as many as fit the
// GPU at once, at most the reduction's 264; tracking_cuda.cu). Any number gives the same
// bits: each block makes the partials of one or more of the reduction's blocks. Nothing
// without a CUDA build.
void SetTrackerRunBlockLimit(int most);

// The per-pixel term arguments of one level and pose (shared by the CPU and CUDA sums), and
// the CPU sum over a level.
IcpArgs MakeIcpArgs(const ReferenceView& ref, const Pose& T_world_ref, const LiveView& live,
                    const Pose& T_world_live, const TrackerOptions& o);
PhotoArgs MakePhotoArgs(const ReferenceView& ref, const LiveView& live, const Pose& T_world_live,
                        const TrackerOptions& o);
GnSystem AccumulateCpu(const ReferenceView& ref, const Pose& T_world_ref, const LiveView& live,
                       const Pose& T_world_live, const TrackerOptions& o);

}  // namespace hdrf::tracking
