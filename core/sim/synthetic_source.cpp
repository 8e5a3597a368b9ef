#include "sim/synthetic_source.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "sim/builtin_sensor.h"
#include "sim/noise.h"

namespace hdrf::sim {

namespace {
// Independent random streams per purpose.
enum Stream : std::uint32_t { kColorNoise = 1, kDepthNoise = 2, kEdgeDrop = 3, kGrazingDrop = 4 };
}  // namespace

SimOptions::SimOptions() {
  const SensorInfo profile = BuiltinXtionProfile();
  response = *profile.response;
  noise = *profile.noise;
}

void SimOptions::Check() const {
  if (width < 16 || height < 16 || width > 8192 || height > 8192)
    throw SettingError("--size", "must be between 16x16 and 8192x8192, got " +
                                     std::to_string(width) + "x" + std::to_string(height));
  if (!sweep && frames <= 0) throw SettingError("--frames", "must be positive");
  if (!(fps > 0)) throw SettingError("--fps", "must be positive");
  if (sweep) {
    if (sweep_exposures_ms.size() < 2)
      throw SettingError("--sweep", "needs at least two exposures");
    if (sweep_repeats < 1) throw SettingError("--sweep-repeats", "must be at least 1");
    for (double e : sweep_exposures_ms)
      if (!(e > 0)) throw SettingError("--sweep", "exposures must be positive");
  } else {
    ae.Check();
  }
  response.Check("simulated sensor response");
  noise.Check("simulated sensor noise");
  if (!(depth_scale > 0) || depth.max_m * depth_scale > 65535.0)
    throw SettingError("--depth-scale", "must be positive and keep the far range within 16 bits");
  const auto names = Scene::Names();
  if (std::find(names.begin(), names.end(), scene) == names.end())
    throw SettingError("--scene", "unknown scene '" + scene + "'; choose one of: " + Scene::NamesText());
}

PinholeCamera SimCamera(int width, int height) {
  const float s = float(width) / 640.f;
  return {width, height, 539.f * s, 539.f * s, 0.5f * float(width) - 0.5f,
          0.5f * float(height) - 0.5f};
}

SyntheticSource::SyntheticSource(SimOptions options)
    : o_((options.Check(), std::move(options))),
      scene_(Scene::Build(o_.scene, o_.seed)),
      path_(o_.sweep ? CameraPath::SweepView(scene_, int(o_.sweep_exposures_ms.size()) *
                                                         o_.sweep_repeats, o_.fps)
                     : scene_.walked_round() ? CameraPath::Walk(scene_, o_.seed, o_.frames, o_.fps)
                                          : CameraPath::Handheld(scene_, o_.seed, o_.frames, o_.fps)),
      ae_(o_.sweep ? AeOptions{} : o_.ae, o_.seed),
      forward_(o_.response),
      camera_(SimCamera(o_.width, o_.height)) {}

SensorInfo SyntheticSource::sensor() const {
  SensorInfo s;
  s.camera = camera_;
  s.depth_scale = o_.depth_scale;
  s.response = o_.response;
  s.noise = o_.noise;
  s.synthetic = SensorInfo::Synthetic{o_.scene, o_.seed};
  return s;
}

SimFrame SyntheticSource::Next(std::optional<double> exposure_ms) {
  if (done()) throw Error("synthetic source: all " + std::to_string(size()) + " frames delivered");
  const int i = next_++;
  const double auto_ms = o_.sweep ? o_.sweep_exposures_ms[std::size_t(i / o_.sweep_repeats)]
                                  : ae_.Next(i, last_metered_);
  SimFrame f = RenderView(i);
  f.exposure_ms = exposure_ms ? *exposure_ms : auto_ms;
  f.color = Expose(f.radiance, f.exposure_ms, Hash(o_.seed, std::uint32_t(i)));
  last_metered_ = MeterCentre(f.radiance);
  return f;
}

double MeterCentre(const RadianceImage& radiance) {
  // Mean luminance of the central third of the image.
  const int w = radiance.width(), h = radiance.height();
  double sum = 0;
  long count = 0;
  for (int y = h / 3; y < 2 * h / 3; ++y)
    for (int x = w / 3; x < 2 * w / 3; ++x) {
      sum += Luminance(radiance(x, y));
      ++count;
    }
  return count ? sum / double(count) : -1;
}

ColorImage SyntheticSource::Expose(const RadianceImage& radiance, double exposure_ms,
                                   std::uint32_t noise_key) const {
  // I = f(L * exposure + n_s + n_c), quantised and clipped.
  const int w = radiance.width(), h = radiance.height();
  ColorImage color(w, h);
  const float exposure = float(exposure_ms);
  const auto& n = o_.noise;
#pragma omp parallel for schedule(static)
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::uint32_t px = std::uint32_t(y * w + x);
      const Float3 L = radiance(x, y);
      const float Lc[3] = {L.x, L.y, L.z};
      std::uint8_t out[3];
      for (int c = 0; c < 3; ++c) {
        const float R = Lc[c] * exposure;
        const float sd = std::sqrt(R * n.sigma_s[c] * n.sigma_s[c] + n.sigma_c[c] * n.sigma_c[c]);
        const float g = Gaussian(Hash(noise_key, px * 4u + std::uint32_t(c), kColorNoise));
        out[c] = forward_.Level(c, R + sd * g);
      }
      color(x, y) = {out[0], out[1], out[2]};
    }
  }
  return color;
}

