// SOURCE arguments of `scan` and of the studio's --source: a sequence folder, or
// "synthetic:" with comma-separated settings, e.g.
//   synthetic:                      the built-in room, 300 frames, 320x240, smooth AE
//   synthetic:scene=desk,seed=3,frames=600,ae=flicker,size=640x480
#pragma once

#include <memory>
#include <string>

#include "pipeline/frame_source.h"

namespace hdrf::io {

// `response` is "" or "srgb" (the fallback for sequences without a calibrated response).
std::unique_ptr<pipeline::FrameSource> OpenSource(const std::string& spec, const std::string& response);

// "WIDTHxHEIGHT" (throws SettingError naming --size).
void ParseSize(const std::string& s, int* w, int* h);

}  // namespace hdrf::io
