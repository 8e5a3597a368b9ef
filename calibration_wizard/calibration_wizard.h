// The calibration wizard (docs/calibration_wizard.md): Source, Set-up, Capture, Fit,
// Validate, Save. Guides a technician from a camera (live, or the synthetic sensor) or a
// recorded sweep folder to a sensor profile stored for the device's serial and a report.
// Opened from the studio's Tools menu and as its own program (hdrfusion-calibration-wizard);
// every step is also a command (capture-sweep, calibrate). Long work (planning, capture,
// fit) runs on a worker thread; the pages show its progress and can cancel it.
#pragma once

#include <QString>
#include <QWizard>
#include <atomic>
#include <filesystem>
#include <memory>
#include <optional>

#include "io/sweep_capture.h"
#include "radiometry/calibration_job.h"
#include "radiometry/sweep_camera.h"

class QThread;

namespace hdrf::wizard {

struct WizardSettings {
  // Run every page with its defaults, save, and close (tests, documentation): the wizard's
  // automation switch. A page that cannot go on emits failed() and the wizard closes.
  bool automatic = false;
  // Preselected source: "synthetic[:...]", "openni:[...]" (sensors/sweep_cameras.h) or a
  // recorded sweep folder. Empty: the synthetic sensor, or the first camera when one is
  // connected.
  QString source;
  QString sweep_folder;   // Capture's folder (default ~/HDRFusion/sweeps/sweep-DATE)
  QString report_folder;  // Save's report folder (default ~/HDRFusion/calibrations/SERIAL-DATE)
  QString screenshots;    // folder: each page saved as NN-page.png once its work is done
  io::SweepPlanOptions plan;
  QString method = "debevec";
  QString emor_basis;     // invemor.txt, for the EMoR method
};

// What the pages share.
struct WizardState {
  std::unique_ptr<radiometry::SweepCamera> camera;
  std::optional<io::SweepPlan> plan;
  std::filesystem::path sweep_folder;
  std::optional<radiometry::Sweep> sweep;
  SensorInfo sweep_sensor;  // the camera's (or the sweep's sensor.json), no response
  std::optional<radiometry::CalibrationOutcome> outcome;
  std::filesystem::path profile, report;
};

class CalibrationWizard : public QWizard {
  Q_OBJECT
 public:
  enum PageId { kSource, kSetup, kCapture, kFit, kValidate, kSave };
  explicit CalibrationWizard(WizardSettings options, QWidget* parent = nullptr);
  ~CalibrationWizard() override;

  const WizardSettings& settings() const { return options_; }
  WizardState& state() { return state_; }
  // Runs `work` on a worker thread (one at a time), then `done` on this thread with the
  // error message ("" on success). False when a task is running already.
  bool RunTask(std::function<void()> work, std::function<void(const QString& error)> done);
  bool busy() const { return worker_ != nullptr; }
  std::atomic<bool>& cancel_flag() { return cancel_; }
  // Automatic runs: saves the page's screenshot (if asked), then moves on.
  void PageDone(const QString& name);
  void Fail(const QString& message);
  int exit_code() const { return exit_code_; }

 signals:
  void failed(const QString& message);
  void saved(const QString& profile, const QString& report);

 private:
  WizardSettings options_;
  WizardState state_;
  QThread* worker_ = nullptr;
  std::atomic<bool> cancel_{false};
  int exit_code_ = 0;
};

}  // namespace hdrf::wizard
