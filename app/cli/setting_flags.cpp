#include "cli/setting_flags.h"

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
}

void SettingFlags::Apply(pipeline::PipelineOptions& options) const {
  for (const Flag& f : flags_)
    if (f.option->count() > 0) f.setting->set(options, f.value);
}

}  // namespace hdrf::cli
