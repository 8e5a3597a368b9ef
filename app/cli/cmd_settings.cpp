// hdrfusion settings: the engine's settings as the registry declares them (key, default,
// range, what each does and when to change it). `--markdown` prints the page
// docs/reference/settings.md is made of, so that page is never written by hand.
#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "pipeline/settings.h"

namespace hdrf::cli {

namespace {

// The section a key belongs to: the part before its first dot ("tracker.levels" ->
// "tracker"); keys without one ("device", "pcf") are the general ones.
std::string Section(const std::string& key) {
  const auto dot = key.find('.');
  return dot == std::string::npos ? "general" : key.substr(0, dot);
}

// A table cell: a '|' would end the cell early.
std::string Cell(std::string s) {
  for (std::size_t i = 0; (i = s.find('|', i)) != std::string::npos; i += 2) s.replace(i, 1, "\\|");
  return s;
}

void PrintMarkdown() {
  std::printf("# Settings reference\n\n"
              "Every engine setting, as `hdrfusion settings --markdown` prints it from the settings\n"
              "registry (a test fails when this page and the program disagree). Each is a flag of\n"
              "`hdrfusion scan` (`--KEY VALUE`), a key of an `--options` settings file\n"
              "(docs/formats.md) and a field of the studio's Controls panel (fields marked *expert* are\n"
              "under \"Advanced\"). A scan's report and its project file keep the values it ran with.\n");
  std::string section;
  for (const auto& s : pipeline::Settings()) {
    if (Section(s.key) != section) {
      section = Section(s.key);
      std::printf("\n## %s\n\n| key | default | range | what it does | when to change it |\n|---|---|---|---|---|\n",
                  section.c_str());
    }
    std::string key = "`" + s.key + "`";
    if (!s.alias.empty()) key += " (`" + s.alias + "`)";
    if (s.expert) key += " *expert*";
    std::printf("| %s | %s | %s | **%s**: %s | %s |\n", key.c_str(), Cell(s.Default()).c_str(),
                Cell(s.Range()).c_str(), Cell(s.label).c_str(), Cell(s.help).c_str(), Cell(s.advice).c_str());
  }
}

void PrintPlain(const std::string& only) {
  bool found = false;
  for (const auto& s : pipeline::Settings()) {
    if (!only.empty() && s.key != only && s.alias != only && s.alias != "--" + only) continue;
    found = true;
    std::printf("%s%s%s\n  %s: %s\n  default %s; %s\n  %s\n", s.key.c_str(), s.alias.empty() ? "" : "  (",
                s.alias.empty() ? "" : (s.alias + ")").c_str(), s.label.c_str(), s.help.c_str(), s.Default().c_str(),
                s.Range().c_str(), s.advice.c_str());
  }
  if (!found) pipeline::FindSetting(only);  // throws "unknown setting", naming it
}

}  // namespace

Command AddSettingsCommand(CLI::App& app) {
  struct Args {
    std::string key;
    bool markdown = false;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("settings", "List the engine's settings: key, default, range, what each does");
  cmd->add_option("KEY", a->key, "Only this setting (e.g. volume.voxel_m)");
  cmd->add_flag("--markdown", a->markdown, "Print the settings reference page (docs/reference/settings.md)");
  return {cmd, [a] {
    if (a->markdown) PrintMarkdown();
    else PrintPlain(a->key);
    return 0;
  }};
}

}  // namespace hdrf::cli
