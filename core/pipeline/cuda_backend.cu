// The CUDA backend: owns the frame's images, the tracker's pyramids and the model in GPU
// memory, and calls each module's GPU side for the stages (radiometry, imaging,
// normalized_radiance, tracking, exposure, volume, mesh: the *_cuda.cu files and the shared
// drivers). It holds no algorithm. Per frame the host sends the colour and depth and reads
// back the Gauss-Newton systems (33 doubles per iteration), the exposure estimate and the
// count of new bricks; nothing else crosses the bus.
#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "common/cuda_check.h"
#include "common/device_buffer.h"
#include "common/error.h"
#include "exposure/exposure_gpu.h"
#include "imaging/imaging_driver.h"
#include "normalized_radiance/normalized_radiance_driver.h"
#include "pipeline/backend.h"
#include "pipeline/pipeline.h"
#include "radiometry/radiance_driver.h"
#include "tracking/tracking_gpu.h"
#include "volume/device_volume.h"

namespace hdrf::pipeline {

namespace {

struct LiveLevelD {
  PinholeCamera cam;
  DeviceImage<float> depth, intensity, gx, gy, weight;
  DeviceImage<Float3> vertex, normal;
  explicit LiveLevelD(const PinholeCamera& c)
      : cam(c), depth(c.width, c.height), intensity(c.width, c.height), gx(c.width, c.height),
        gy(c.width, c.height), weight(c.width, c.height), vertex(c.width, c.height), normal(c.width, c.height) {}
  tracking::LiveView view() const {
    return {cam, vertex.view(), normal.view(), intensity.view(), gx.view(), gy.view(), weight.view()};
  }
  tracking::LiveLevelViews views() {
    return {cam, depth.view(), intensity.view(), weight.view(), gx.view(), gy.view(), vertex.view(), normal.view()};
  }
};

struct RefLevelD {
  PinholeCamera cam;
  DeviceImage<Float3> vertex, normal;
  DeviceImage<float> intensity;
  explicit RefLevelD(const PinholeCamera& c)
      : cam(c), vertex(c.width, c.height), normal(c.width, c.height), intensity(c.width, c.height) {}
  tracking::ReferenceView view() const { return {cam, vertex.view(), normal.view(), intensity.view()}; }
  tracking::ReferenceLevelViews views() { return {cam, vertex.view(), normal.view(), intensity.view()}; }
};

struct RenderD {
  DeviceImage<Float3> vertex, normal, radiance;
  DeviceImage<float> nr, depth;
  RenderD(int w, int h) : vertex(w, h), normal(w, h), radiance(w, h), nr(w, h), depth(w, h) {}
  volume::RenderingViews views() {
    return {vertex.view(), normal.view(), radiance.view(), nr.view(), depth.view()};
  }
  volume::Volume::Rendering ToHost() const {
    return {vertex.ToHost(), normal.ToHost(), radiance.ToHost(), nr.ToHost(), depth.ToHost()};
  }
};

// Work images of normalized radiance on the down-sampled grid.
struct NrScratchD {
  DeviceImage<float> cells, mean_s, std_s;
  DeviceImage<double> cnt, s1, s2;
  NrScratchD(int w, int h, int f)
      : cells((w + f - 1) / f, (h + f - 1) / f), mean_s(cells.width(), cells.height()),
        std_s(cells.width(), cells.height()), cnt(cells.width() + 1, cells.height() + 1),
        s1(cells.width() + 1, cells.height() + 1), s2(cells.width() + 1, cells.height() + 1) {}
  nr::Scratch views() { return {cells.view(), mean_s.view(), std_s.view(), {cnt.view(), s1.view(), s2.view()}}; }
};

template <typename T>
void CopyD2D(DeviceImage<T>& dst, const DeviceImage<T>& src) {
  HDRF_CUDA_CHECK(cudaMemcpyAsync(dst.data(), src.data(), sizeof(T) * std::size_t(src.width()) * src.height(),
                                  cudaMemcpyDeviceToDevice, 0));
}

class CudaBackend final : public Backend {
 public:
  explicit CudaBackend(const BackendSetup& s)
      : o_(s.options), cam_(s.camera),
        color_(cam_.width, cam_.height), depth_raw_(cam_.width, cam_.height), depth_(cam_.width, cam_.height),
        conf_(cam_.width, cam_.height), maxconf_(cam_.width, cam_.height), lum_(cam_.width, cam_.height), conf_track_(cam_.width, cam_.height),
        nr_(cam_.width, cam_.height), lum_render_(cam_.width, cam_.height), radiance_(cam_.width, cam_.height),
        nr_scratch_(cam_.width, cam_.height, o_.nr.downsample), render_(cam_.width, cam_.height),
        exposure_(cam_.width, cam_.height, o_.exposure), volume_(o_.volume) {
    const imaging::BilateralTables bt =
        imaging::MakeBilateralTables(o_.depth.sigma_space_px, o_.depth.sigma_depth_m, o_.depth.radius);
    cuda::CopyHostToDevice(bilateral_.data(), &bt, sizeof(bt));
    inverse_.Upload(s.inverse, 768);
    pcf_.Upload(s.pcf, 768);
    PinholeCamera c = cam_;
    for (int l = 0; l < o_.tracker.levels; ++l) {
      live_.push_back(std::make_unique<LiveLevelD>(c));
      ref_.push_back(std::make_unique<RefLevelD>(c));
      c = c.Scaled(2);
    }
  }

