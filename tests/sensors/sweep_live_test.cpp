// Calibration sweeps from a live OpenNI2 camera (the test driver): exposure control, and
// what the operator is told when auto exposure is left on, the camera moves mid-sweep or
// the scene is saturated; cancel keeps the steps captured and resume completes them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "eval/response_error.h"
#include "io/sweep.h"
#include "io/sweep_capture.h"
#include "radiometry/calibration_job.h"
#include "sensors/sweep_cameras.h"
#include "sim/builtin_sensor.h"
#include "support/test_support.h"
#include "test_device_control.h"

namespace {

namespace fs = std::filesystem;
using namespace hdrf;

// Set before OpenNI2 loads the driver (it reads them once).
const test::TestDeviceControl g_env("hdrf_sweep_live", "plugged still");

constexpr const char* kSpec = "openni:mode=qvga,unit=0.1";

io::SweepPlanOptions Quick() {
  io::SweepPlanOptions o;
  o.step_stops = 1;
  o.repeats = 3;
  return o;
}

TEST(SweepLive, CapturesWithExposureControlAndCalibrates) {
  g_env.Set("plugged still");
  test::TempDir tmp;
  auto cam = sensors::OpenSweepCamera(kSpec);
  EXPECT_EQ(cam->serial(), "HDRF-SIM-0001");
  cam->SetAutomatic(false, false);
  const io::SweepPlan plan = io::PlanSweep(*cam, Quick());
  ASSERT_GE(plan.exposures_ms.size(), 4u);
  for (double t : plan.exposures_ms) EXPECT_NEAR(t / 0.1, std::round(t / 0.1), 1e-9) << t;  // the device's unit
  const io::CaptureResult r = io::SweepCapture(*cam, plan, tmp / "sweep").Run();
  ASSERT_TRUE(r.complete());
  const radiometry::Sweep s = io::ReadSweep(tmp / "sweep");
  EXPECT_EQ(s.images.size(), plan.exposures_ms.size() * 3);
  EXPECT_EQ(s.images[0].width(), 320);
  const radiometry::CalibrationOutcome out = radiometry::RunCalibration(s, {});
  const eval::ResponseAccuracy a = eval::CompareResponse(out.fit.inverse, *sim::BuiltinXtionProfile().response);
  std::printf("live sweep: %zu exposures %.3g..%.3g ms; response within %.4f of the range (bins %.4f); verdict %s\n",
              plan.exposures_ms.size(), plan.exposures_ms.front(), plan.exposures_ms.back(), a.PointMax(), a.BinMax(),
              radiometry::VerdictName(out.check.verdict));
  EXPECT_LT(a.BinMax(), 0.01);
  EXPECT_NE(out.check.verdict, radiometry::Verdict::kRedo);
}

TEST(SweepLive, AutoExposureLeftOnIsRefused) {
  g_env.Set("plugged still");
  auto cam = sensors::OpenSweepCamera(kSpec);
  cam->SetAutomatic(true, false);  // the operator left it on
  test::ExpectErrorContaining([&] { io::PlanSweep(*cam, Quick()); }, {"auto exposure is on", "Lock auto exposure"});
  cam->SetAutomatic(false, false);  // the way back: lock it
  EXPECT_NO_THROW(io::PlanSweep(*cam, Quick()));
}

TEST(SweepLive, SaturatedSceneIsRefusedWithWhatToDo) {
  g_env.Set("plugged still light=5000");
  auto cam = sensors::OpenSweepCamera(kSpec);
  cam->SetAutomatic(false, false);
  test::ExpectErrorContaining([&] { io::PlanSweep(*cam, Quick()); },
                              {"even at the shortest exposure (0.1 ms)", "saturated", "darker scene"});
  g_env.Set("plugged still");
}

TEST(SweepLive, CameraMovedMidSweepIsCaughtAndCaptureKept) {
  g_env.Set("plugged still");
  test::TempDir tmp;
  auto cam = sensors::OpenSweepCamera(kSpec);
  cam->SetAutomatic(false, false);
  const io::SweepPlan plan = io::PlanSweep(*cam, Quick());
  io::SweepCapture capture(*cam, plan, tmp / "sweep");
  bool moved = false;
  const std::string msg = test::ExpectErrorContaining(
      [&] {
        capture.Run([&](const io::CaptureStatus& s) {
          if (!moved && s.frames_written >= 6) {  // two steps in: the camera is picked up
            g_env.Set("plugged");
            moved = true;
          }
        });
      },
      {"moved", "kept in"});
  g_env.Set("plugged still");
  const io::CaptureRecord rec = io::ReadCaptureRecord(tmp / "sweep");
  EXPECT_GE(rec.steps_done, 2) << msg;
  EXPECT_LT(rec.steps_done, int(plan.exposures_ms.size())) << msg;
  EXPECT_EQ(io::ReadSweep(tmp / "sweep").images.size(), std::size_t(rec.steps_done) * 3);
  // Still again but somewhere else: resuming is refused (the frames would not match).
  test::ExpectErrorContaining([&] { io::SweepCapture::Resume(*cam, tmp / "sweep").Run(); },
                              {"no longer matches the exposure before", "start a new sweep"});
}

TEST(SweepLive, CancelKeepsStepsAndResumeCompletes) {
  g_env.Set("plugged still");
  test::TempDir tmp;
  std::atomic<bool> cancel{false};
  io::SweepPlan plan;
  {
    auto cam = sensors::OpenSweepCamera(kSpec);
    cam->SetAutomatic(false, false);
    plan = io::PlanSweep(*cam, Quick());
    io::SweepCapture capture(*cam, plan, tmp / "sweep");
    const io::CaptureResult r = capture.Run(
        [&](const io::CaptureStatus& s) {
          if (s.frames_written >= 6) cancel = true;
        },
        &cancel);
    EXPECT_TRUE(r.cancelled);
    EXPECT_EQ(r.steps_done, 2);
  }
  // The camera closed and opened again (the wizard restarted), held still where it was.
  auto cam = sensors::OpenSweepCamera(kSpec);
  cam->SetAutomatic(false, false);
  const io::CaptureResult rest = io::SweepCapture::Resume(*cam, tmp / "sweep").Run();
  EXPECT_TRUE(rest.complete());
  EXPECT_EQ(io::ReadSweep(tmp / "sweep").images.size(), plan.exposures_ms.size() * 3);
}

}  // namespace
