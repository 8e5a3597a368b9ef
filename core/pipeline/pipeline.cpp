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

// The reference backend: host images, OpenMP loops.
class CpuBackend final : public Backend {
 public:
  explicit CpuBackend(const BackendSetup& s)
      : o_(*s.options), cam_(s.camera), volume_(o_.volume),
        bilateral_(imaging::MakeBilateralTables(2.0f, 0.03f, 3)) {
    inverse_.assign(s.inverse, s.inverse + 768);
    pcf_.assign(s.pcf, s.pcf + 768);
  }

  void Convert(const ColorImage& color, const DepthImage& depth_m) override {
    const int w = color.width(), h = color.height();
    radiance_ = RadianceImage(w, h);
    conf_ = Image<float>(w, h);
    maxconf_ = Image<float>(w, h);
#pragma omp parallel for schedule(static)
    for (long i = 0; i < long(color.size()); ++i)
      imaging::ConvertPixel(color[std::size_t(i)], inverse_.data(), pcf_.data(), &radiance_[std::size_t(i)],
                            &conf_[std::size_t(i)], &maxconf_[std::size_t(i)]);
    if (o_.bilateral) {
      depth_ = DepthImage(w, h);
#pragma omp parallel for schedule(static)
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) depth_(x, y) = imaging::BilateralPixel(View(depth_m), bilateral_, x, y);
    } else {
      depth_ = depth_m.Clone();
    }
  }

  void Normalize(const ColorImage& color) override {
    nr_ = imaging::NormalizedRadiance(imaging::Luminance(radiance_), o_.nr);
    if (o_.tracker.kind == tracking::TrackerKind::kIntensity) {
      track_image_ = Image<float>(color.width(), color.height());
      for (std::size_t i = 0; i < color.size(); ++i) track_image_[i] = imaging::RawIntensityPixel(color[i]);
      track_weight_ = Image<float>(color.width(), color.height(), 1.f);
    } else {
      track_image_ = nr_.Clone();
      track_weight_ = conf_.Clone();
    }
  }

  void BuildLive() override {
    live_ = tracking::MakeLive(depth_, track_image_, track_weight_, cam_, o_.tracker.levels);
  }

  tracking::GnSystem Accumulate(int level, const Pose& T_world_ref, const Pose& T_world_live) override {
    return tracking::AccumulateCpu(reference_.levels[std::size_t(level)].view(), T_world_ref,
                                   live_.levels[std::size_t(level)].view(), T_world_live, o_.tracker);
  }

  long ReferenceValid() override {
    long n = 0;
    const auto& v = reference_.levels[0].vertex_w;
    for (std::size_t i = 0; i < v.size(); ++i) n += v[i].z != 0.f || v[i].x != 0.f || v[i].y != 0.f;
    return n;
  }
  long LiveValid() override {
    long n = 0;
    const auto& v = live_.levels[0].vertex_c;
    for (std::size_t i = 0; i < v.size(); ++i) n += v[i].z > 0;
    return n;
  }

  tracking::ExposureEstimate EstimateExposure(const Pose& T) override {
    return tracking::EstimateExposureRatio(render_.vertex, render_.radiance, radiance_, conf_, cam_, T);
  }

  void Integrate(const Pose& T, float ratio) override {
    // The finest tracking level already holds this frame's normals (same filtered depth).
    volume::Volume::FrameInput fi{&depth_, &live_.levels[0].normal_c, &radiance_, &nr_, &conf_, &maxconf_,
                                  cam_, T, ratio};
    last_visible_ = volume_.Integrate(fi).visible_bricks;
  }
  std::size_t LastVisibleBricks() override { return last_visible_; }
  std::size_t AllocatedBricks() override { return volume_.allocated_bricks(); }
  std::size_t VolumeBytes() override { return volume_.bytes(); }

  void Raycast(const Pose& T) override { render_ = Render(T); }

  void ReferenceFromRender() override {
    reference_ = tracking::MakeReference(render_.vertex, render_.normal, render_.nr, cam_, o_.tracker.levels,
                                         Pose::Identity());
  }
  void ReferenceFromLive(const Pose& T_pose) override {
    // Frame to frame: the live frame itself, in world coordinates at its pose.
    const RigidTransform T = ToRigidTransform(T_pose);
    const auto& L0 = live_.levels[0];
    Image<Float3> vw(cam_.width, cam_.height), nw(cam_.width, cam_.height);
    for (std::size_t i = 0; i < vw.size(); ++i)
      if (L0.vertex_c[i].z > 0 && Length(L0.normal_c[i]) > 0) {
        vw[i] = T.Apply(L0.vertex_c[i]);
        nw[i] = T.Rotate(L0.normal_c[i]);
      }
    reference_ = tracking::MakeReference(vw, nw, track_image_, cam_, o_.tracker.levels, T_pose);
  }

  volume::Volume::Rendering Render(const Pose& T) override {
    volume::Volume::Rendering r = volume_.Raycast(cam_, T);
    // A model without NR: the tracker normalizes the ray-cast radiance instead.
    if (!volume::EncodingStoresNr(o_.volume.encoding))
      r.nr = imaging::NormalizedRadiance(imaging::Luminance(r.radiance), o_.nr);
    return r;
  }
  const volume::Volume& HostVolume() override { return volume_; }
  mesh::Mesh ExtractMesh(const std::function<bool(double)>& progress) override {
    if (!progress) return mesh::ExtractMesh(volume_);
    return mesh::ExtractMesh(
        volume_,
        [](double f, void* user) {
          if (!(*static_cast<const std::function<bool(double)>*>(user))(f)) throw Cancelled();
        },
        const_cast<std::function<bool(double)>*>(&progress));
  }
  FrameImages Download() override {
    FrameImages f;
    f.radiance = radiance_.Clone();
    f.confidence = conf_.Clone();
    f.max_confidence = maxconf_.Clone();
    f.nr = nr_.Clone();
    f.depth = depth_.Clone();
    for (const auto& L : live_.levels) {
      f.live_vertex.push_back(L.vertex_c.Clone());
      f.live_normal.push_back(L.normal_c.Clone());
      f.live_intensity.push_back(L.intensity.Clone());
      f.live_weight.push_back(L.weight.Clone());
      f.live_grad_x.push_back(L.grad_x.Clone());
    }
    for (const auto& L : reference_.levels) {
      f.ref_vertex.push_back(L.vertex_w.Clone());
      f.ref_normal.push_back(L.normal_w.Clone());
      f.ref_intensity.push_back(L.intensity.Clone());
    }
    f.render = {render_.vertex.Clone(), render_.normal.Clone(), render_.radiance.Clone(), render_.nr.Clone(),
                render_.depth.Clone()};
    return f;
  }

 private:
  const PipelineOptions& o_;
  PinholeCamera cam_;
  std::vector<float> inverse_, pcf_;
  volume::Volume volume_;
  imaging::BilateralTables bilateral_;
  RadianceImage radiance_;
  Image<float> conf_, maxconf_, nr_, track_image_, track_weight_;
  DepthImage depth_;
  tracking::Live live_;
  tracking::Reference reference_;
  volume::Volume::Rendering render_;
  std::size_t last_visible_ = 0;
};
}  // namespace