  void Convert(const ColorImage& color, const DepthImage& depth_m) override {
    SettleModel();  // (its last frame's images are about to be overwritten)
    exposure_ready_ = false;
    // Through pinned staging memory, piece by piece (the CPU's threads copy the frame there
    // while the GPU fetches the pieces already copied at full bus speed): a copy from
    // ordinary memory went through the driver's own staging a piece at a time.
    const std::size_t cb = color.size() * sizeof(Rgb8), db = depth_m.size() * sizeof(float);
    if (cb > stage_.color_bytes || db > stage_.depth_bytes)
      throw Error("the frame is larger than the camera the GPU pipeline was set up for");
    HDRF_CUDA_CHECK(cudaEventSynchronize(stage_.copied));  // the last frame has left the staging memory
    const cuda::UploadPart parts[2] = {{color_.data(), stage_.color, color.data(), cb},
                                       {depth_raw_.data(), stage_.depth, depth_m.data(), db}};
    cuda::UploadThroughStaging(parts, 2);
    HDRF_CUDA_CHECK(cudaEventRecord(stage_.copied, 0));
    radiometry::ConvertFrameOnGpu(color_.view(), inverse_.data(), pcf_.data(), radiance_.view(), conf_.view(),
                                  maxconf_.view());
    if (o_.depth.bilateral) imaging::BilateralFilterOnGpu(depth_raw_.view(), bilateral_.data(), depth_.view());
    else CopyD2D(depth_, depth_raw_);
    // The ray cast's guide from this depth, made now beside the last frame's ray cast rather
    // than on the way to this frame's (Raycast with kDepth takes it).
    if (guide_next_.width() == 0)
      guide_next_ = DeviceImage<float>(volume::GuideTiles(cam_.width), volume::GuideTiles(cam_.height));
    volume::RaycastGuideOnGpu(depth_.view(), o_.volume.truncation_m(), guide_next_.view());
    guide_next_ready_ = true;
  }

  void Normalize() override {
    exposure_ready_ = false;
    LiveLevelD& L0 = *live_[0];
    nr::TrackingLuminanceOnGpu(color_.view(), radiance_.view(), conf_.view(), lum_.view(), conf_track_.view());
    nr::NormalizeOnGpu(lum_.view(), nr_scratch_.views(), o_.nr, nr_.view());
    if (o_.tracker.kind == tracking::TrackerKind::kIntensity) {
      imaging::RawIntensityOnGpu(color_.view(), L0.intensity.view(), L0.weight.view());
    } else {
      CopyD2D(L0.intensity, nr_);
      CopyD2D(L0.weight, conf_track_);
    }
  }

