#include "pipeline/pipeline.h"

#include <chrono>

#include "common/error.h"

namespace hdrf::pipeline {

namespace {
using Clock = std::chrono::steady_clock;
double Ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}
// Grey level in [0, 1] of the delivered colour: the brightness-constancy baseline's input.
Image<float> RawIntensity(const ColorImage& c) {
  Image<float> out(c.width(), c.height());
  for (std::size_t i = 0; i < c.size(); ++i) out[i] = (c[i].r + c[i].g + c[i].b) / 765.f;
  return out;
}
}  // namespace

void PipelineOptions::Check() const {
  volume.Check();
  tracker.Check();
  if (pcf < 0 || pcf > 3) throw SettingError("--pcf", "must be 0, 1, 2 or 3 (p0..p3)");
  if (nr.patch < 3 || nr.patch % 2 == 0) throw SettingError("nr.patch", "must be odd and >= 3");
  if (nr.downsample < 1 || nr.downsample > 8) throw SettingError("nr.downsample", "must be 1..8");
}

Pipeline::Pipeline(const PipelineOptions& options, const PinholeCamera& camera,
                   const SensorInfo& sensor)
    : o_((options.Check(), options)), cam_(camera), volume_(o_.volume) {
  if (!camera.Valid()) throw SettingError("camera", "intrinsics must be positive");
  if (!sensor.response)
    throw Error("the sensor has no response calibration (sensor.json 'response'); calibrate it "
                "with hdrfusion calibrate, or pass --response srgb to assume an sRGB camera");
  inverse_ = *sensor.response;
  inverse_.Check("sensor response");
  radiometry::NoiseModel noise;
  if (sensor.noise) {
    noise = *sensor.noise;
  } else {  // PCF from the response alone: a mild noise floor, documented in docs/engine.md
    noise.sigma_s = {0.02f, 0.02f, 0.02f};
    noise.sigma_c = {0.002f * inverse_.table[0][128], 0.002f * inverse_.table[1][128],
                     0.002f * inverse_.table[2][128]};
  }
  pcf_ = radiometry::ComputePcf(inverse_, noise);
}

volume::Volume::Rendering Pipeline::Render(const Pose& T) const { return volume_.Raycast(cam_, T); }

FrameReport Pipeline::Process(const FrameInput& in) {
  if (in.color.width() != cam_.width || in.color.height() != cam_.height ||
      in.depth_m.width() != cam_.width || in.depth_m.height() != cam_.height)
    throw Error("frame " + std::to_string(index_) + ": colour or depth size differs from the camera (" +
                std::to_string(cam_.width) + "x" + std::to_string(cam_.height) + ")");
  FrameReport rep;
  rep.index = index_;
  rep.timestamp = in.timestamp;
  const auto t0 = Clock::now();
  // 1. Convert: radiance and confidence; depth filtering.
  RadianceImage radiance;
  Image<float> conf, maxconf;
  imaging::ConvertFrame(in.color, inverse_, pcf_, o_.pcf, radiance, conf, maxconf);
  const DepthImage depth = o_.bilateral ? imaging::BilateralDepth(in.depth_m) : in.depth_m.Clone();
  const auto t1 = Clock::now();
  // 2. Normalize.
  const Image<float> nr = imaging::NormalizedRadiance(imaging::Luminance(radiance), o_.nr);
  const bool baseline = o_.tracker.kind == tracking::TrackerKind::kIntensity;
  const Image<float> track_image = baseline ? RawIntensity(in.color) : nr.Clone();
  Image<float> track_weight = baseline ? Image<float>(cam_.width, cam_.height, 1.f) : conf.Clone();
  const auto t2 = Clock::now();
  // 3. Track.
  const tracking::Live live = tracking::MakeLive(depth, track_image, track_weight, cam_, o_.tracker.levels);
  if (index_ == 0 || !reference_) {
    previous_pose_ = pose_;
    rep.tracking.T_world_camera = pose_;
    rep.tracking.inlier_share = 1;
  } else {
    // Start from a constant-velocity prediction (the last inter-frame motion, repeated).
    const Pose predicted = se3::Orthonormalized(pose_ * (previous_pose_.inverse() * pose_));
    rep.tracking = tracking::Track(*reference_, live, predicted, o_.tracker);
    if (!rep.tracking.lost) {
      previous_pose_ = pose_;
      pose_ = rep.tracking.T_world_camera;
    }
  }
  rep.T_world_camera = pose_;
  const auto t3 = Clock::now();
  // 4. Exposure compensation against the model as seen from the last pose.
  double t_ratio = 1;
  if (index_ > 0 && have_render_ && !rep.tracking.lost) {
    const auto est = tracking::EstimateExposureRatio(last_render_.vertex, last_render_.radiance,
                                                     radiance, conf, cam_, pose_);
    rep.exposure_samples = est.samples;
    if (est.valid) t_ratio = est.ratio;
  }
  rep.exposure_ratio = t_ratio;
  if (in.exposure_ms) {
    if (index_ == 0) first_exposure_ms_ = in.exposure_ms;
    if (first_exposure_ms_) rep.exposure_ratio_reported = *first_exposure_ms_ / *in.exposure_ms;
  }
  const auto t4 = Clock::now();
  // 5. Integrate (lost frames are not fused).
  if (!rep.tracking.lost) {
    RadianceImage scaled(radiance.width(), radiance.height());
    for (std::size_t i = 0; i < radiance.size(); ++i) scaled[i] = radiance[i] * float(t_ratio);
    // The finest tracking level already holds this frame's normals (same filtered depth).
    const Image<Float3>& nc = live.levels[0].normal_c;
    volume::Volume::FrameInput fi{&depth, &nc, &scaled, &nr, &conf, &maxconf, cam_, pose_};
    volume_.Integrate(fi);
    rep.fused = true;
  }
  rep.allocated_bricks = volume_.allocated_bricks();
  const auto t5 = Clock::now();
  // 6. Ray cast the model from the new pose: the next frame's reference.
  if (rep.fused || !have_render_) {
    last_render_ = volume_.Raycast(cam_, pose_);
    have_render_ = true;
  }
  if (o_.tracker.frame_to_model && !baseline) {
    reference_ = tracking::MakeReference(last_render_.vertex, last_render_.normal, last_render_.nr,
                                         cam_, o_.tracker.levels, pose_);
  } else if (!rep.tracking.lost || !reference_) {
    // Frame to frame: the live frame itself, in world coordinates at its pose.
    const RigidTransform T = ToRigidTransform(pose_);
    const auto& L0 = live.levels[0];
    Image<Float3> vw(cam_.width, cam_.height, Float3{0, 0, 0}), nw(cam_.width, cam_.height, Float3{0, 0, 0});
    for (std::size_t i = 0; i < vw.size(); ++i)
      if (L0.vertex_c[i].z > 0 && Length(L0.normal_c[i]) > 0) {
        vw[i] = T.Apply(L0.vertex_c[i]);
        nw[i] = T.Rotate(L0.normal_c[i]);
      }
    reference_ = tracking::MakeReference(vw, nw, track_image, cam_, o_.tracker.levels, pose_);
  }
  const auto t6 = Clock::now();
  rep.ms = {Ms(t0, t1), Ms(t1, t2), Ms(t2, t3), Ms(t3, t4), Ms(t4, t5), Ms(t5, t6)};
  ++index_;
  return rep;
}

}  // namespace hdrf::pipeline
