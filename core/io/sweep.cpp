#include "io/sweep.h"

#include <cstdio>

#include "common/error.h"
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
  radiometry::Sweep s;
  s.source = folder.string();
  for (const FrameInfo& f : seq.frames()) {
    if (!f.exposure_ms) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.6f", f.timestamp);
      throw InputError(folder / "exposure.txt",
                       std::string("no exposure for colour frame at timestamp ") + buf);
    }
    s.images.push_back(ReadColorImage(f.color_path));
    const auto& im = s.images.back();
    if (im.width() != seq.sensor().camera.width || im.height() != seq.sensor().camera.height)
      throw InputError(f.color_path, "image size does not match sensor.json");
    s.exposure_ms.push_back(*f.exposure_ms);
  }
  return s;
}

}  // namespace hdrf::io