  void BuildLive() override {
    valid_from_run_ = false;
    CopyD2D(live_[0]->depth, depth_);
    for (std::size_t l = 0; l < live_.size(); ++l) {
      const tracking::LiveLevelViews finer = l > 0 ? live_[l - 1]->views() : tracking::LiveLevelViews{};
      tracking::BuildLiveLevelOnGpu(l > 0 ? &finer : nullptr, live_[l]->views(), o_.depth.max_normal_jump_m);
    }
  }

  tracking::GnSystem Accumulate(int level, const Pose& T_world_live, const tracking::TrackerOptions& t) override {
    return sums_.Accumulate(ref_[std::size_t(level)]->view(), reference_pose_, live_[std::size_t(level)]->view(),
                            T_world_live, t);
  }
  tracking::GaussNewtonRun RunTracker(const Pose& initial, const tracking::TrackerOptions& t,
                                      const tracking::MotionPrior* prior) override {
    std::vector<tracking::GpuNormalEquations::Level> levels;
    for (std::size_t l = 0; l < live_.size(); ++l) levels.push_back({ref_[l]->view(), live_[l]->view()});
    const bool with_exposure = std::exchange(exposure_next_, false) && has_render_;
    exposure_ready_ = false;
    if (with_exposure) WaitRaycast();  // (before the run's start: it waits for the default stream)
    sums_.QueueRun(levels, reference_pose_, initial, t, prior);
    if (with_exposure) exposure_.Queue(ExposureViews(), sums_.device_pose(), nullptr);  // the default stream, behind the run
    tracking::GaussNewtonRun run = sums_.FinishRun();
    valid_from_run_ = true;
    if (with_exposure) {
      exposure_estimate_ = exposure_.Result();
      exposure_pose_ = run.T_world_camera;
      exposure_ready_ = true;
    }
    return run;
  }
  void EstimateExposureWithNextRun() override { exposure_next_ = true; }
  // Counted inside the last tracker run where neither side has changed since.
  long LiveValid() override {
    return valid_from_run_ ? sums_.last_valid().live : sums_.CountLiveVertices(live_[0]->vertex.view());
  }
  long ReferenceValid() override {
    return valid_from_run_ ? sums_.last_valid().reference : sums_.CountReferenceVertices(ref_[0]->vertex.view());
  }

  exposure::ExposureEstimate EstimateExposure(const Pose& T) override {
    // Made with the tracker's run at this very pose, on the same inputs: that one.
    if (exposure_ready_ && T.matrix() == exposure_pose_.matrix()) return exposure_estimate_;
    WaitRaycast();
    return exposure_.Estimate(ExposureViews(), T);
  }

  void Integrate(const Pose& T, float ratio) override {
    WaitRaycast();  // (the model changes under it)
    volume::IntegrateArgs a = volume::Volume::MakeIntegrateArgs(o_.volume, cam_, T, ratio);
    a.depth = depth_.view();
    a.normals = live_[0]->normal.view();
    a.radiance = radiance_.view();
    a.nr = nr_.view();
    a.confidence = conf_.view();
    a.max_confidence = maxconf_.view();
    volume_.Integrate(a, T);
  }
  std::size_t AllocatedBricks() override { return SettleModel(), volume_.allocated_bricks(); }
  std::size_t LastVisibleBricks() override { return SettleModel(), volume_.last_visible_bricks(); }
  std::size_t VolumeBytes() override { return SettleModel(), volume_.bytes(); }
  bool VolumeFull() override { return SettleModel(), volume_.full(); }
  std::string VolumeFullReason() override { return SettleModel(), volume_.full_reason(); }
  std::array<Float3, 2> VolumeBounds() override { return SettleModel(), volume_.Bounds(); }
  StreamingStats Streaming() override {
    SettleModel();
    return {volume_.gpu_bricks(), volume_.host_bricks(), volume_.gpu_bytes(), volume_.swapped_out(), volume_.swapped_in()};
  }

