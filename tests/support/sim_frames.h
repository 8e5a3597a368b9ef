// Helpers shared by the module tests: simulated frames, depth in metres, medians.
#pragma once

#include <algorithm>
#include <vector>

#include "common/image.h"
#include "pipeline/pipeline.h"
#include "sim/synthetic_source.h"

namespace hdrf::test {

inline double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// n frames of the default synthetic room with the given auto exposure (a list of exposures
// for kList); exact depth when asked (no sensor noise).
inline std::vector<sim::SimFrame> Frames(int n, sim::AeMode ae, bool exact_depth = false,
                                         std::vector<double> list = {}) {
  sim::SimOptions o;
  o.frames = n;
  o.ae.mode = ae;
  o.ae.list_ms = list;
  o.depth.enabled = !exact_depth;
  sim::SyntheticSource src(o);
  std::vector<sim::SimFrame> out;
  while (!src.done()) out.push_back(src.Next());
  return out;
}

// Raw synthetic depth (units of 1/5000 m) in metres.
inline DepthImage Metres(const DepthRawImage& raw) {
  DepthImage d(raw.width(), raw.height());
  for (std::size_t i = 0; i < raw.size(); ++i) d[i] = raw[i] / 5000.f;
  return d;
}

// A simulated frame as the engine takes it (colour, depth in metres, time).
inline pipeline::FrameInput AsInput(const sim::SimFrame& f) {
  pipeline::FrameInput in;
  in.color = f.color.Clone();
  in.depth_m = Metres(f.depth);
  in.timestamp = f.timestamp;
  return in;
}

}  // namespace hdrf::test
