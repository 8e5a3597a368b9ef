// The engine's settings as command-line flags, generated from the settings registry
// (pipeline/settings.h): `--<key> VALUE` for every setting, plus its short alias where it
// has one (`--voxel`). Values are checked by the registry, which names the key.
#pragma once

#include <CLI/CLI.hpp>
#include <deque>
#include <string>
#include <vector>

#include "pipeline/settings.h"

namespace hdrf::cli {

class SettingFlags {
 public:
  // Adds the flags to `cmd`, in an option group of their own.
  explicit SettingFlags(CLI::App* cmd);
  // Sets every setting given on the command line, in registry order; throws SettingError.
  void Apply(pipeline::PipelineOptions& options) const;

 private:
  struct Flag {
    const pipeline::Setting* setting;
    CLI::Option* option;
    std::string value;
  };
  std::deque<Flag> flags_;  // stable addresses: CLI11 writes into `value`
  // Flags of settings that were removed (pipeline::RetiredSetting): refused with the reason.
  std::deque<std::pair<CLI::Option*, std::string>> retired_;
  std::string retired_value_;
};

}  // namespace hdrf::cli
