// The plots of a calibration, filled from its outcome: shown on the wizard's Fit and
// Validate pages and written into its report.
#pragma once

#include "calibration_wizard/plot_widget.h"
#include "radiometry/calibration_job.h"

namespace hdrf::wizard {

void ShowResponse(PlotWidget& plot, const radiometry::CalibrationOutcome& out);    // f^-1 per channel
void ShowDerivative(PlotWidget& plot, const radiometry::CalibrationOutcome& out);  // f' per channel
void ShowNoise(PlotWidget& plot, const radiometry::CalibrationOutcome& out);       // Var R, measured and fitted
void ShowPcf(PlotWidget& plot, const radiometry::CalibrationOutcome& out);         // p0..p3 (green)
void ShowResiduals(PlotWidget& plot, const radiometry::CalibrationOutcome& out);   // stops per level
void ShowConsistency(PlotWidget& plot, const radiometry::CalibrationOutcome& out,
                     const radiometry::CheckLimits& limits = {});                  // stops per exposure

}  // namespace hdrf::wizard
