// The engine's settings registry: every field of PipelineOptions declared once, with its
// key, type, range, default, unit and one line of help. The CLI's flags (`--<key>`), the
// settings files (io/options_json), and the studio's settings form and saved settings are
// all generated from this list, and every message names a setting by its key.
//
// Adding a setting: a field with its default in the module's options struct, its check in
// that struct's Check(), one entry in Settings() and its words (label and advice) in
// kWords (settings.cpp); a test fails for a setting without them.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "pipeline/options.h"

namespace hdrf::pipeline {

enum class SettingKind {
  kInt,      // whole number in [min, max]
  kReal,     // number in [min, max]
  kBool,     // true / false
  kChoice,   // one of `choices`
  kIntList,  // 1..max_items whole numbers, each in [min, max], comma-separated as text
};

struct Setting {
  std::string key;    // "volume.voxel_m": section and field, the name used everywhere
  std::string alias;  // a short CLI spelling kept for scripts ("--voxel"), or ""
  SettingKind kind = SettingKind::kReal;
  double min = 0, max = 0;           // kInt, kReal, kIntList: inclusive range
  int max_items = 1;                 // kIntList
  std::vector<std::string> choices;  // kChoice
  std::string unit;                  // "m", "px", "deg", "MiB", "voxels"; "" for none
  std::string label;                 // plain words for forms ("Voxel size")
  std::string help;                  // one line: what it does
  std::string advice;                // one line: when to change it
  bool expert = false;               // shown in the studio's expert section only

  // The value as text: numbers in full precision, booleans as true/false, lists as "1,2,3".
  std::function<std::string(const PipelineOptions&)> get;
  // Parses `text`, checks the type and the range and sets the field; throws SettingError
  // naming the key and what is wrong. Cross-field checks are PipelineOptions::Check's.
  std::function<void(PipelineOptions&, const std::string&)> set;

  std::string Default() const { return get(PipelineOptions{}); }
  std::string Range() const;  // "8 .. 4096 voxels", "one of nr, nr+icp, icp, intensity"
};

// Every setting, in the order the help and the forms list them.
const std::vector<Setting>& Settings();
// The setting with this key; throws SettingError ("unknown setting") for any other.
// Why a setting of an earlier version is gone and what replaces it ("" for any other key).
std::string RetiredSetting(const std::string& key);
const Setting& FindSetting(const std::string& key);

}  // namespace hdrf::pipeline
