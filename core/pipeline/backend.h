// The engine's per-frame stages behind one interface, so that Pipeline::Process runs the
// same sequence (and the same Gauss-Newton loop) on the CPU reference backend and on the
// CUDA backend. A backend holds the frame's images and the model wherever it computes.
#pragma once

#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "common/camera.h"
#include "common/image.h"
#include "common/se3.h"
#include "exposure/exposure.h"
#include "imaging/imaging.h"
#include "pipeline/options.h"
#include "mesh/mesh.h"
#include "tracking/tracking.h"
#include "volume/volume.h"

namespace hdrf::pipeline {

// Where the model's bricks are, with a GPU budget (volume.gpu_memory_mb): on the GPU, or
// moved to host memory, and how many moved each way so far (zeros on the CPU).
struct StreamingStats {
  std::size_t gpu_bricks = 0, host_bricks = 0, gpu_bytes = 0;
  long swapped_out = 0, swapped_in = 0;
};

struct BackendSetup {
  const PipelineOptions& options;  // copied by the backend
  PinholeCamera camera;
  const float* inverse;  // 3 x 256 inverse response, channel-major
  const float* pcf;      // 3 x 256 PCF of the chosen variant
};

// What the studio's live views show of a frame (host copies): its radiance, confidence,
// normalized radiance and filtered depth, and the model ray cast from its pose.
struct FrameViews {
  RadianceImage radiance;
  Image<float> confidence, max_confidence, nr;
  DepthImage depth;  // filtered, metres
  volume::Volume::Rendering render;
};
// Which of them a caller wants copied (the studio: only the views on screen; an image not
// wanted stays empty).
struct ViewSet {
  bool radiance = true;    // radiance
  bool confidence = true;  // confidence and max_confidence
  bool nr = true;
  bool depth = true;
  bool render = true;      // the model's ray cast
};

// Every intermediate image of the last frame, every pyramid level (host copies): what the
// backend parity tests compare stage by stage. Much larger than FrameViews.
struct FrameImages {
  RadianceImage radiance;
  Image<float> confidence, max_confidence, nr;
  DepthImage depth;                        // filtered
  std::vector<Image<Float3>> live_vertex, live_normal;  // per pyramid level, finest first
  std::vector<Image<float>> live_intensity, live_weight, live_grad_x;
  std::vector<Image<Float3>> ref_vertex, ref_normal;
  std::vector<Image<float>> ref_intensity;
  volume::Volume::Rendering render;
};

// The stages of one frame, in the order Pipeline::Process calls them. Each stage reads what
// the stages before it left in the backend (named under "reads") and replaces what it
// writes; nothing else carries over between frames except the model and the reference.
// The clipping level of a reference with none: every model radiance takes part in its
// normalized radiance's statistics.
inline constexpr Float3 kNoClip{std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
                                std::numeric_limits<float>::infinity()};
inline bool SameClip(const Float3& a, const Float3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

class Backend {
 public:
  virtual ~Backend() = default;
  // 1. Reads the frame. Writes the radiance and pixel confidence of the colour, and the
  // filtered depth.
  virtual void Convert(const ColorImage& color, const DepthImage& depth_m) = 0;
  // 2. Reads the radiance (or, for the brightness-constancy tracker, the colour of stage 1).
  // Writes the normalized radiance and the image and weight the tracker matches.
  virtual void Normalize() = 0;
  // 3. Reads the filtered depth and the tracked image. Writes the live pyramid.
  virtual void BuildLive() = 0;
  // The tracker's normal equations of the live pyramid at a pose against the reference (at
  // its own pose), with the tracker settings of this frame (its measured scales); pixels with
  // depth in the live frame; pixels the reference offers.
  virtual tracking::GnSystem Accumulate(int level, const Pose& T_world_live, const tracking::TrackerOptions& t) = 0;
  // The tracker's Gauss-Newton iterations from a pose, with this frame's tracker settings:
  // tracking::RunGaussNewton over Accumulate; the CUDA backend keeps them on the device.
  virtual tracking::GaussNewtonRun RunTracker(const Pose& initial, const tracking::TrackerOptions& t,
                                              const tracking::MotionPrior* prior) {
    return tracking::RunGaussNewton([&](int l, const Pose& T) { return Accumulate(l, T, t); }, t.levels, initial, t,
                                    prior);
  }
  virtual long LiveValid() = 0;
  virtual long ReferenceValid() = 0;
  // 4. Reads the radiance and the last ray cast. The exposure ratio of the live frame.
  virtual exposure::ExposureEstimate EstimateExposure(const Pose& T_world_live) = 0;
  // Says that the next RunTracker is likely followed by EstimateExposure at the pose it finds:
  // a backend may make the estimate with the run (the CUDA backend queues it behind the run on
  // the device and reads both back at once). The same estimate either way.
  virtual void EstimateExposureWithNextRun() {}
  // 5. Reads the radiance, confidence, NR, filtered depth and finest live normals. Fuses
  // them at a pose into the model, the radiance scaled by `ratio`.
  virtual void Integrate(const Pose& T_world_camera, float ratio) = 0;
  virtual std::size_t AllocatedBricks() = 0;
  virtual std::size_t LastVisibleBricks() = 0;  // bricks updated by the last Integrate
  virtual std::size_t VolumeBytes() = 0;
  virtual bool VolumeFull() = 0;  // allocation stopped at the memory limit
  virtual std::string VolumeFullReason() = 0;  // why, naming the limit ("" while not full)
  virtual std::array<Float3, 2> VolumeBounds() = 0;  // the allocated bricks' world box
  virtual StreamingStats Streaming() { return {}; }
  // 6. Ray casts the model from a pose (kept as the last rendering). Where the rays start:
  // kNear: at volume.raycast_near_m; kDepth: near the surface this frame's filtered depth
  // shows (the pose must be the frame's: the frame just fused), each tile of rays from its
  // nearest depth less the truncation (RaycastGuide); kKept: as the guide set last.
  enum class RaycastStart { kNear, kDepth, kKept };
  virtual void Raycast(const Pose& T_world_camera, RaycastStart start) = 0;
  // The last ray cast's guide (host copy; empty when it started at near), and one to use
  // with kKept (a resumed scan's).
  virtual Image<float> RaycastGuide() = 0;
  virtual void SetRaycastGuide(const Image<float>& guide) = 0;
  virtual bool HasRender() const = 0;
  // The tracking reference, with the pose it belongs to: the last ray cast (frame to model),
  // or the live pyramid placed at a pose (frame to frame). The ray cast's normalized radiance
  // leaves out model radiance at or above `clip` in any channel (the live frame's clipping
  // level in model units; infinite: none), where the model keeps no NR of its own: such a
  // model's ray cast is normalized here, once per ray cast and clipping level.
  virtual void ReferenceFromRender(const Float3& clip) = 0;
  virtual void ReferenceFromLive(const Pose& T_world_camera) = 0;
  virtual bool HasReference() const = 0;
  virtual Pose ReferencePose() const = 0;
  // Waits for queued work (timing); a no-op on the CPU.
  virtual void Synchronize() {}
  // The frame Convert was last given (colour and depth as delivered), read back for another
  // thread without the calling thread waiting or copying: `wait`, called on that thread,
  // returns once `color` and `depth` hold it; they stay valid until the next call. Only a
  // backend whose frame is in device memory offers it (the CUDA backend; others: nothing,
  // and the caller copies the frame itself).
  struct FrameReadback {
    const Rgb8* color = nullptr;
    const float* depth = nullptr;
    std::function<void()> wait;
  };
  virtual bool ReadBackFrame(FrameReadback*) { return false; }

  // Host copies for reports, views, tests and export.
  virtual volume::Volume::Rendering Render(const Pose& T_world_camera) = 0;
  // The whole model as a host volume (on CUDA: a download of every allocated brick).
  virtual const volume::Volume& DownloadVolume() = 0;
  // Replaces the model with a host volume of the same voxel size, truncation and encoding (a
  // project reopened); the last rendering and the reference are dropped.
  virtual void LoadVolume(const volume::Volume& model) = 0;
  // The model's surface (marching tetrahedra, mesh_impl.h), extracted where the model lives.
  // `progress(fraction)` returning false cancels: hdrf::Cancelled is thrown.
  virtual mesh::Mesh ExtractMesh(const std::function<bool(double)>& progress = {}) = 0;
  virtual FrameViews DownloadViews(const ViewSet& which) = 0;
  // The model's bricks changed since the last call (every brick on the first call and after
  // LoadVolume): their coordinates and voxels, for meshing them elsewhere.
  virtual volume::BrickSet ChangedBricks() = 0;
  virtual FrameImages DownloadStages() = 0;
};

std::unique_ptr<Backend> MakeCpuBackend(const BackendSetup& setup);
// Throws hdrf::Error where this build has no CUDA backend or no GPU is usable.
std::unique_ptr<Backend> MakeCudaBackend(const BackendSetup& setup);

}  // namespace hdrf::pipeline
