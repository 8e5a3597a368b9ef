#include "cli/setting_flags.h"

#include "common/error.h"

namespace hdrf::cli {

SettingFlags::SettingFlags(CLI::App* cmd) {
  CLI::App* group = cmd->add_option_group("Engine settings",
                                          "Engine settings (also read from an --options file)");
  for (const pipeline::Setting& s : pipeline::Settings()) {
    flags_.push_back({&s, nullptr, {}});
    Flag& f = flags_.back();
    std::string names = "--" + s.key;
    if (!s.alias.empty()) names += "," + s.alias;
    f.option = group->add_option(names, f.value,
                                 s.help + " [" + s.Range() + "; default " + s.Default() + "]");
    f.option->type_name(s.kind == pipeline::SettingKind::kChoice ? "CHOICE" : "VALUE");
  }
  for (const char* name : {"--volume.resolution", "--volume-res", "--volume.size_m", "--volume-size"})
    retired_.push_back({group->add_option(name, retired_value_)->group(""), name});
}

void SettingFlags::Apply(pipeline::PipelineOptions& options) const {
  for (const auto& [option, name] : retired_)
    if (option->count() > 0) throw SettingError(name, pipeline::RetiredSetting(name));
  for (const Flag& f : flags_)
    if (f.option->count() > 0) f.setting->set(options, f.value);
}

}  // namespace hdrf::cli
