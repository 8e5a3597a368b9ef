#include "sim/sweep_simulator.h"

#include <cmath>

#include "sim/synthetic_source.h"

namespace hdrf::sim {

radiometry::Sweep SimulateSweep(const radiometry::InverseResponse& truth,
                                const radiometry::NoiseModel& noise, int repeats, int width,
                                int height, const std::string& scene) {
  SimOptions o;
  o.scene = scene;
  o.width = width;
  o.height = height;
  o.sweep = true;
  o.sweep_exposures_ms.clear();
  for (int k = 0; k <= 18; ++k) o.sweep_exposures_ms.push_back(0.25 * std::pow(2.0, k / 2.0));
  o.sweep_repeats = repeats;
  o.response = truth;
  o.noise = noise;
  SyntheticSource src(o);
  radiometry::Sweep s;
  s.source = "simulated sweep";
  while (!src.done()) {
    SimFrame f = src.Next();
    s.images.push_back(std::move(f.color));
    s.exposure_ms.push_back(f.exposure_ms);
  }
  return s;
}

}  // namespace hdrf::sim
