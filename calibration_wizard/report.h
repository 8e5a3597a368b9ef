// The calibration report: the plots as PNG and one HTML page with the figures (sweep,
// method, residuals, noise, verdict and its reasons), beside a copy of the saved profile.
#pragma once

#include <QString>
#include <filesystem>

#include "calibration_wizard/calibration_wizard.h"

namespace hdrf::wizard {

// Writes report.html, response.png, derivative.png, noise.png, pcf.png, residuals.png,
// consistency.png and sensor.json into `folder` (created). Returns report.html. Throws
// InputError naming the file that could not be written.
std::filesystem::path WriteReport(const std::filesystem::path& folder, const WizardState& state,
                                  const QString& source, const SensorInfo& profile);

}  // namespace hdrf::wizard
