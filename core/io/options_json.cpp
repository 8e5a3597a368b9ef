#include "io/options_json.h"

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "io/json_file.h"
#include "pipeline/settings.h"

namespace hdrf::io {

using nlohmann::json;
using pipeline::Setting;
using pipeline::SettingKind;

namespace {

// A JSON value of the setting's type, as the registry's text; throws naming the key.
std::string ValueText(const std::filesystem::path& file, const Setting& s, const json& v) {
  auto wrong = [&](const char* expected) {
    const std::string range = s.Range();
    return InputError(file, "'" + s.key + "' must be " + expected + (range == expected ? "" : " (" + range + ")") +
                                ", found " + v.dump());
  };
  switch (s.kind) {
    case SettingKind::kBool:
      if (!v.is_boolean()) throw wrong("true or false");
      return v.get<bool>() ? "true" : "false";
    case SettingKind::kChoice:
      if (!v.is_string()) throw wrong("a string");
      return v.get<std::string>();
    case SettingKind::kInt:
      if (!v.is_number_integer()) throw wrong("a whole number");
      return v.dump();
    case SettingKind::kReal:
      if (!v.is_number()) throw wrong("a number");
      return v.dump();
    case SettingKind::kIntList: {
      if (!v.is_array()) throw wrong("an array of whole numbers");
      std::string t;
      for (std::size_t i = 0; i < v.size(); ++i) {
        if (!v[i].is_number_integer()) throw wrong("an array of whole numbers");
        if (i) t += ',';
        t += v[i].dump();
      }
      return t;
    }
  }
  return v.dump();
}

json TextToJson(const Setting& s, const std::string& text) {
  switch (s.kind) {
    case SettingKind::kBool: return text == "true";
    case SettingKind::kChoice: return text;
    case SettingKind::kInt: return std::stoll(text);
    case SettingKind::kReal: return std::stod(text);
    case SettingKind::kIntList: {
      json a = json::array();
      std::size_t start = 0;
      for (std::size_t k = 0; k <= text.size(); ++k)
        if (k == text.size() || text[k] == ',') a.push_back(std::stoi(text.substr(start, k - start))), start = k + 1;
      return a;
    }
  }
  return text;
}

void Apply(const std::filesystem::path& file, pipeline::PipelineOptions& o, const std::string& key, const json& v) {
  // Files written before the depth section had the bilateral switch at the top level.
  const std::string k = key == "bilateral" ? "depth.bilateral" : key;
  const Setting* s = nullptr;
  for (const Setting& c : pipeline::Settings())
    if (c.key == k) s = &c;
  if (!s) {
    for (const Setting& c : pipeline::Settings())
      if (c.key.rfind(key + ".", 0) == 0)
        throw InputError(file, "'" + key + "' is a section: it must be an object of settings, found " + v.dump());
    if (const std::string why = pipeline::RetiredSetting(k); !why.empty())
      throw InputError(file, "setting '" + k + "' " + why);
    throw InputError(file, "unknown setting '" + key + "'");
  }
  try {
    s->set(o, ValueText(file, *s, v));
  } catch (const InputError&) {
    throw;
  } catch (const Error& e) {
    throw InputError(file, e.what());
  }
}

}  // namespace

void ReadPipelineOptions(const std::filesystem::path& file, pipeline::PipelineOptions& o) {
  ApplyPipelineOptionsJson(file, ReadJsonFile(file), o);
}

void ApplyPipelineOptionsJson(const std::filesystem::path& file, const json& j, pipeline::PipelineOptions& o) {
  if (!j.is_object()) throw InputError(file, "top level must be a JSON object");
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it.value().is_object()) {
      for (auto f = it.value().begin(); f != it.value().end(); ++f) Apply(file, o, it.key() + "." + f.key(), f.value());
    } else {
      Apply(file, o, it.key(), it.value());
    }
  }
  try {
    o.Check();
  } catch (const Error& e) {
    throw InputError(file, e.what());
  }
}

std::string PipelineOptionsToJson(const pipeline::PipelineOptions& o) {
  json j = json::object();
  for (const Setting& s : pipeline::Settings()) {
    const std::size_t dot = s.key.find('.');
    const json value = TextToJson(s, s.get(o));
    if (dot == std::string::npos) j[s.key] = value;
    else j[s.key.substr(0, dot)][s.key.substr(dot + 1)] = value;
  }
  return j.dump(2);
}

}  // namespace hdrf::io
