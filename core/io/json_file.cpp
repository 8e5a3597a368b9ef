#include "io/json_file.h"

#include "common/error.h"
#include "common/input_file.h"

namespace hdrf::io {

nlohmann::json ReadJsonFile(const std::filesystem::path& file) {
  const std::string text = ReadInputFile(file, kMaxTextBytes, "a JSON file");
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.what() carries "line L, column C"; keep the part after the library's prefix.
    const std::string msg = e.what();
    const auto pos = msg.find("parse error");
    throw InputError(file, "is not valid JSON (" + msg.substr(pos == std::string::npos ? 0 : pos) + ")");
  } catch (const nlohmann::json::exception& e) {
    // Numbers beyond a double's range ("1e400") are not a syntax error but cannot be read.
    const std::string msg = e.what();
    const auto pos = msg.find("] ");
    throw InputError(file, "cannot be read as JSON (" + msg.substr(pos == std::string::npos ? 0 : pos + 2) + ")");
  }
}

}  // namespace hdrf::io
