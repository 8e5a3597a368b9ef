// hdrfusion bench --suite tonemap: the tone-mapping operators beside Debian's pfstmo (run
// as programs, timed in the same run) at 640x480.
#pragma once

#include <string>
#include <vector>

namespace hdrf::cli {

// Images: OpenEXR files (resampled to 640x480); empty takes the shared data's hdr_images.
int BenchTonemap(int frames, std::vector<std::string> images);

}  // namespace hdrf::cli
