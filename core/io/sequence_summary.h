// What `hdrfusion info` reports about a sequence.
#pragma once

#include <optional>
#include <string>

#include "io/sequence.h"

namespace hdrf::io {

struct SequenceSummary {
  std::size_t frames = 0;
  std::size_t unmatched_color_frames = 0;
  double duration_s = 0;
  double rate_hz = 0;
  int width = 0, height = 0;
  std::optional<double> exposure_min_ms, exposure_max_ms;
  std::size_t frames_with_exposure = 0;
  double depth_coverage = 0;      // share of valid depth pixels over the sampled frames
  double depth_min_m = 0, depth_max_m = 0;
  std::size_t depth_frames_sampled = 0;
  std::size_t frames_with_groundtruth = 0;
  bool has_response = false;
  bool has_noise = false;
  bool has_hdr = false;

  std::string ToText(const std::string& name) const;
};

// Reads the sequence's metadata and up to `depth_samples` depth frames, evenly spread.
SequenceSummary Summarize(const SequenceReader& seq, std::size_t depth_samples = 30);

}  // namespace hdrf::io
