// hdrfusion bench --suite export: the textured export of a scanned room, stage by stage.
#pragma once

#include <string>

namespace hdrf::cli {

// Scans the built-in room (`frames` frames at 320x240) or takes the scan folder `scan`, then
// exports it at 2 mm per texel and into a 4096^2 texture, timing each stage.
int BenchExport(int frames, const std::string& scan);

}  // namespace hdrf::cli
