// The reference backend: host images and OpenMP loops over the modules' per-element
// functions. It owns the frame's buffers and the model and calls the modules; the
// algorithms live in the modules (imaging, tracking, volume, mesh).
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "common/error.h"
#include "imaging/imaging_driver.h"
#include "normalized_radiance/normalized_radiance_driver.h"
#include "pipeline/backend.h"
#include "radiometry/radiance_driver.h"
#include "tracking/pyramid_driver.h"
#include "volume/raycast_driver.h"
#include "pipeline/pipeline.h"

namespace hdrf::pipeline {

namespace {

// The reference backend: host images, OpenMP loops.
class CpuBackend final : public Backend {
 public:
  explicit CpuBackend(const BackendSetup& s)
      : o_(s.options), cam_(s.camera), volume_(o_.volume),
        bilateral_(imaging::MakeBilateralTables(o_.depth.sigma_space_px, o_.depth.sigma_depth_m, o_.depth.radius)) {
    inverse_.assign(s.inverse, s.inverse + 768);
    pcf_.assign(s.pcf, s.pcf + 768);
  }

  void Convert(const ColorImage& color, const DepthImage& depth_m) override {
    const int w = color.width(), h = color.height();
    color_ = color.Clone();  // stage 2 looks at it again (clipped pixels; the intensity tracker)
    radiance_ = RadianceImage(w, h);
    conf_ = Image<float>(w, h);
    maxconf_ = Image<float>(w, h);
    radiometry::ConvertFrameViews(par::Host{}, View(color), inverse_.data(), pcf_.data(), View(radiance_),
                                  View(conf_), View(maxconf_));
    if (o_.depth.bilateral) {
      depth_ = DepthImage(w, h);
      imaging::BilateralFilter(par::Host{}, View(depth_m), bilateral_, View(depth_));
    } else {
      depth_ = depth_m.Clone();
    }
  }

  void Normalize() override {
    Image<float> lum(color_.width(), color_.height());
    track_conf_ = Image<float>(color_.width(), color_.height());
    nr::TrackingLuminanceOf(par::Host{}, View(color_), View(radiance_), View(conf_), View(lum), View(track_conf_));
    nr_ = nr::NormalizedRadiance(lum, o_.nr);
    if (o_.tracker.kind == tracking::TrackerKind::kIntensity) {
      track_image_ = Image<float>(color_.width(), color_.height());
      track_weight_ = Image<float>(color_.width(), color_.height());
      imaging::RawIntensity(par::Host{}, View(color_), View(track_image_), View(track_weight_));
    } else {
      track_image_ = nr_.Clone();
      track_weight_ = track_conf_.Clone();
    }
  }

  void BuildLive() override {
    live_ = tracking::MakeLive(depth_, track_image_, track_weight_, cam_, o_.tracker.levels,
                               o_.depth.max_normal_jump_m);
  }

