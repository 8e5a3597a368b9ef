// Capturing an exposure sweep from a camera (the calibration wizard's Set-up and Capture
// pages, `hdrfusion capture-sweep`): manual exposure verified, exposures planned from the
// scene, each step checked for motion and flicker and re-captured when it fails, frames
// written to a sweep folder (docs/formats.md) as they come, and an interrupted capture
// resumed where it stopped. A controller with Run(): the CLI calls it, the wizard runs the
// same object on a worker thread.
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/error.h"
#include "radiometry/sweep_camera.h"
#include "radiometry/validation.h"

namespace hdrf::io {

// A problem the operator must fix, and where: the wizard goes back to that page.
class CaptureProblem : public Error {
 public:
  enum class FixAt { kSetup, kCapture };
  CaptureProblem(FixAt at, const std::string& what) : Error(what), at_(at) {}
  FixAt fix_at() const { return at_; }

 private:
  FixAt at_;
};

// What the plan meters and the wizard's preview highlights: a pixel is saturated when any
// channel reaches 250, black when every channel is 5 or below.
inline bool IsSaturated(const Rgb8& v) { return v.r >= 250 || v.g >= 250 || v.b >= 250; }
inline bool IsBlack(const Rgb8& v) { return v.r <= 5 && v.g <= 5 && v.b <= 5; }

struct SweepPlanOptions {
  double step_stops = 0.5;  // between exposures (half a stop: steep knees recovered)
  int repeats = 5;          // frames per exposure (the noise fit needs 3 or more)
  double min_ms = 0;        // shortest exposure; 0: metered (the brightest parts just unclipped)
  double max_ms = 0;        // longest; 0: metered (90 % of the image saturated)
  int max_exposures = 40;   // a wider range gets larger steps (with a warning)
  int settle_frames = 2;    // frames dropped after each change of exposure
  int max_retries = 3;      // re-captures of a step that fails its checks
  // Between repeats of one exposure: a change of mean level beyond this share is flicker.
  double flicker_share = 0.03;
  void Check() const;       // throws SettingError naming the key
};

struct SweepPlan {
  std::vector<double> exposures_ms;  // ascending, as the camera sets them
  SweepPlanOptions options;
  // Measured on a preview sweep (one frame per exposure) before capture.
  radiometry::LevelCoverage coverage;
  double saturated_at_shortest = 0;  // share of pixels clipped high at the shortest exposure
  double dark_at_longest = 0;        // share of pixels clipped low at the longest
  std::vector<std::string> warnings;
};

struct CaptureStatus {
  std::string stage;     // "metering", "preview", "capture"
  int step = 0, steps = 0;
  double exposure_ms = 0;
  int frames_written = 0;
  int recaptures = 0;    // steps taken again (motion, flicker)
  std::string note;      // the last re-capture's reason, or ""
  std::shared_ptr<const ColorImage> frame;  // the step's last frame, once the step is written
};
using CaptureProgress = std::function<void(const CaptureStatus&)>;

// Auto exposure and white balance off as read back from the camera, and the exposure acting
// on the images (a camera that keeps its automatic exposure ignores what is set). Throws
// CaptureProblem (FixAt::kSetup) saying what to do.
void VerifyManualExposure(radiometry::SweepCamera& camera);

// Meters the scene (the shortest exposure that leaves its brightest parts unclipped, the
// longest that saturates most of it, within the camera's limits), then takes one frame per
// planned exposure and measures which levels of each channel they cover. Throws
// CaptureProblem (FixAt::kSetup) for a scene saturated even at the shortest exposure, black
// at the longest, or covering under half the levels of a channel; warnings for less.
SweepPlan PlanSweep(radiometry::SweepCamera& camera, const SweepPlanOptions& options,
                    const CaptureProgress& progress = {}, const std::atomic<bool>* cancel = nullptr);

// What capture.json in the sweep folder keeps (the plan, how far the capture got).
struct CaptureRecord {
  std::string camera, serial;
  SweepPlan plan;
  int steps_done = 0, recaptures = 0;
};
CaptureRecord ReadCaptureRecord(const std::filesystem::path& folder);  // throws InputError

struct CaptureResult {
  int steps_done = 0, steps = 0;
  int frames = 0, recaptures = 0;
  bool cancelled = false;
  bool complete() const { return steps_done == steps; }
};

class SweepCapture {
 public:
  // A new capture into `folder` (absent or empty; created).
  SweepCapture(radiometry::SweepCamera& camera, SweepPlan plan, std::filesystem::path folder);
  // Goes on with an interrupted capture in `folder` (its capture.json): the same camera
  // (serial) is required; a step left half-written is taken again.
  static SweepCapture Resume(radiometry::SweepCamera& camera, const std::filesystem::path& folder);

  // Captures the steps not done yet. Each step: set the exposure, drop settle frames, take
  // the repeats, check them against each other (motion, flicker) and against the step
  // before (motion), take the step again when a check fails (up to max_retries), then write
  // it and note it in capture.json. Cancel stops between frames and keeps every complete
  // step. Throws CaptureProblem (FixAt::kCapture) when a step keeps failing; what was
  // written stays and can be resumed.
  CaptureResult Run(const CaptureProgress& progress = {}, const std::atomic<bool>* cancel = nullptr);

  const std::filesystem::path& folder() const { return folder_; }
  const SweepPlan& plan() const { return record_.plan; }

 private:
  SweepCapture(radiometry::SweepCamera& camera, CaptureRecord record, std::filesystem::path folder, bool resume);
  radiometry::SweepCamera& camera_;
  CaptureRecord record_;
  std::filesystem::path folder_;
  bool resume_;
};

}  // namespace hdrf::io
