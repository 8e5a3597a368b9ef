// Simulated exposure sweeps: a static camera looking at a built-in scene through a known
// response and noise, for calibration tests, demos and the experiments.
#pragma once

#include <string>

#include "radiometry/calibration.h"

namespace hdrf::sim {

// The sensor noise of the calibration tests and `hdrfusion-experiments calibration`: a consumer
// sensor at base gain, in units of f^-1(128) = 1.
inline const radiometry::NoiseModel kSweepNoise{{0.030f, 0.025f, 0.035f}, {0.020f, 0.015f, 0.025f}};

// A static-camera exposure sweep of a built-in synthetic scene ("room" or "desk") through
// `truth`: half-stop exposures from 0.25 to 128 ms (19), `repeats` frames each.
radiometry::Sweep SimulateSweep(const radiometry::InverseResponse& truth,
                                const radiometry::NoiseModel& noise, int repeats = 2,
                                int width = 160, int height = 120,
                                const std::string& scene = "room");

}  // namespace hdrf::sim
