// The synthetic auto-exposure RGB-D sensor: a camera moving through a built-in HDR scene,
// with every truth known (pose, radiance, depth, exposure). The embedded default source of
// the studio and of `scan`, and the generator of test data. Deterministic for a seed.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "common/image.h"
#include "common/se3.h"
#include "radiometry/sensor.h"
#include "sim/auto_exposure.h"
#include "sim/camera_path.h"
#include "sim/scene.h"
#include "sim/sensor_model.h"

namespace hdrf::sim {

struct SimOptions {
  std::string scene = "room";  // built-in scene: room, desk, hall
  std::uint32_t seed = 1;      // varies textures, lights, path and noise
  int width = 320, height = 240;
  int frames = 300;
  double fps = 30.0;
  AeOptions ae;                // auto exposure (smooth by default)
  // Exposure sweep for calibration: static camera, each exposure `sweep_repeats` times.
  // Frames = sweep_exposures_ms.size() * sweep_repeats; `frames` and `ae` are ignored.
  bool sweep = false;
  // Half-stop steps from 0.25 to 128 ms: dense enough to recover steep response knees.
  std::vector<double> sweep_exposures_ms = {0.25, 0.354, 0.5, 0.707, 1, 1.41, 2, 2.83, 4, 5.66,
                                            8, 11.3, 16, 22.6, 32, 45.3, 64, 90.5, 128};
  int sweep_repeats = 5;
  // The sensor's true calibration; defaults to the built-in Xtion profile.
  radiometry::InverseResponse response;
  radiometry::NoiseModel noise;
  DepthNoiseOptions depth;
  double depth_scale = 5000.0;  // raw units per metre in the written depth PNGs

  SimOptions();
  void Check() const;  // throws SettingError naming the flag
};

struct SimFrame {
  int index = 0;
  double timestamp = 0;
  double exposure_ms = 0;
  Pose T_world_camera = Pose::Identity();
  ColorImage color;       // 8-bit, as the sensor delivers it
  DepthRawImage depth;    // raw units (depth_scale per metre), 0 = no data
  RadianceImage radiance; // true scene radiance L per pixel (linear, before exposure)
  DepthImage depth_true;  // exact depth in metres (0 where nothing would be measured)
};

class SyntheticSource {
 public:
  explicit SyntheticSource(SimOptions options);

  int size() const { return path_.size(); }
  bool done() const { return next_ >= size(); }
  // Renders the next frame. Frames come in order (auto exposure has state). An exposure
  // given replaces auto exposure's choice for this frame (a camera with AE switched off);
  // auto exposure still meters it.
  SimFrame Next(std::optional<double> exposure_ms = std::nullopt);

  // The parts of a frame, for a device that serves the scene live (the test OpenNI2
  // driver): view i of the path without colour (pose, radiance, raw and true depth;
  // deterministic, no auto-exposure state), and the colour the sensor forms from radiance
  // at an exposure, with noise drawn from `noise_key` (Next uses Hash(seed, i)).
  SimFrame RenderView(int i) const;
  ColorImage Expose(const RadianceImage& radiance, double exposure_ms, std::uint32_t noise_key) const;

  const SimOptions& options() const { return o_; }
  const Scene& scene() const { return scene_; }
  const CameraPath& path() const { return path_; }
  // Camera, depth scale, and the true response and noise, as sensor.json holds them.
  SensorInfo sensor() const;

 private:
  SimOptions o_;
  Scene scene_;
  CameraPath path_;
  AutoExposure ae_;
  ForwardResponse forward_;
  PinholeCamera camera_;
  int next_ = 0;
  double last_metered_ = -1;
};

// What auto exposure meters: the mean luminance of the central third of the image.
double MeterCentre(const RadianceImage& radiance);

// The camera of the built-in profile scaled to width x height.
PinholeCamera SimCamera(int width, int height);

}  // namespace hdrf::sim
