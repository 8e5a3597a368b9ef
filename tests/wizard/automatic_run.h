// Runs the calibration wizard under its automation switch in a test (offscreen or Xvfb),
// waiting for it to close: its exit code and, when it stopped, the reason it gave.
#pragma once

#include <gtest/gtest.h>

#include <QElapsedTimer>
#include <QTest>

#include "calibration_wizard/calibration_wizard.h"

namespace hdrf::test {

struct AutomaticRun {
  int exit_code = -1;
  QString reason;  // failed()'s message; empty when it saved
};

inline AutomaticRun RunWizardAutomatic(wizard::WizardSettings s, int timeout_ms = 180000) {
  s.automatic = true;
  wizard::CalibrationWizard w(s);
  AutomaticRun run;
  bool finished = false;
  QObject::connect(&w, &wizard::CalibrationWizard::failed, [&](const QString& m) { run.reason = m; });
  QObject::connect(&w, &QDialog::finished, [&] { finished = true; });
  w.show();
  QElapsedTimer t;
  t.start();
  while (!finished && t.elapsed() < timeout_ms) QTest::qWait(20);
  EXPECT_TRUE(finished) << "the automatic run did not finish in " << timeout_ms / 1000 << " s";
  run.exit_code = w.exit_code();
  return run;
}

}  // namespace hdrf::test
