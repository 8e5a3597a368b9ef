#include "io/text_table.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/input_file.h"

namespace hdrf::io {

std::vector<TextRow> ReadTextTable(const std::filesystem::path& file) {
  std::istringstream in(ReadInputFile(file, kMaxTextBytes, "a text table"));
  std::vector<TextRow> rows;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    std::istringstream ss(text);
    TextRow row{line, {}};
    std::string tok;
    while (ss >> tok) row.fields.push_back(tok);
    if (row.fields.empty() || row.fields[0][0] == '#') continue;
    rows.push_back(std::move(row));
  }
  return rows;
}

double ParseNumber(const std::filesystem::path& file, const TextRow& row, std::size_t field,
                   const char* what) {
  if (field >= row.fields.size())
    throw InputError(file, row.line,
                     std::string("line is truncated: missing ") + what + " (field " +
                         std::to_string(field + 1) + ")");
  const std::string& s = row.fields[field];
  double v = 0;
  const char* first = s.data();
  if (*first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size())
    throw InputError(file, row.line, std::string("cannot parse ") + what + " '" + s + "'");
  if (!std::isfinite(v))
    throw InputError(file, row.line, std::string(what) + " is not a finite number ('" + s + "')");
  return v;
}

}  // namespace hdrf::io
