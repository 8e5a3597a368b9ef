// Reading a JSON file with errors that name the file (and the line, for syntax errors).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

namespace hdrf::io {

// Throws InputError: missing/unreadable file, or "is not valid JSON (... line L, column C)".
nlohmann::json ReadJsonFile(const std::filesystem::path& file);

}  // namespace hdrf::io
