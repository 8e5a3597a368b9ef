// Capturing calibration sweeps (io/sweep_capture.h) from the synthetic sweep camera: the
// plan, the checks that send the operator back (auto exposure on, saturated scene, motion,
// flicker), cancel and resume, and the whole chain to a calibration scored against the
// camera's true response and noise.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include "eval/response_error.h"
#include "io/sweep.h"
#include "io/sweep_capture.h"
#include "radiometry/calibration_job.h"
#include "sim/sweep_camera.h"
#include "support/test_support.h"

namespace hdrf {
namespace {

using io::CaptureProblem;

sim::SyntheticSweepOptions Small(const std::string& response = "gamma2.2") {
  sim::SyntheticSweepOptions o;
  o.width = 160;
  o.height = 120;
  o.response = sim::NamedResponse(response);
  o.response_name = response;
  return o;
}

CaptureProblem::FixAt FixOf(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const CaptureProblem& p) {
    return p.fix_at();
  }
  ADD_FAILURE() << "no CaptureProblem thrown";
  return CaptureProblem::FixAt::kSetup;
}

TEST(SweepCapture, AutoExposureLeftOnIsRefusedBeforeCapture) {
  sim::SyntheticSweepCamera cam(Small());
  ASSERT_TRUE(cam.colour_lock().auto_exposure);  // cameras start automatic
  test::ExpectErrorContaining([&] { io::PlanSweep(cam, {}); }, {"auto exposure is on", "Lock auto exposure"});
  EXPECT_EQ(FixOf([&] { io::PlanSweep(cam, {}); }), CaptureProblem::FixAt::kSetup);
  cam.SetAutomatic(false, true);
  test::ExpectErrorContaining([&] { io::PlanSweep(cam, {}); }, {"auto white balance is on"});
  cam.SetAutomatic(false, false);
  EXPECT_NO_THROW(io::PlanSweep(cam, {}));
}

TEST(SweepCapture, PlanCoversTheSceneWithinTheCamerasUnit) {
  sim::SyntheticSweepCamera cam(Small("xtion"));
  cam.SetAutomatic(false, false);
  const io::SweepPlan plan = io::PlanSweep(cam, {});
  ASSERT_GE(plan.exposures_ms.size(), 5u);
  for (std::size_t k = 1; k < plan.exposures_ms.size(); ++k) {
    const double stops = std::log2(plan.exposures_ms[k] / plan.exposures_ms[k - 1]);
    EXPECT_GT(stops, 0.3) << k;
    EXPECT_LT(stops, 0.7) << k;
    EXPECT_NEAR(plan.exposures_ms[k], cam.Quantise(plan.exposures_ms[k]), 1e-12);
  }
  for (int c = 0; c < 3; ++c) EXPECT_GT(plan.coverage.share[std::size_t(c)], 0.9) << c;
  EXPECT_LT(plan.saturated_at_shortest, 0.2);   // what stays clipped is the window's light
  EXPECT_LT(plan.dark_at_longest, 0.05);
  // Given limits are kept.
  io::SweepPlanOptions o;
  o.min_ms = 1;
  o.max_ms = 16;
  o.step_stops = 1;
  const io::SweepPlan fixed = io::PlanSweep(cam, o);
  EXPECT_EQ(fixed.exposures_ms, (std::vector<double>{1, 2, 4, 8, 16}));
}

TEST(SweepCapture, SaturatedSceneSendsTheOperatorBackToSetup) {
  sim::SyntheticSweepOptions o = Small();
  o.limits = {200, 2000};  // the shortest exposure is far too long for this scene
  sim::SyntheticSweepCamera cam(o);
  cam.SetAutomatic(false, false);
  test::ExpectErrorContaining([&] { io::PlanSweep(cam, {}); },
                              {"even at the shortest exposure (200 ms)", "saturated", "darker scene"});
  EXPECT_EQ(FixOf([&] { io::PlanSweep(cam, {}); }), CaptureProblem::FixAt::kSetup);
}

TEST(SweepCapture, CameraMovedMidSweepStopsKeepsStepsAndResumes) {
  test::TempDir tmp;
  const auto folder = tmp / "sweep";
  io::SweepPlan plan;
  {
    sim::SyntheticSweepOptions o = Small();
    sim::SyntheticSweepCamera planner(o);
    planner.SetAutomatic(false, false);
    plan = io::PlanSweep(planner, {});
  }
  sim::SyntheticSweepCamera cam(Small());
  cam.SetAutomatic(false, false);
  io::SweepCapture capture(cam, plan, folder);
  const int knock_at = int(plan.exposures_ms.size()) / 2;  // mid-sweep, well exposed
  bool knocked = false;
  const std::string msg = test::ExpectErrorContaining(
      [&] {
        capture.Run([&](const io::CaptureStatus& s) {
          if (!knocked && s.step == knock_at - 1 && s.frames_written == knock_at * plan.options.repeats) {
            cam.KnockAside(6);
            knocked = true;
          }
        });
      },
      {"moved", "kept in"});
  EXPECT_EQ(FixOf([&] { io::SweepCapture::Resume(cam, folder).Run(); }), CaptureProblem::FixAt::kCapture);
  const io::CaptureRecord rec = io::ReadCaptureRecord(folder);
  EXPECT_EQ(rec.steps_done, knock_at) << msg;
  EXPECT_GT(rec.recaptures, 0);
  EXPECT_EQ(io::ReadSweep(folder).images.size(), std::size_t(rec.steps_done * plan.options.repeats));
  // Put back where it was (a fresh camera, unmoved): resume completes the same sweep.
  sim::SyntheticSweepCamera back(Small());
  back.SetAutomatic(false, false);
  const io::CaptureResult r = io::SweepCapture::Resume(back, folder).Run();
  EXPECT_TRUE(r.complete());
  const radiometry::Sweep s = io::ReadSweep(folder);
  EXPECT_EQ(s.images.size(), plan.exposures_ms.size() * std::size_t(plan.options.repeats));
  EXPECT_NO_THROW(radiometry::CheckSweepForCalibration(s));
}

TEST(SweepCapture, FlickerIsRecapturedThenReported) {
  test::TempDir tmp;
  sim::SyntheticSweepOptions o = Small();
  o.flicker = 0.15;
  sim::SyntheticSweepCamera cam(o);
  cam.SetAutomatic(false, false);
  io::SweepPlanOptions po;
  po.min_ms = 2;
  po.max_ms = 32;
  po.step_stops = 1;
  po.max_retries = 2;
  // Planning meters single frames and passes; the repeats show the flicker.
  io::SweepCapture capture(cam, io::PlanSweep(cam, po), tmp / "sweep");
  test::ExpectErrorContaining([&] { capture.Run(); }, {"between repeats: flickering light", "3 times in a row"});
  EXPECT_EQ(io::ReadCaptureRecord(tmp / "sweep").steps_done, 0);
}

TEST(SweepCapture, CancelKeepsCompleteStepsAndResumeFinishes) {
  test::TempDir tmp;
  const auto folder = tmp / "sweep";
  sim::SyntheticSweepCamera cam(Small("xtion"));
  cam.SetAutomatic(false, false);
  const io::SweepPlan plan = io::PlanSweep(cam, {});
  std::atomic<bool> cancel{false};
  io::SweepCapture capture(cam, plan, folder);
  const io::CaptureResult first = capture.Run(
      [&](const io::CaptureStatus& s) {
        if (s.frames_written >= 2 * plan.options.repeats + 1 || (s.step == 2 && s.frames_written > 0)) cancel = true;
      },
      &cancel);
  EXPECT_TRUE(first.cancelled);
  EXPECT_EQ(first.steps_done, 2);
  EXPECT_EQ(io::ReadSweep(folder).images.size(), std::size_t(2 * plan.options.repeats));
  // A new folder is refused where one is being captured; resume is the way on.
  test::ExpectErrorContaining([&] { io::SweepCapture(cam, plan, folder).Run(); }, {"not empty"});
  const io::CaptureResult rest = io::SweepCapture::Resume(cam, folder).Run();
  EXPECT_TRUE(rest.complete());
  EXPECT_EQ(rest.frames, int(plan.exposures_ms.size()) * plan.options.repeats);
  // Another camera cannot resume it.
  struct Other : sim::SyntheticSweepCamera {
    using SyntheticSweepCamera::SyntheticSweepCamera;
    std::string serial() const override { return "SOMEONE-ELSE"; }
  } other(Small());
  test::ExpectErrorContaining([&] { io::SweepCapture::Resume(other, folder); }, {"HDRF-SYNTHETIC", "same camera"});
}

// The whole chain on responses the calibration is not told: captured, fitted, validated;
// scored against the camera's truth (1 % of the range, noise within 10 %).
TEST(SweepCapture, CapturedSweepCalibratesToTheTruth) {
  for (const std::string response : {"gamma2.2", "xtion"}) {
    test::TempDir tmp;
    sim::SyntheticSweepCamera cam(Small(response));
    cam.SetAutomatic(false, false);
    io::SweepPlanOptions po;
    po.repeats = 6;
    const io::SweepPlan plan = io::PlanSweep(cam, po);
    ASSERT_TRUE(io::SweepCapture(cam, plan, tmp / "sweep").Run().complete());
    const radiometry::Sweep s = io::ReadSweep(tmp / "sweep");
    const radiometry::CalibrationOutcome out = radiometry::RunCalibration(s, {});
    const eval::ResponseAccuracy a = eval::CompareResponse(out.fit.inverse, cam.true_response());
    std::printf("%s: %zu exposures %.3g..%.3g ms, response within %.4f of the range (bins %.4f), verdict %s\n",
                response.c_str(), plan.exposures_ms.size(), plan.exposures_ms.front(), plan.exposures_ms.back(),
                a.PointMax(), a.BinMax(), radiometry::VerdictName(out.check.verdict));
    EXPECT_LT(a.BinMax(), 0.01) << response;
    for (const std::string& r : out.check.reasons) std::printf("  - %s\n", r.c_str());
    EXPECT_EQ(out.check.verdict, radiometry::Verdict::kGood) << response;
    ASSERT_TRUE(out.noise_saved()) << response;
    const radiometry::NoiseModel& truth = cam.options().noise;
    for (int c = 0; c < 3; ++c) {
      std::printf("  channel %d: sigma_s %.5f (true %.5f), sigma_c %.5f (true %.5f)\n", c, out.noise.sigma_s[c],
                  truth.sigma_s[c], out.noise.sigma_c[c], truth.sigma_c[c]);
      EXPECT_NEAR(out.noise.sigma_s[c], truth.sigma_s[c], 0.1 * truth.sigma_s[c]) << response << c;
      EXPECT_NEAR(out.noise.sigma_c[c], truth.sigma_c[c], 0.1 * truth.sigma_c[c]) << response << c;
    }
  }
}

}  // namespace
}  // namespace hdrf
