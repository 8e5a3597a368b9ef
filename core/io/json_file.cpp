#include "io/json_file.h"

#include <fstream>

#include "common/error.h"

namespace hdrf::io {

nlohmann::json ReadJsonFile(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in)
    throw InputError(file, std::filesystem::exists(file) ? "cannot be opened for reading" : "file is missing");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    // e.what() carries "line L, column C"; keep the part after the library's prefix.
    const std::string msg = e.what();
    const auto pos = msg.find("parse error");
    throw InputError(file, "is not valid JSON (" + msg.substr(pos == std::string::npos ? 0 : pos) + ")");
  }
}

}  // namespace hdrf::io