std::unique_ptr<Backend> MakeCpuBackend(const BackendSetup& setup) {
  return std::make_unique<CpuBackend>(setup);
}

#if !HDRF_HAS_CUDA
std::unique_ptr<Backend> MakeCudaBackend(const BackendSetup&) { ThrowNoCudaBackend(); }
#endif

void PipelineOptions::Check() const {
  volume.Check();
  tracker.Check();
  if (pcf < 0 || pcf > 3) throw SettingError("--pcf", "must be 0, 1, 2 or 3 (p0..p3)");
  if (nr.patch < 3 || nr.patch % 2 == 0) throw SettingError("nr.patch", "must be odd and >= 3");
  if (nr.downsample < 1 || nr.downsample > 8) throw SettingError("nr.downsample", "must be 1..8");
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
  const BackendSetup setup{&o_, cam_, inverse.data(), p.data()};
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

volume::Volume::Rendering Pipeline::Render(const Pose& T) const { return backend_->Render(T); }
const volume::Volume& Pipeline::volume() const { return backend_->HostVolume(); }
mesh::Mesh Pipeline::ExtractMesh(const std::function<bool(double)>& progress) const {
  return backend_->ExtractMesh(progress);
}
std::size_t Pipeline::volume_bytes() const { return backend_->VolumeBytes(); }
Backend& Pipeline::backend() const { return *backend_; }

FrameReport Pipeline::Process(const FrameInput& in) {
  if (in.color.width() != cam_.width || in.color.height() != cam_.height ||
      in.depth_m.width() != cam_.width || in.depth_m.height() != cam_.height)
    throw Error("frame " + std::to_string(index_) + ": colour or depth size differs from the camera (" +
                std::to_string(cam_.width) + "x" + std::to_string(cam_.height) + ")");
  FrameReport rep;
  rep.index = index_;
  rep.timestamp = in.timestamp;
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
  b.Normalize(in.color);
  const bool baseline = o_.tracker.kind == tracking::TrackerKind::kIntensity;
  const auto t2 = now();
  // 3. Track.
  b.BuildLive();
  if (index_ == 0 || !have_reference_) {
    previous_pose_ = pose_;
    rep.tracking.T_world_camera = pose_;
    rep.tracking.inlier_share = 1;
  } else {
    // Start from a constant-velocity prediction (the last inter-frame motion, repeated). The
    // inlier share counts matches against what both sides can offer: where the model covers
    // only part of the view (an area not scanned yet, or beyond the volume), matching all of
    // that part is a success, not a loss.
    const Pose predicted = se3::Orthonormalized(pose_ * (previous_pose_.inverse() * pose_));
    const Pose T_ref = reference_pose_;
    rep.tracking = tracking::Track([&](int l, const Pose& T) { return b.Accumulate(l, T_ref, T); },
                                   o_.tracker.levels, std::min(b.LiveValid(), b.ReferenceValid()), predicted,
                                   o_.tracker);
    if (!rep.tracking.lost) {
      previous_pose_ = pose_;
      pose_ = rep.tracking.T_world_camera;
    }
  }
  rep.T_world_camera = pose_;
  const auto t3 = now();
  // 4. Exposure compensation against the model as seen from the last pose.
  double t_ratio = 1;
  if (index_ > 0 && have_render_ && !rep.tracking.lost) {
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
  const auto t5 = now();
  // 6. Ray cast the model from the new pose: the next frame's reference.
  if (rep.fused || !have_render_) {
    b.Raycast(pose_);
    have_render_ = true;
  }
  if (o_.tracker.frame_to_model && !baseline) {
    b.ReferenceFromRender();
    reference_pose_ = pose_;
    have_reference_ = true;
  } else if (!rep.tracking.lost || !have_reference_) {
    b.ReferenceFromLive(pose_);
    reference_pose_ = pose_;
    have_reference_ = true;
  }
  const auto t6 = now();
  rep.ms = {Ms(t0, t1), Ms(t1, t2), Ms(t2, t3), Ms(t3, t4), Ms(t4, t5), Ms(t5, t6)};
  ++index_;
  return rep;
}

}  // namespace hdrf::pipeline