  void Raycast(const Pose& T, RaycastStart start) override {
    exposure_ready_ = false;
    AfterRaycast();  // (its guide and rendering are rewritten; the model may still be settling)
    if (start == RaycastStart::kDepth) {
      if (guide_next_ready_) {  // (made from the same depth in Convert)
        std::swap(guide_, guide_next_);
        guide_next_ready_ = false;
      } else {
        if (guide_.width() == 0) guide_ = DeviceImage<float>(volume::GuideTiles(cam_.width), volume::GuideTiles(cam_.height));
        volume::RaycastGuideOnGpu(depth_.view(), o_.volume.truncation_m(), guide_.view());
      }
      guided_ = true;
    } else if (start == RaycastStart::kNear) {
      guided_ = false;
    }
    volume::RaycastArgs a{cam_, ToRigidTransform(T), o_.volume.raycast_near_m, o_.volume.raycast_far_m};
    if (guided_) a.start = guide_.view();
    // The box as the device keeps it: a frame's Integrate queued before may still be adding to it.
    a.box_bricks = volume_.device_box();
    a.box_brick_m = o_.volume.voxel_m * volume::kBrick;
    // On the ray cast's own stream, after everything queued so far (the model as fused, the
    // guide); the next frame's upload and first stages run beside it.
    HDRF_CUDA_CHECK(cudaEventRecord(side_.ready, 0));
    HDRF_CUDA_CHECK(cudaStreamWaitEvent(side_.stream, side_.ready, 0));
    volume_.Raycast(a, render_.views(), side_.stream);
    HDRF_CUDA_CHECK(cudaEventRecord(side_.done, side_.stream));
    volume_.QueueCounts();  // (a queued Integrate's counts, read back beside the ray cast)
    raycast_pending_ = true;
    render_in_ref_ = false;
    raycast_unsettled_ = !volume_.settled();
    raycast_start_ = start;
    render_pose_ = T;
    has_render_ = true;
    render_nr_ready_ = false;  // a model without NR: normalized once the clipping level is known
  }
  bool HasRender() const override { return has_render_; }
  Image<float> RaycastGuide() override { return guided_ ? guide_.ToHost() : Image<float>(); }
  void SetRaycastGuide(const Image<float>& guide) override {
    WaitRaycast();
    guided_ = !guide.empty();
    if (guided_) guide_ = DeviceImage<float>(guide);
  }

  void ReferenceFromRender(const Float3& clip) override {
    WaitRaycast();
    valid_from_run_ = false;
    // The ray cast's vertices and normals become the reference's finest level by exchanging
    // the images, not by copying them: they are the rendering's too (RenderVertex) until the
    // next ray cast, which writes into the pair the reference had.
    if (!render_in_ref_) ExchangeRenderAndReference();
    NormalizeRender(clip);
    CopyD2D(ref_[0]->intensity, render_.nr);
    BuildReferencePyramid();
    reference_pose_ = render_pose_;
    has_reference_ = true;
  }
  void ReferenceFromLive(const Pose& T) override {
    valid_from_run_ = false;
    if (render_in_ref_) ExchangeRenderAndReference();  // (the rendering keeps its images; the reference is written anew)
    const LiveLevelD& L0 = *live_[0];
    tracking::PlaceInWorldOnGpu(L0.vertex.view(), L0.normal.view(), ToRigidTransform(T), ref_[0]->vertex.view(),
                                ref_[0]->normal.view());
    CopyD2D(ref_[0]->intensity, L0.intensity);
    BuildReferencePyramid();
    reference_pose_ = T;
    has_reference_ = true;
  }
  bool HasReference() const override { return has_reference_; }
  Pose ReferencePose() const override { return reference_pose_; }
  void Synchronize() override { cuda::Synchronize(); }
  bool ReadBackFrame(FrameReadback* out) override {
    // Queued on the default stream, before the next frame's upload overwrites the frame.
    if (!readback_) readback_ = std::make_unique<PinnedFrame>(cam_);
    HDRF_CUDA_CHECK(cudaMemcpyAsync(readback_->color, color_.data(), readback_->color_bytes, cudaMemcpyDeviceToHost, 0));
    HDRF_CUDA_CHECK(cudaMemcpyAsync(readback_->depth, depth_raw_.data(), readback_->depth_bytes, cudaMemcpyDeviceToHost, 0));
    HDRF_CUDA_CHECK(cudaEventRecord(readback_->copied, 0));
    const cudaEvent_t there = readback_->copied;
    out->color = static_cast<const Rgb8*>(readback_->color);
    out->depth = static_cast<const float*>(readback_->depth);
    out->wait = [there] { HDRF_CUDA_CHECK(cudaEventSynchronize(there)); };
    return true;
  }

