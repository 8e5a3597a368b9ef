#include "io/sequence_summary.h"

#include <algorithm>
#include <cstdio>
#include <limits>

namespace hdrf::io {

SequenceSummary Summarize(const SequenceReader& seq, std::size_t depth_samples) {
  SequenceSummary s;
  const auto& frames = seq.frames();
  s.frames = frames.size();
  s.unmatched_color_frames = seq.unmatched_color_frames();
  s.width = seq.sensor().camera.width;
  s.height = seq.sensor().camera.height;
  s.duration_s = frames.back().timestamp - frames.front().timestamp;
  s.rate_hz = s.duration_s > 0 ? double(frames.size() - 1) / s.duration_s : 0;
  for (const auto& f : frames) {
    if (f.exposure_ms) {
      ++s.frames_with_exposure;
      s.exposure_min_ms = std::min(s.exposure_min_ms.value_or(*f.exposure_ms), *f.exposure_ms);
      s.exposure_max_ms = std::max(s.exposure_max_ms.value_or(*f.exposure_ms), *f.exposure_ms);
    }
    if (f.T_world_camera) ++s.frames_with_groundtruth;
  }
  s.has_response = seq.sensor().response.has_value();
  s.has_noise = seq.sensor().noise.has_value();
  s.has_hdr = seq.has_hdr();

  std::vector<std::size_t> with_depth;
  for (std::size_t i = 0; i < frames.size(); ++i)
    if (!frames[i].depth_path.empty()) with_depth.push_back(i);
  const std::size_t n = std::min(depth_samples, with_depth.size());
  std::size_t valid = 0, total = 0;
  float lo = std::numeric_limits<float>::max(), hi = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = with_depth[n == 1 ? 0 : k * (with_depth.size() - 1) / (n - 1)];
    const Frame f = seq.ReadFrame(i);
    for (std::size_t p = 0; p < f.depth_m.size(); ++p) {
      const float d = f.depth_m[p];
      if (d > 0) {
        ++valid;
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
    }
    total += f.depth_m.size();
  }
  s.depth_frames_sampled = n;
  s.depth_coverage = total ? double(valid) / double(total) : 0;
  if (valid) {
    s.depth_min_m = lo;
    s.depth_max_m = hi;
  }
  return s;
}

std::string SequenceSummary::ToText(const std::string& name) const {
  char buf[4096];
  std::string out;
  auto line = [&](const char* fmt, auto... args) {
    std::snprintf(buf, sizeof buf, fmt, args...);
    out += buf;
  };
  line("sequence      %s\n", name.c_str());
  line("frames        %zu", frames);
  if (unmatched_color_frames) line(" (%zu colour frames without depth left out)", unmatched_color_frames);
  line("\nduration      %.3f s (%.2f Hz)\n", duration_s, rate_hz);
  line("resolution    %dx%d\n", width, height);
  if (exposure_min_ms)
    line("exposure      %.4g .. %.4g ms (%zu of %zu frames; ratio %.1f)\n", *exposure_min_ms,
         *exposure_max_ms, frames_with_exposure, frames, *exposure_max_ms / *exposure_min_ms);
  else
    line("exposure      not reported (no exposure.txt)\n");
  if (depth_frames_sampled)
    line("depth         %.1f %% valid pixels, %.3f .. %.3f m (%zu frames sampled)\n",
         100.0 * depth_coverage, depth_min_m, depth_max_m, depth_frames_sampled);
  else
    line("depth         none\n");
  line("ground truth  %s", frames_with_groundtruth ? "yes" : "no");
  if (frames_with_groundtruth) line(" (%zu of %zu frames)", frames_with_groundtruth, frames);
  line("\nresponse      %s\n", has_response ? "calibrated (sensor.json response.inverse)" : "none");
  line("noise         %s\n", has_noise ? "calibrated (sensor.json noise)" : "none");
  line("hdr radiance  %s\n", has_hdr ? "yes (hdr/*.exr for every frame)" : "no");
  return out;
}

}  // namespace hdrf::io
