#include "io/sweep.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "common/error.h"
#include "common/message.h"
#include "io/image_io.h"
#include "io/sequence.h"

namespace hdrf::io {

radiometry::Sweep ReadSweep(const std::filesystem::path& folder) {
  SequenceReadOptions o;
  o.allow_missing_depth = true;
  const SequenceReader seq(folder, o);
  if (!seq.has_exposure())
    throw InputError(folder / "exposure.txt",
                     "file is missing: an exposure sweep needs the exposure of every frame");
  // An analog gain multiplies the signal as the exposure time does, in units only the device
  // knows: a sweep whose gain changes (exposure x gain held constant, say) would be fitted as
  // if only the time had changed, 30-50 % off and judged good. Only a gain held fixed (or none
  // given) is taken; it then cancels out.
  const std::vector<FrameInfo>& frames = seq.frames();
  const auto with_gain = std::count_if(frames.begin(), frames.end(), [](const FrameInfo& f) { return f.gain.has_value(); });
  if (with_gain > 0 && std::size_t(with_gain) < frames.size())
    throw InputError(folder / "exposure.txt", "gives the analog gain for " + std::to_string(with_gain) + " of " +
                                                  std::to_string(frames.size()) +
                                                  " frames: a sweep gives it for every frame or for none");
  if (with_gain > 0) {
    const auto [lo, hi] = std::minmax_element(frames.begin(), frames.end(),
                                              [](const FrameInfo& a, const FrameInfo& b) { return *a.gain < *b.gain; });
    if (*hi->gain > *lo->gain * (1 + 1e-9))
      throw InputError(folder / "exposure.txt",
                       "the analog gain changes across the sweep (" + Num(*lo->gain, 3) + " to " + Num(*hi->gain, 3) +
                           "): a calibration sweep changes only the exposure time; capture it again with the gain "
                           "fixed");
  }
  radiometry::Sweep s;
  s.source = folder.string();
  for (const FrameInfo& f : frames) {
    if (!f.exposure_ms) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.6f", f.timestamp);
      throw InputError(folder / "exposure.txt",
                       std::string("no exposure for colour frame at timestamp ") + buf);
    }
    // The size is checked from the header, before a frame is decoded (and again after).
    const PinholeCamera& cam = seq.sensor().camera;
    s.images.push_back(ReadColorImage(f.color_path, ExpectSize(f.color_path, cam.width, cam.height)));
    s.exposure_ms.push_back(*f.exposure_ms);
  }
  return s;
}

}  // namespace hdrf::io