  volume::Volume::Rendering Render(const Pose& T) override {
    SettleModel();
    RenderD tmp(cam_.width, cam_.height);
    RaycastInto(tmp, T);
    return tmp.ToHost();
  }
  const volume::Volume& DownloadVolume() override { return SettleModel(), volume_.Download(); }
  void LoadVolume(const volume::Volume& model) override {
    exposure_ready_ = false;
    WaitRaycast();
    volume_.Upload(model);
    has_render_ = false;
    has_reference_ = false;
    valid_from_run_ = false;
  }
  mesh::Mesh ExtractMesh(const std::function<bool(double)>& progress) override {
    SettleModel();
    // On the GPU the extraction takes milliseconds: progress at its start and end only.
    if (progress && !progress(0.0)) throw Cancelled();
    // Part of the model in host memory (a GPU budget): the whole model is meshed on the CPU.
    mesh::Mesh m = volume_.host_bricks() > 0 ? mesh::ExtractMesh(volume_.Download()) : mesh::ExtractMeshOnGpu(volume_);
    if (progress && !progress(1.0)) throw Cancelled();
    return m;
  }

  FrameViews DownloadViews(const ViewSet& which) override {
    WaitRaycast();
    FrameViews v;
    if (which.radiance) v.radiance = radiance_.ToHost();
    if (which.confidence) v.confidence = conf_.ToHost(), v.max_confidence = maxconf_.ToHost();
    if (which.nr) v.nr = nr_.ToHost();
    if (which.depth) v.depth = depth_.ToHost();
    if (which.render) {
      if (!render_nr_ready_) NormalizeRender(kNoClip);
      v.render = RenderToHost();
    }
    return v;
  }
  volume::BrickSet ChangedBricks() override { return SettleModel(), volume_.CopyChanged(); }
  FrameImages DownloadStages() override {
    WaitRaycast();
    if (!render_nr_ready_) NormalizeRender(kNoClip);
    FrameImages f;
    f.radiance = radiance_.ToHost();
    f.confidence = conf_.ToHost();
    f.max_confidence = maxconf_.ToHost();
    f.nr = nr_.ToHost();
    f.depth = depth_.ToHost();
    for (const auto& L : live_) {
      f.live_vertex.push_back(L->vertex.ToHost());
      f.live_normal.push_back(L->normal.ToHost());
      f.live_intensity.push_back(L->intensity.ToHost());
      f.live_weight.push_back(L->weight.ToHost());
      f.live_grad_x.push_back(L->gx.ToHost());
    }
    for (const auto& L : ref_) {
      f.ref_vertex.push_back(L->vertex.ToHost());
      f.ref_normal.push_back(L->normal.ToHost());
      f.ref_intensity.push_back(L->intensity.ToHost());
    }
    f.render = RenderToHost();
    return f;
  }

