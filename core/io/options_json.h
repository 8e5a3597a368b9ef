// The engine's settings in a JSON file (`scan --options FILE`), the same struct the flags
// and the studio fill. Every key is optional; unknown keys are refused (a typo would
// otherwise silently do nothing), naming the file and the key.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "pipeline/pipeline.h"

namespace hdrf::io {

void ReadPipelineOptions(const std::filesystem::path& file, pipeline::PipelineOptions& options);
// The same from a JSON value held inside `file` (project files).
void ApplyPipelineOptionsJson(const std::filesystem::path& file, const nlohmann::json& j,
                              pipeline::PipelineOptions& options);
std::string PipelineOptionsToJson(const pipeline::PipelineOptions& options);

}  // namespace hdrf::io
