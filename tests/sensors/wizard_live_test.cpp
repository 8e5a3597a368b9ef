// The calibration wizard on a live OpenNI2 camera (the test driver), offscreen: the automation
// switch captures through the device's exposure control and stores the profile under the
// device's serial, which the live sources pick from then on; a saturated scene stops at
// Set-up with what to do.
#include <gtest/gtest.h>
#include <unistd.h>

#include <QApplication>
#include <QElapsedTimer>
#include <QLabel>
#include <QPushButton>
#include <QTest>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "calibration_wizard/calibration_wizard.h"
#include "eval/response_error.h"
#include "io/sensor_json.h"
#include "sensors/profiles.h"
#include "sim/builtin_sensor.h"
#include "support/test_support.h"
#include "test_device_control.h"
#include "wizard/automatic_run.h"

namespace {

namespace fs = std::filesystem;
using namespace hdrf;

// Set before OpenNI2 loads the driver (it reads them once).
const test::TestDeviceControl g_env("hdrf_wizard_live", "plugged still");

TEST(WizardLive, CalibratesTheDeviceAndStoresItsProfile) {
  g_env.Set("plugged still");
  test::TempDir tmp;
  const sensors::DeviceEntry device{"Synthetic RGB-D (test driver)", "HDRFusion", "hdrf-test://0", "HDRF-SIM-0001"};
  EXPECT_FALSE(sensors::ProfileFor(device, sensors::ParseCaptureMode("qvga")).own);
  wizard::WizardSettings s;
  s.source = "openni:mode=qvga,unit=0.1";
  s.sweep_folder = QString::fromStdString((tmp / "sweep").string());
  s.report_folder = QString::fromStdString((tmp / "report").string());
  s.plan.step_stops = 1;
  s.plan.repeats = 3;
  const test::AutomaticRun run = test::RunWizardAutomatic(s);
  ASSERT_EQ(run.exit_code, 0) << run.reason.toStdString();
  // The live sources take the device's own profile from now on.
  const sensors::Profile p = sensors::ProfileFor(device, sensors::ParseCaptureMode("qvga"));
  EXPECT_TRUE(p.own);
  ASSERT_TRUE(p.sensor.response);
  ASSERT_TRUE(p.sensor.device && p.sensor.device->exposure_ms_per_unit);
  EXPECT_DOUBLE_EQ(*p.sensor.device->exposure_ms_per_unit, 0.1);
  const eval::ResponseAccuracy a = eval::CompareResponse(*p.sensor.response, *sim::BuiltinXtionProfile().response);
  std::printf("test device: response within %.4f of the range (bins %.4f)\n", a.PointMax(), a.BinMax());
  EXPECT_LT(a.BinMax(), 0.01);
  EXPECT_TRUE(fs::exists(tmp / "report" / "report.html"));
}

TEST(WizardLive, SaturatedSceneStopsAtSetupWithWhatToDo) {
  g_env.Set("plugged still light=5000");
  test::TempDir tmp;
  wizard::WizardSettings s;
  s.source = "openni:mode=qvga,unit=0.1";
  s.sweep_folder = QString::fromStdString((tmp / "sweep").string());
  wizard::CalibrationWizard w(s);
  w.show();
  w.next();
  ASSERT_EQ(w.currentId(), wizard::CalibrationWizard::kSetup);
  QTest::mouseClick(w.findChild<QPushButton*>("setup_plan"), Qt::LeftButton);
  QLabel* problem = w.findChild<QLabel*>("setup_problem");
  QElapsedTimer t;
  t.start();
  while ((w.busy() || problem->text().isEmpty()) && t.elapsed() < 60000) QTest::qWait(20);
  EXPECT_TRUE(problem->text().contains("saturated")) << problem->text().toStdString();
  EXPECT_TRUE(problem->text().contains("darker scene")) << problem->text().toStdString();
  EXPECT_FALSE(w.currentPage()->isComplete());
  EXPECT_FALSE(fs::exists(tmp / "sweep"));
  // The light dimmed, the plan goes through.
  g_env.Set("plugged still");
  QTest::mouseClick(w.findChild<QPushButton*>("setup_plan"), Qt::LeftButton);
  t.restart();
  while (!w.currentPage()->isComplete() && t.elapsed() < 60000) QTest::qWait(20);
  EXPECT_TRUE(w.currentPage()->isComplete()) << problem->text().toStdString();
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  QApplication app(argc, argv);
  return RUN_ALL_TESTS();
}