 private:
  // The exposure estimate's inputs: the last ray cast and the live frame (its transform comes
  // from the pose the estimate is made at).
  exposure::ExposureArgs ExposureViews() const {
    return {RenderVertex().view(), render_.radiance.view(), radiance_.view(), conf_track_.view(), cam_, {}};
  }
  // The last ray cast's vertices and normals: in render_, or in the reference's finest level
  // since ReferenceFromRender (render_in_ref_).
  const DeviceImage<Float3>& RenderVertex() const { return render_in_ref_ ? ref_[0]->vertex : render_.vertex; }
  const DeviceImage<Float3>& RenderNormal() const { return render_in_ref_ ? ref_[0]->normal : render_.normal; }
  void ExchangeRenderAndReference() {
    std::swap(ref_[0]->vertex, render_.vertex);
    std::swap(ref_[0]->normal, render_.normal);
    render_in_ref_ = !render_in_ref_;
  }
  volume::Volume::Rendering RenderToHost() const {
    return {RenderVertex().ToHost(), RenderNormal().ToHost(), render_.radiance.ToHost(), render_.nr.ToHost(),
            render_.depth.ToHost()};
  }
  // The model's host side after a queued Integrate (DeviceVolume::Settle). Where it fused
  // new bricks only now, a ray cast queued after the Integrate saw the model without them:
  // it is cast again (the work Settle queues waits for it first).
  void SettleModel() {
    if (volume_.settled()) return;
    if (volume_.Settle(raycast_pending_ ? side_.done : nullptr) && raycast_unsettled_) Raycast(render_pose_, raycast_start_);
    raycast_unsettled_ = false;
  }
  // The default stream's next work waits (on the GPU, not the host) for the last ray cast,
  // and the model is settled: for whatever reads the rendering or changes the model.
  void WaitRaycast() {
    SettleModel();
    AfterRaycast();
  }
  // The same without settling the model (the next ray cast, queued behind the model's work).
  void AfterRaycast() {
    if (!raycast_pending_) return;
    HDRF_CUDA_CHECK(cudaStreamWaitEvent(0, side_.done, 0));
    raycast_pending_ = false;
  }
  // A model without NR: the NR of a ray cast's radiance, with the radiance at or above `clip`
  // left out (infinite: none).
  void NormalizeRadiance(const DeviceImage<Float3>& radiance, const Float3& clip, DeviceImage<float>& out) {
    nr::ClippedLuminanceOnGpu(radiance.view(), clip, lum_render_.view());
    nr::NormalizeOnGpu(lum_render_.view(), nr_scratch_.views(), o_.nr, out.view());
  }
  void RaycastInto(RenderD& out, const Pose& T) {
    volume_.Raycast({cam_, ToRigidTransform(T), o_.volume.raycast_near_m, o_.volume.raycast_far_m}, out.views());
    if (!volume::EncodingStoresNr(o_.volume.encoding)) NormalizeRadiance(out.radiance, kNoClip, out.nr);
  }
  // The frame's ray cast's NR (ReferenceFromRender), once per ray cast and clipping level.
  void NormalizeRender(const Float3& clip) {
    if (!has_render_ || volume::EncodingStoresNr(o_.volume.encoding)) return;
    if (render_nr_ready_ && SameClip(clip, render_nr_clip_)) return;
    NormalizeRadiance(render_.radiance, clip, render_.nr);
    render_nr_ready_ = true;
    render_nr_clip_ = clip;
  }
  void BuildReferencePyramid() {
    for (std::size_t l = 1; l < ref_.size(); ++l)
      tracking::BuildReferenceLevelOnGpu(ref_[l - 1]->views(), ref_[l]->views());
  }

  // Pinned host memory for one frame's colour and depth, and an event that marks the last
  // copies queued to or from it (recorded once at the start: nothing to wait for).
  struct PinnedFrame {
    void* color = nullptr;
    void* depth = nullptr;
    std::size_t color_bytes = 0, depth_bytes = 0;
    cudaEvent_t copied = nullptr;
    explicit PinnedFrame(const PinholeCamera& c)
        : color_bytes(std::size_t(c.width) * std::size_t(c.height) * sizeof(Rgb8)),
          depth_bytes(std::size_t(c.width) * std::size_t(c.height) * sizeof(float)) {
      HDRF_CUDA_CHECK(cudaMallocHost(&color, color_bytes));
      HDRF_CUDA_CHECK(cudaMallocHost(&depth, depth_bytes));
      HDRF_CUDA_CHECK(cudaEventCreateWithFlags(&copied, cudaEventDisableTiming));
      HDRF_CUDA_CHECK(cudaEventRecord(copied, 0));
    }
    ~PinnedFrame() {
      cudaEventDestroy(copied);
      cudaFreeHost(depth);
      cudaFreeHost(color);
    }
    PinnedFrame(const PinnedFrame&) = delete;
    PinnedFrame& operator=(const PinnedFrame&) = delete;
  };

