// SOURCE arguments of `scan` and of the studio's --source: a sequence folder, or
// "synthetic:" with comma-separated settings, e.g.
//   synthetic:                      the built-in room, 300 frames, 320x240, smooth AE
//   synthetic:scene=desk,seed=3,frames=600,ae=flicker,size=640x480
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "pipeline/frame_source.h"

namespace hdrf::io {

// `response` is "" or "srgb" (the fallback for sequences without a calibrated response).
std::unique_ptr<pipeline::FrameSource> OpenSource(const std::string& spec, const std::string& response);

// The "key=value,key=value" settings after a spec's "name:" (`from`: where they start);
// empty items are skipped. Throws SettingError naming SOURCE and the item that is not
// key=value, with `example` (a spec of this kind that works) where one is given. Used by
// every spec: synthetic:, openni:, and the sweep cameras.
std::vector<std::pair<std::string, std::string>> SplitSpec(const std::string& spec, std::size_t from,
                                                           const std::string& example = "");

// "WIDTHxHEIGHT" (throws SettingError naming --size).
void ParseSize(const std::string& s, int* w, int* h);

}  // namespace hdrf::io
