// Whitespace-separated text tables with '#' comments: the shape of every TUM-style file.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace hdrf::io {

struct TextRow {
  int line = 0;                     // 1-based line number in the file
  std::vector<std::string> fields;  // whitespace-separated tokens
};

// Reads all non-empty, non-comment lines. Throws InputError if the file cannot be opened.
std::vector<TextRow> ReadTextTable(const std::filesystem::path& file);

// Parses a finite number; throws InputError naming the file, line and field otherwise.
double ParseNumber(const std::filesystem::path& file, const TextRow& row, std::size_t field,
                   const char* what);

}  // namespace hdrf::io
