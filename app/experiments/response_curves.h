// Measured camera responses used as ground truth by the experiments and the calibration
// tests: Grossberg & Nayar's DoRF curves and TUM-monoVO / DSO pcalib files.
#pragma once

#include <array>
#include <filesystem>
#include <vector>

#include "radiometry/response.h"

namespace hdrf::experiments {

// dorf_invI_201x1024.txt: one inverse response per line (irradiance at brightness
// B = j / 1023, 1024 values rising from 0 to 1); '#' lines are comments. Throws InputError
// naming the file and line for a missing file, a short row or a non-finite value.
std::vector<std::vector<double>> LoadDorfInverseCurves(const std::filesystem::path& file);

// A TUM-monoVO / DSO pcalib.txt (256 numbers, the inverse response of an 8-bit camera), as
// the same curve in all three channels scaled so that f^-1(128) = 1. Throws InputError naming
// the file for a missing file, a value that is not a number, or a count other than 256.
radiometry::InverseResponse LoadPcalibResponse(const std::filesystem::path& file);

// A 256-level inverse response from sampled curves (one per channel, any length >= 2),
// linearly interpolated at B = i / 255, scaled so that f^-1(128) = 1. A ramp of 1e-4 of the range
// keeps flat runs of the measured table strictly increasing.
radiometry::InverseResponse InverseFromCurves(const std::array<const std::vector<double>*, 3>& curves);

}  // namespace hdrf::experiments
