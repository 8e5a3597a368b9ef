// The engine's per-frame stages behind one interface, so that Pipeline::Process runs the
// same sequence (and the same Gauss-Newton loop) on the CPU reference backend and on the
// CUDA backend. A backend holds the frame's images and the model wherever it computes.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/camera.h"
#include "common/image.h"
#include "common/se3.h"
#include "imaging/imaging.h"
#include "mesh/mesh.h"
#include "tracking/tracking.h"
#include "volume/volume.h"

namespace hdrf::pipeline {

struct PipelineOptions;

struct BackendSetup {
  const PipelineOptions* options;
  PinholeCamera camera;
  const float* inverse;  // 3 x 256 inverse response, channel-major
  const float* pcf;      // 3 x 256 PCF of the chosen variant
};

// Host copies of a frame's images and of the last ray cast: what the studio's views show
// and what the backend parity tests compare.
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

class Backend {
 public:
  virtual ~Backend() = default;
  // 1. Radiance and confidence of the colour; filtered depth.
  virtual void Convert(const ColorImage& color, const DepthImage& depth_m) = 0;
  // 2. Normalized radiance, and the image and weight the tracker uses (raw intensity and
  // weight 1 for the brightness-constancy baseline).
  virtual void Normalize(const ColorImage& color) = 0;
  // 3. Live pyramid; the tracker's sums against the current reference; live pixels with depth.
  virtual void BuildLive() = 0;
  virtual tracking::GnSystem Accumulate(int level, const Pose& T_world_ref, const Pose& T_world_live) = 0;
  virtual long LiveValid() = 0;
  // Reference pixels with a vertex at the finest level (what the live frame can match).
  virtual long ReferenceValid() = 0;
  // 4. Exposure ratio of the live frame against the last ray cast.
  virtual tracking::ExposureEstimate EstimateExposure(const Pose& T_world_live) = 0;
  // 5. Fuses the live frame at a pose, radiance scaled by `ratio`; allocated bricks after.
  virtual void Integrate(const Pose& T_world_camera, float ratio) = 0;
  virtual std::size_t AllocatedBricks() = 0;
  virtual std::size_t LastVisibleBricks() = 0;  // bricks updated by the last Integrate
  virtual std::size_t VolumeBytes() = 0;
  // 6. Ray casts the model (kept as the last rendering), and makes the tracking reference
  // from it or from the live frame at a pose.
  virtual void Raycast(const Pose& T_world_camera) = 0;
  virtual void ReferenceFromRender() = 0;
  virtual void ReferenceFromLive(const Pose& T_world_camera) = 0;
  // Waits for queued work (timing); a no-op on the CPU.
  virtual void Synchronize() {}

  // Host copies for reports, tests and export.
  virtual volume::Volume::Rendering Render(const Pose& T_world_camera) = 0;
  virtual const volume::Volume& HostVolume() = 0;
  // The model's surface (marching tetrahedra, mesh_impl.h), extracted where the model lives.
  // `progress(fraction)` returning false cancels: hdrf::Cancelled is thrown.
  virtual mesh::Mesh ExtractMesh(const std::function<bool(double)>& progress = {}) = 0;
  virtual FrameImages Download() = 0;
};

std::unique_ptr<Backend> MakeCpuBackend(const BackendSetup& setup);
// Throws hdrf::Error where this build has no CUDA backend or no GPU is usable.
std::unique_ptr<Backend> MakeCudaBackend(const BackendSetup& setup);

}  // namespace hdrf::pipeline
