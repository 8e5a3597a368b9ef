// Errors that a user can act on: every message names the file, line or setting at fault.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace hdrf {

// `text` made safe for a terminal or a log: control characters (C0, DEL, C1), which input
// files can carry into messages (a file name, a quoted field), and bytes that are not UTF-8
// are written as \xNN; everything else, backslashes included, is kept as it was.
std::string Printable(std::string_view text);

// Thrown for bad configuration and bad input. what() is a complete, one-line sentence, with
// no control characters (Printable).
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(Printable(message)) {}
};

// "<file>: <what>" or "<file>:<line>: <what>" (line is 1-based; 0 means no line).
std::string FormatInputMessage(const std::filesystem::path& file, int line, const std::string& what);

// Bad input found in a file: names the file and, where known, the line.
class InputError : public Error {
 public:
  InputError(const std::filesystem::path& file, int line, const std::string& what)
      : Error(FormatInputMessage(file, line, what)), file_(file), line_(line) {}
  InputError(const std::filesystem::path& file, const std::string& what)
      : InputError(file, 0, what) {}
  const std::filesystem::path& file() const { return file_; }
  int line() const { return line_; }

 private:
  std::filesystem::path file_;
  int line_;
};

// A setting that cannot work, named as the user wrote it (e.g. "--voxel-size").
class SettingError : public Error {
 public:
  SettingError(const std::string& setting, const std::string& what)
      : Error("setting '" + setting + "': " + what) {}
};

// Long work stopped because the user asked (a progress callback said so).
class Cancelled : public Error {
 public:
  Cancelled() : Error("cancelled") {}
  explicit Cancelled(const std::string& what) : Error(what) {}  // what was kept, and where
};

}  // namespace hdrf