  const PipelineOptions o_;
  PinholeCamera cam_;
  PinnedFrame stage_{cam_};              // a frame goes to the GPU through it
  std::unique_ptr<PinnedFrame> readback_;  // a frame read back into it (ReadBackFrame), made at the first
  DeviceBuffer<imaging::BilateralTables> bilateral_{1};  // (device memory)
  DeviceBuffer<float> inverse_, pcf_;
  DeviceImage<Rgb8> color_;
  DeviceImage<float> depth_raw_, depth_, conf_, maxconf_, lum_, nr_, lum_render_;
  DeviceImage<float> guide_;  // the ray cast's start guide (RaycastGuide), used while guided_
  DeviceImage<float> guide_next_;  // the guide from the last converted frame's depth, while guide_next_ready_
  bool guide_next_ready_ = false;
  bool guided_ = false;
  DeviceImage<float> conf_track_;  // the confidence, 0 where a channel is clipped (tracking, exposure)
  bool render_nr_ready_ = false;  // render_.nr holds the ray cast's NR for render_nr_clip_
  Float3 render_nr_clip_{};
  DeviceImage<Float3> radiance_;
  NrScratchD nr_scratch_;
  std::vector<std::unique_ptr<LiveLevelD>> live_;
  std::vector<std::unique_ptr<RefLevelD>> ref_;
  RenderD render_;
  Pose render_pose_ = Pose::Identity(), reference_pose_ = Pose::Identity();
  bool has_render_ = false, has_reference_ = false;
  bool render_in_ref_ = false;  // the rendering's vertices and normals are ref_[0]'s (ReferenceFromRender)
  bool valid_from_run_ = false;  // LiveValid / ReferenceValid: the last tracker run's counts hold
  tracking::GpuNormalEquations sums_;
  exposure::GpuExposureEstimator exposure_;
  // EstimateExposureWithNextRun: the next run makes the estimate too; the one it made, at
  // exposure_pose_, while exposure_ready_ (until the inputs change: a frame, a ray cast).
  bool exposure_next_ = false, exposure_ready_ = false;
  exposure::ExposureEstimate exposure_estimate_;
  Pose exposure_pose_ = Pose::Identity();
  volume::DeviceVolume volume_;
  // The ray cast's stream (not synchronised with the default one: the frame's ray cast runs
  // beside the next frame's first stages), the point it starts after, the point it ends.
  // Whatever reads the rendering or changes the model waits for it first (WaitRaycast).
  struct SideStream {
    cudaStream_t stream = nullptr;
    cudaEvent_t ready = nullptr, done = nullptr;
    SideStream() {
      HDRF_CUDA_CHECK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
      HDRF_CUDA_CHECK(cudaEventCreateWithFlags(&ready, cudaEventDisableTiming));
      HDRF_CUDA_CHECK(cudaEventCreateWithFlags(&done, cudaEventDisableTiming));
    }
    ~SideStream() {
      cudaStreamSynchronize(stream);
      cudaEventDestroy(done);
      cudaEventDestroy(ready);
      cudaStreamDestroy(stream);
    }
    SideStream(const SideStream&) = delete;
    SideStream& operator=(const SideStream&) = delete;
  };
  SideStream side_;  // (last: gone before the buffers it may still write)
  bool raycast_pending_ = false;
  bool raycast_unsettled_ = false;  // the last ray cast was queued before the model was settled
  RaycastStart raycast_start_ = RaycastStart::kNear;  // ... from there
};

}  // namespace

std::unique_ptr<Backend> MakeCudaBackend(const BackendSetup& setup) {
  std::string why;
  if (!CudaAvailable(&why)) throw Error("the CUDA backend cannot run: " + why);
  return std::make_unique<CudaBackend>(setup);
}

}  // namespace hdrf::pipeline