SimFrame SyntheticSource::RenderView(int i) const {
  if (i < 0 || i >= size())
    throw Error("synthetic source: view " + std::to_string(i) + " outside the path of " +
                std::to_string(size()) + " frames");
  SimFrame f;
  f.index = i;
  f.timestamp = path_.timestamp(i);
  f.T_world_camera = path_.T_world_camera(i);
  const int w = o_.width, h = o_.height;
  const PinholeCamera cam = camera_;
  const RigidTransform T = ToRigidTransform(f.T_world_camera);
  f.radiance = RadianceImage(w, h);
  f.depth_true = DepthImage(w, h);
  Image<float> grazing(w, h);   // |n . view ray|
  Image<std::uint8_t> emitter(w, h);  // surfaces the depth camera cannot see

  // 1. Ray casting: true radiance, depth, surface orientation.
#pragma omp parallel for schedule(dynamic, 4)
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const Float3 dc = Normalized(Float3{(float(x) - cam.cx) / cam.fx, (float(y) - cam.cy) / cam.fy, 1.f});
      const Float3 dw = T.Rotate(dc);
      const Hit hit = scene_.Intersect(T.t, dw);
      f.radiance(x, y) = scene_.Shade(hit);
      f.depth_true(x, y) = hit.t * dc.z;
      grazing(x, y) = std::abs(Dot(hit.normal, dw));
      // Emitters bright enough to blind the IR camera (daylight) give no depth; a monitor does.
      emitter(x, y) = scene_.IsEmissive(hit.material) && MaxComponent(f.radiance(x, y)) > 20.f;
    }
  }

  // 2. Depth: dropouts (range, emitters, grazing angles, edges), axial noise, disparity
  //    quantisation.
  f.depth = DepthRawImage(w, h);
  const std::uint32_t frame_key = Hash(o_.seed, std::uint32_t(i));
  const DepthNoiseOptions& dn = o_.depth;
#pragma omp parallel for schedule(static)
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::uint32_t px = std::uint32_t(y * w + x);
      const float z = f.depth_true(x, y);
      bool valid = z >= dn.min_m && z <= dn.max_m && !emitter(x, y);
      if (valid && dn.enabled) {
        if (grazing(x, y) < dn.grazing_cos) valid = false;
        float jump = 0;
        for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          const int xx = std::clamp(x + dx, 0, w - 1), yy = std::clamp(y + dy, 0, h - 1);
          jump = std::max(jump, std::abs(f.depth_true(xx, yy) - z));
        }
        if (jump > dn.edge_jump * z &&
            HashToUnit(Hash(frame_key, px, kEdgeDrop)) < dn.edge_dropout)
          valid = false;
      }
      if (!valid) {
        f.depth(x, y) = 0;
        continue;
      }
      float zn = z;
      if (dn.enabled) {
        zn += AxialSigma(z) * Gaussian(Hash(frame_key, px, kDepthNoise));
        const float disparity = dn.focal_px * dn.baseline_m / zn;
        const float q = std::round(disparity * dn.subpixel) / dn.subpixel;
        zn = dn.focal_px * dn.baseline_m / q;
      }
      f.depth(x, y) = std::uint16_t(std::clamp(std::round(double(zn) * o_.depth_scale), 1.0, 65535.0));
    }
  }
  // Emitters and out-of-range surfaces have no true depth either.
  for (std::size_t k = 0; k < f.depth_true.size(); ++k)
    if (emitter[k] || f.depth_true[k] < dn.min_m || f.depth_true[k] > dn.max_m) f.depth_true[k] = 0;

  return f;
}

}  // namespace hdrf::sim
