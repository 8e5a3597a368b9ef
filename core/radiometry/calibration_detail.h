// Internal to the calibration methods (debevec.cpp, robertson.cpp, emor.cpp,
// thresholds.cpp, merge.cpp): grouping a sweep by exposure, sampling pixels, the hat weight,
// the common last step of a response fit, and the threshold refinement.
#pragma once

#include <cstdint>
#include <vector>

#include "radiometry/calibration.h"

namespace hdrf::radiometry::detail {

inline std::uint8_t Level(const Rgb8& p, int c) { return c == 0 ? p.r : (c == 1 ? p.g : p.b); }
inline bool Clipped(int z, ClipLevels clip) { return z < clip.lo || z > clip.hi; }

// Debevec's hat weight, zero where clipped, with a floor of 20 % of its peak so that the
// data (not the smoothness prior) shapes steep knees near saturation.
inline double Hat(int z, ClipLevels clip) {
  if (Clipped(z, clip)) return 0;
  const double hat = z <= 127 ? double(z - clip.lo + 1) : double(clip.hi - z + 1);
  return hat > 25.0 ? hat : 25.0;
}

struct Groups {
  std::vector<double> exposure;           // distinct, ascending
  std::vector<std::vector<int>> images;   // image indices per exposure
};
Groups GroupByExposure(const Sweep& s);

// Pixel locations for fitting, stratified by the level of a middle exposure so that dark
// and bright parts of the curve both get samples; only pixels unclipped in >= 2 exposures.
std::vector<std::size_t> SamplePixels(const Sweep& s, const Groups& g, int c, int count, ClipLevels clip);

// Monotonic, f^-1(128) = 1, and the fit's residual figures.
ResponseFit Finish(ResponseFit fit, const Sweep& s, const Groups& g, ClipLevels clip);

// The noise-aware last step of Debevec and Robertson (thresholds.cpp): each level moved to
// the midpoint of its two probit-fitted thresholds, `passes` times.
void RefineOnThresholds(const Sweep& s, const Groups& g, InverseResponse& inv, int passes, ClipLevels clip);

}  // namespace hdrf::radiometry::detail
