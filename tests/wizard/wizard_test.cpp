// The calibration wizard offscreen: every page driven by its widgets (choices, errors and the
// way back, cancel and resume, plots filled, verdict, save), and the automation switch end to
// end on the synthetic sensor with a response it is not told and from a recorded sweep folder,
// the saved profile scored against the truth (response within 1 % of the range, noise within
// 10 %).
#include <gtest/gtest.h>

#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QElapsedTimer>
#include <QLabel>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QRadioButton>
#include <QSpinBox>
#include <QTextBrowser>
#include <QUrl>
#include <QWizard>
#include <QTest>
#include <cstdlib>
#include <filesystem>

#include "calibration_wizard/calibration_wizard.h"
#include "calibration_wizard/plot_widget.h"
#include "eval/response_error.h"
#include "io/sensor_json.h"
#include "io/sequence.h"
#include "io/sweep_capture.h"
#include "response_curves.h"
#include "sensors/profiles.h"
#include "sim/sweep_camera.h"
#include "sim/sweep_simulator.h"
#include "support/test_support.h"
#include "wizard/automatic_run.h"

namespace hdrf::wizard {
namespace {

namespace fs = std::filesystem;

// A private profile folder per test (profiles are stored per serial under XDG_DATA_HOME).
struct ProfileHome {
  test::TempDir dir;
  ProfileHome() { setenv("XDG_DATA_HOME", (dir / "xdg").c_str(), 1); }
};

bool WaitFor(const std::function<bool()>& done, int ms = 60000) {
  QElapsedTimer t;
  t.start();
  while (!done() && t.elapsed() < ms) QTest::qWait(20);
  return done();
}

// Share of pixels that are not white: a plot with curves drawn, not an empty frame.
double Inked(const fs::path& png) {
  const QImage im(QString::fromStdString(png.string()));
  if (im.isNull()) return 0;
  long n = 0;
  for (int y = 0; y < im.height(); ++y)
    for (int x = 0; x < im.width(); ++x) n += QColor(im.pixel(x, y)).lightness() < 200;
  return double(n) / (double(im.width()) * im.height());
}

void ExpectProfileMatches(const std::string& serial, const radiometry::InverseResponse& truth,
                          const radiometry::NoiseModel& noise, const char* what) {
  const fs::path file = sensors::ProfilePath(serial);
  ASSERT_TRUE(fs::exists(file)) << what << ": no profile at " << file;
  const SensorInfo s = io::ReadSensorJson(file);
  ASSERT_TRUE(s.response && s.noise) << what;
  const eval::ResponseAccuracy a = eval::CompareResponse(*s.response, truth);
  std::printf("%s: response within %.4f of the range (bins %.4f)\n", what, a.PointMax(), a.BinMax());
  EXPECT_LT(a.BinMax(), 0.01) << what;
  for (int c = 0; c < 3; ++c) {
    std::printf("  channel %d: sigma_s %.5f (true %.5f), sigma_c %.5f (true %.5f)\n", c, s.noise->sigma_s[c],
                noise.sigma_s[c], s.noise->sigma_c[c], noise.sigma_c[c]);
    EXPECT_NEAR(s.noise->sigma_s[c], noise.sigma_s[c], 0.1 * noise.sigma_s[c]) << what << c;
    EXPECT_NEAR(s.noise->sigma_c[c], noise.sigma_c[c], 0.1 * noise.sigma_c[c]) << what << c;
  }
}

// The wizard's Help button: a menu whose first entry opens the calibration guide in the
// documentation window, rendered from its Markdown; About names the program.
TEST(Wizard, HelpButtonOpensTheCalibrationGuide) {
  CalibrationWizard w(WizardSettings{});
  w.show();
  auto* button = qobject_cast<QPushButton*>(w.button(QWizard::HelpButton));
  ASSERT_NE(button, nullptr);
  EXPECT_TRUE(button->isVisible());
  ASSERT_NE(button->menu(), nullptr);
  QAction* guide = w.findChild<QAction*>("action_help_guide");
  ASSERT_NE(guide, nullptr);
  guide->trigger();
  auto* browser = w.findChild<QTextBrowser*>("documentation_browser");
  ASSERT_NE(browser, nullptr);
  EXPECT_TRUE(browser->source().toLocalFile().endsWith("tutorials/calibrate.md")) << browser->source().toString().toStdString();
  EXPECT_TRUE(browser->toPlainText().contains("Calibrating a camera"));
  // A relative link of the page, resolved as a click resolves it, opens inside the window.
  browser->setSource(browser->source().resolved(QUrl("../calibration_wizard.md")));
  EXPECT_TRUE(browser->source().toLocalFile().endsWith("docs/calibration_wizard.md") ||
              browser->source().toLocalFile().endsWith("hdrfusion-studio/calibration_wizard.md"))
      << browser->source().toString().toStdString();
  EXPECT_TRUE(browser->toPlainText().contains("The calibration wizard"));
  browser->window()->close();
}

TEST(Wizard, AutomaticOnTheSyntheticSensorSavesItsTrueResponse) {
  ProfileHome home;
  test::TempDir tmp;
  WizardSettings s;
  s.source = "synthetic:response=gamma2.2,size=160x120";
  s.sweep_folder = QString::fromStdString((tmp / "sweep").string());
  s.report_folder = QString::fromStdString((tmp / "report").string());
  s.plan.repeats = 6;
  const test::AutomaticRun run = test::RunWizardAutomatic(s);
  ASSERT_EQ(run.exit_code, 0) << run.reason.toStdString();
  radiometry::InverseResponse truth = sim::NamedResponse("gamma2.2");
  ExpectProfileMatches("HDRF-SYNTHETIC", truth, sim::kSweepNoise, "gamma 2.2");
  for (const char* f : {"response.png", "derivative.png", "noise.png", "pcf.png", "residuals.png", "consistency.png"})
    EXPECT_GT(Inked(tmp / "report" / f), 0.01) << f;
  const std::string html = test::ReadText(tmp / "report" / "report.html");
  EXPECT_NE(html.find("Verdict: good"), std::string::npos);
  EXPECT_NE(html.find("response.png"), std::string::npos);
  EXPECT_TRUE(fs::exists(tmp / "report" / "sensor.json"));
}

// A measured film/camera curve from DoRF, handed to the synthetic sensor as a sensor.json
// the wizard only sees through the images.
TEST(Wizard, AutomaticRecoversAMeasuredCurveItWasNotTold) {
  const fs::path dorf = test::SharedData("dorf/dorf_invI_201x1024.txt");
  HDRF_SKIP_WITHOUT(dorf, "dorf/dorf_invI_201x1024.txt");
  ProfileHome home;
  test::TempDir tmp;
  const auto rows = experiments::LoadDorfInverseCurves(dorf);
  SensorInfo truth_file;
  truth_file.camera = PinholeCamera{160, 120, 150, 150, 79.5, 59.5};
  truth_file.response = experiments::InverseFromCurves({&rows.at(12), &rows.at(146), &rows.at(159)});
  truth_file.noise = sim::kSweepNoise;
  io::WriteSensorJson(tmp / "truth.json", truth_file);
  WizardSettings s;
  s.source = QString::fromStdString("synthetic:response=" + (tmp / "truth.json").string() + ",size=160x120");
  s.sweep_folder = QString::fromStdString((tmp / "sweep").string());
  s.report_folder = QString::fromStdString((tmp / "report").string());
  s.plan.repeats = 6;
  const test::AutomaticRun run = test::RunWizardAutomatic(s);
  ASSERT_EQ(run.exit_code, 0) << run.reason.toStdString();
  ExpectProfileMatches("HDRF-SYNTHETIC", *truth_file.response, sim::kSweepNoise, "DoRF 12/146/159");
}

TEST(Wizard, AutomaticFromARecordedSweepFolder) {
  ProfileHome home;
  test::TempDir tmp;
  sim::SyntheticSweepOptions o;
  o.width = 160;
  o.height = 120;
  sim::SyntheticSweepCamera cam(o);
  cam.SetAutomatic(false, false);
  io::SweepPlanOptions po;
  po.repeats = 6;
  ASSERT_TRUE(io::SweepCapture(cam, io::PlanSweep(cam, po), tmp / "recorded").Run().complete());
  WizardSettings s;
  s.source = QString::fromStdString((tmp / "recorded").string());
  s.report_folder = QString::fromStdString((tmp / "report").string());
  const test::AutomaticRun run = test::RunWizardAutomatic(s);
  ASSERT_EQ(run.exit_code, 0) << run.reason.toStdString();
  ExpectProfileMatches("HDRF-SYNTHETIC", cam.true_response(), sim::kSweepNoise, "recorded folder");
}

TEST(Wizard, AutomaticStopsWithTheReasonOnABadSource) {
  ProfileHome home;
  WizardSettings s;
  s.source = "/nonexistent/sweep";
  test::AutomaticRun run = test::RunWizardAutomatic(s);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_TRUE(run.reason.contains("/nonexistent/sweep")) << run.reason.toStdString();
  s.source = "synthetic:response=gamma9";
  run = test::RunWizardAutomatic(s);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_TRUE(run.reason.contains("gamma9")) << run.reason.toStdString();
  EXPECT_FALSE(fs::exists(sensors::ProfileFolder()));
}

// HDRF_DOCS_SHOTS=DIR: the pages as the operator sees them, for docs/calibration_wizard.md.
void DocsShot(QWidget& w, const char* name) {
  const char* dir = std::getenv("HDRF_DOCS_SHOTS");
  if (dir && *dir) w.grab().save(QString("%1/%2.png").arg(dir, name));
}

// A recorded sweep of 2 exposures (1 and 2 ms) stops at Fit, saying why, before anything is
// written.
TEST(Wizard, TwoExposureSweepStopsAtFitWithTheReason) {
  ProfileHome home;
  test::TempDir tmp;
  {
    sim::SyntheticSweepOptions o;
    o.width = 96;
    o.height = 72;
    sim::SyntheticSweepCamera cam(o);
    cam.SetAutomatic(false, false);
    io::SequenceWriter::Options wo;
    wo.write_groundtruth = false;
    wo.write_depth = false;
    io::SequenceWriter w(tmp / "two", cam.sensor(), wo);
    int k = 0;
    for (double t : {1.0, 2.0})
      for (int r = 0; r < 3; ++r) {
        cam.SetExposure(t);
        w.Add(0.1 * ++k, cam.Grab(), nullptr, t, std::nullopt, nullptr);
      }
  }
  WizardSettings s;
  s.source = QString::fromStdString((tmp / "two").string());
  const test::AutomaticRun run = test::RunWizardAutomatic(s);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_TRUE(run.reason.contains("at least 3")) << run.reason.toStdString();
  EXPECT_FALSE(fs::exists(sensors::ProfileFolder()));
}

template <class T>
T* Find(QWidget& w, const char* name) {
  T* t = w.findChild<T*>(name);
  EXPECT_NE(t, nullptr) << name;
  return t;
}

// Every page by hand, as an operator uses them.
TEST(Wizard, PagesDrivenByHand) {
  ProfileHome home;
  test::TempDir tmp;
  CalibrationWizard w(WizardSettings{});
  w.show();
  ASSERT_EQ(w.currentId(), CalibrationWizard::kSource);
  // Source: a folder that is not a sweep is refused with its name; the synthetic sensor opens.
  Find<QRadioButton>(w, "source_folder")->setChecked(true);
  Find<QLineEdit>(w, "source_folder_edit")->setText("/nonexistent/sweep");
  w.next();
  EXPECT_EQ(w.currentId(), CalibrationWizard::kSource);
  QLabel* err = Find<QLabel>(w, "source_error");
  EXPECT_TRUE(err->text().contains("/nonexistent/sweep")) << err->text().toStdString();
  Find<QRadioButton>(w, "source_synthetic")->setChecked(true);
  auto* response = Find<QComboBox>(w, "source_response");
  response->setCurrentIndex(response->findData("gamma2.2"));
  w.next();
  ASSERT_EQ(w.currentId(), CalibrationWizard::kSetup);
  // Set-up: auto exposure left on is refused, and locking it is the way back.
  QCheckBox* ae = Find<QCheckBox>(w, "setup_lock_ae");
  ae->setChecked(false);
  EXPECT_TRUE(Find<QLabel>(w, "setup_lock_state")->text().contains("auto exposure <b>on</b>"));
  Find<QSpinBox>(w, "setup_repeats")->setValue(4);
  QTest::mouseClick(Find<QPushButton>(w, "setup_plan"), Qt::LeftButton);
  QLabel* problem = Find<QLabel>(w, "setup_problem");
  ASSERT_TRUE(WaitFor([&] { return !w.busy() && !problem->text().isEmpty(); }));
  EXPECT_TRUE(problem->text().contains("auto exposure is on")) << problem->text().toStdString();
  EXPECT_FALSE(w.currentPage()->isComplete());
  DocsShot(w, "wizard_setup_auto_exposure_on");
  ae->setChecked(true);
  QTest::mouseClick(Find<QPushButton>(w, "setup_plan"), Qt::LeftButton);
  ASSERT_TRUE(WaitFor([&] { return w.currentPage()->isComplete(); }));
  EXPECT_TRUE(Find<QLabel>(w, "setup_plan_label")->text().contains("exposures from"));
  auto* hist = Find<PlotWidget>(w, "setup_histogram");
  EXPECT_EQ(hist->series().size(), 3u);
  w.next();
  ASSERT_EQ(w.currentId(), CalibrationWizard::kCapture);
  // Capture: cancel keeps what was captured, resume completes it.
  Find<QLineEdit>(w, "capture_folder")->setText(QString::fromStdString((tmp / "sweep").string()));
  QTest::mouseClick(Find<QPushButton>(w, "capture_start"), Qt::LeftButton);
  QTest::mouseClick(Find<QPushButton>(w, "capture_cancel"), Qt::LeftButton);
  ASSERT_TRUE(WaitFor([&] { return !w.busy(); }));
  QPlainTextEdit* log = Find<QPlainTextEdit>(w, "capture_log");
  EXPECT_TRUE(log->toPlainText().contains("Cancelled")) << log->toPlainText().toStdString();
  DocsShot(w, "wizard_capture_cancelled");
  EXPECT_FALSE(w.currentPage()->isComplete());
  QPushButton* resume = Find<QPushButton>(w, "capture_resume");
  ASSERT_TRUE(resume->isEnabled());
  QTest::mouseClick(resume, Qt::LeftButton);
  ASSERT_TRUE(WaitFor([&] { return w.currentPage()->isComplete(); }));
  EXPECT_TRUE(log->toPlainText().contains("Complete")) << log->toPlainText().toStdString();
  w.next();
  ASSERT_EQ(w.currentId(), CalibrationWizard::kFit);
  // Fit: runs on entering; the plots fill.
  ASSERT_TRUE(WaitFor([&] { return w.currentPage()->isComplete(); }));
  EXPECT_EQ(Find<PlotWidget>(w, "plot_response")->series().size(), 3u);
  EXPECT_EQ(Find<PlotWidget>(w, "plot_noise")->series().size(), 6u);
  EXPECT_GT(Find<PlotWidget>(w, "plot_noise")->series()[0].x.size(), 100u);  // measured thresholds
  EXPECT_EQ(Find<PlotWidget>(w, "plot_pcf")->series().size(), 4u);
  EXPECT_EQ(Find<PlotWidget>(w, "plot_residuals")->series().size(), 3u);
  EXPECT_TRUE(Find<QLabel>(w, "fit_summary")->text().contains("debevec"));
  w.next();
  ASSERT_EQ(w.currentId(), CalibrationWizard::kValidate);
  EXPECT_TRUE(Find<QLabel>(w, "validate_verdict")->text().contains("Good"))
      << Find<QLabel>(w, "validate_verdict")->text().toStdString() << Find<QLabel>(w, "validate_details")->text().toStdString();
  EXPECT_GE(Find<PlotWidget>(w, "plot_consistency")->series().size(), 2u);
  w.next();
  ASSERT_EQ(w.currentId(), CalibrationWizard::kSave);
  // Save: the serial comes from the camera; the profile and report are written.
  EXPECT_EQ(Find<QLineEdit>(w, "save_serial")->text(), "HDRF-SYNTHETIC");
  Find<QLineEdit>(w, "save_report")->setText(QString::fromStdString((tmp / "report").string()));
  EXPECT_FALSE(w.currentPage()->isComplete());
  QTest::mouseClick(Find<QPushButton>(w, "save_run"), Qt::LeftButton);
  EXPECT_TRUE(w.currentPage()->isComplete());
  EXPECT_TRUE(fs::exists(sensors::ProfilePath("HDRF-SYNTHETIC")));
  EXPECT_TRUE(fs::exists(tmp / "report" / "report.html"));
}

}  // namespace
}  // namespace hdrf::wizard

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  QApplication app(argc, argv);
  return RUN_ALL_TESTS();
}
