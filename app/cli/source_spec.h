// SOURCE arguments of `scan` (and later the studio's --source): a sequence folder, or
// "synthetic:" with comma-separated settings, e.g.
//   synthetic:                      the built-in room, 300 frames, 320x240, smooth AE
//   synthetic:scene=desk,seed=3,frames=600,ae=flicker,size=640x480
#pragma once

#include <memory>
#include <string>

#include "pipeline/frame_source.h"

namespace hdrf::cli {

// `response` is "" or "srgb" (the fallback for sequences without a calibrated response).
std::unique_ptr<pipeline::FrameSource> OpenSource(const std::string& spec, const std::string& response);

}  // namespace hdrf::cli