  tracking::GnSystem Accumulate(int level, const Pose& T_world_live, const tracking::TrackerOptions& t) override {
    return tracking::AccumulateCpu(reference_.levels[std::size_t(level)].view(), reference_.T_world_camera,
                                   live_.levels[std::size_t(level)].view(), T_world_live, t);
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

  exposure::ExposureEstimate EstimateExposure(const Pose& T) override {
    // Clipped pixels' radiance is only a bound: the ratio comes from the unclipped ones.
    return exposure::EstimateExposureRatio(render_.vertex, render_.radiance, radiance_, track_conf_, cam_, T,
                                           o_.exposure);
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
  bool VolumeFull() override { return volume_.full(); }
  std::string VolumeFullReason() override { return volume_.full_reason(); }
  std::array<Float3, 2> VolumeBounds() override { return volume_.Bounds(); }

  void Raycast(const Pose& T, RaycastStart start) override {
    if (start == RaycastStart::kDepth) {
      guide_ = Image<float>(volume::GuideTiles(cam_.width), volume::GuideTiles(cam_.height));
      volume::RaycastGuide(par::Host{}, View(depth_), o_.volume.truncation_m(), View(guide_));
    } else if (start == RaycastStart::kNear) {
      guide_ = Image<float>();
    }
    render_ = volume_.Raycast(cam_, T, &guide_);
    render_pose_ = T;
    has_render_ = true;
    render_nr_ready_ = false;  // a model without NR: normalized once the clipping level is known
  }
  bool HasRender() const override { return has_render_; }
  Image<float> RaycastGuide() override { return guide_.Clone(); }
  void SetRaycastGuide(const Image<float>& guide) override { guide_ = guide.Clone(); }

  void ReferenceFromRender(const Float3& clip) override {
    // The ray cast's vertices and normals are in world coordinates already; the reference
    // carries the pose they were cast from.
    NormalizeRender(clip);
    reference_ =
        tracking::MakeReference(render_.vertex, render_.normal, render_.nr, cam_, o_.tracker.levels, render_pose_);
  }
  bool HasReference() const override { return !reference_.levels.empty(); }
  Pose ReferencePose() const override { return reference_.T_world_camera; }
  void ReferenceFromLive(const Pose& T_pose) override {
    // Frame to frame: the live frame itself, in world coordinates at its pose.
    const auto& L0 = live_.levels[0];
    Image<Float3> vw(cam_.width, cam_.height), nw(cam_.width, cam_.height);
    tracking::PlaceInWorld(par::Host{}, View(L0.vertex_c), View(L0.normal_c), ToRigidTransform(T_pose), View(vw),
                           View(nw));
    reference_ = tracking::MakeReference(vw, nw, track_image_, cam_, o_.tracker.levels, T_pose);
  }

  volume::Volume::Rendering Render(const Pose& T) override {
    volume::Volume::Rendering r = volume_.Raycast(cam_, T);
    // A model without NR: the tracker normalizes the ray-cast radiance instead.
    if (!volume::EncodingStoresNr(o_.volume.encoding))
      r.nr = nr::NormalizedRadiance(nr::Luminance(r.radiance), o_.nr);
    return r;
  }
  const volume::Volume& DownloadVolume() override { return volume_; }
  void LoadVolume(const volume::Volume& model) override {
    volume_.Assign(model.pool(), model.bricks(), model.full_reason());
    has_render_ = false;
    reference_ = {};
  }
  mesh::Mesh ExtractMesh(const std::function<bool(double)>& progress) override {
    if (!progress) return mesh::ExtractMesh(volume_);
    return mesh::ExtractMesh(
        volume_,
        [](double f, void* user) {
          if (!(*static_cast<const std::function<bool(double)>*>(user))(f)) throw Cancelled();
        },
        const_cast<std::function<bool(double)>*>(&progress));
  }
  FrameViews DownloadViews(const ViewSet& which) override {
    FrameViews v;
    if (which.radiance) v.radiance = radiance_.Clone();
    if (which.confidence) v.confidence = conf_.Clone(), v.max_confidence = maxconf_.Clone();
    if (which.nr) v.nr = nr_.Clone();
    if (which.depth) v.depth = depth_.Clone();
    if (which.render) {
      if (!render_nr_ready_) NormalizeRender(kNoClip);
      v.render = {render_.vertex.Clone(), render_.normal.Clone(), render_.radiance.Clone(), render_.nr.Clone(),
                  render_.depth.Clone()};
    }
    return v;
  }
  volume::BrickSet ChangedBricks() override {
    volume::BrickSet b = volume_.CopyChanged(changes_seen_);
    changes_seen_ = volume_.change_clock();
    return b;
  }
  FrameImages DownloadStages() override {
    if (!render_nr_ready_) NormalizeRender(kNoClip);
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
  // A model without NR: the ray cast's NR from its radiance, with the radiance at or above
  // `clip` left out (ReferenceFromRender), once per ray cast and clipping level.
  void NormalizeRender(const Float3& clip) {
    if (!has_render_ || volume::EncodingStoresNr(o_.volume.encoding)) return;
    if (render_nr_ready_ && SameClip(clip, render_nr_clip_)) return;
    Image<float> lum(cam_.width, cam_.height);
    nr::ClippedLuminanceOf(par::Host{}, View(render_.radiance), clip, View(lum));
    render_.nr = nr::NormalizedRadiance(lum, o_.nr);
    render_nr_ready_ = true;
    render_nr_clip_ = clip;
  }

  const PipelineOptions o_;
  PinholeCamera cam_;
  ColorImage color_;  // the frame's colour (clipped pixels; the intensity tracker)
  std::vector<float> inverse_, pcf_;
  volume::Volume volume_;
  imaging::BilateralTables bilateral_;
  RadianceImage radiance_;
  Image<float> conf_, maxconf_, nr_, track_image_, track_weight_;
  Image<float> track_conf_;  // the confidence, 0 where a channel is clipped (tracking, exposure)
  bool render_nr_ready_ = false;  // render_.nr holds the ray cast's NR for render_nr_clip_
  Float3 render_nr_clip_{};
  DepthImage depth_;
  tracking::Live live_;
  tracking::Reference reference_;
  volume::Volume::Rendering render_;
  Pose render_pose_ = Pose::Identity();
  bool has_render_ = false;
  std::size_t last_visible_ = 0;
  std::uint32_t changes_seen_ = 0;  // the volume's change clock at the last ChangedBricks
  Image<float> guide_;              // the last ray cast's start guide (empty: from near)
};

}  // namespace

std::unique_ptr<Backend> MakeCpuBackend(const BackendSetup& setup) {
  return std::make_unique<CpuBackend>(setup);
}

}  // namespace hdrf::pipeline
