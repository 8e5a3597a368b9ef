// Prints gui/registry_strings.cpp: the words of the engine's settings registry, of the
// tone-mapping operators' declarations and the engine's message wordings, as QT_TRANSLATE_NOOP entries for Qt Linguist's
// lupdate (the core does not use Qt, so lupdate cannot find them in the core's sources).
// tools/update_translations.sh writes the file with it; a test fails when the file is stale.
#include <cstdio>
#include <set>
#include <string>

#include "common/message.h"
#include "pipeline/settings.h"
#include "tonemap/operator.h"

namespace {

std::string Quoted(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') q += '\\';
    q += c;
  }
  return q + "\"";
}

void List(const char* context, const char* array, const std::vector<std::string>& words) {
  std::printf("static const char* const %s[] = {\n", array);
  std::set<std::string> seen;
  for (const std::string& w : words)
    if (!w.empty() && seen.insert(w).second)
      std::printf("    QT_TRANSLATE_NOOP(\"%s\", %s),\n", context, Quoted(w).c_str());
  std::printf("};\n");
}

}  // namespace

int main() {
  std::vector<std::string> settings, tone, engine;
  for (const hdrf::Wording* w : hdrf::AllWordings()) engine.push_back(w->english);
  for (const auto& s : hdrf::pipeline::Settings()) {
    settings.push_back(s.label);
    settings.push_back(s.help);
    settings.push_back(s.advice);
  }
  for (const auto& d : hdrf::tonemap::Operators()) {
    tone.push_back(d.label);
    tone.push_back(d.help);
    for (const auto& p : d.params) {
      tone.push_back(p.label);
      tone.push_back(p.help);
    }
    for (const auto& p : d.presets) tone.push_back(p.label);
  }
  std::printf(
      "// Written by tools/update_translations.sh from the engine's settings registry, the\n"
      "// tone-mapping operators' declarations and the engine's message wordings\n"
      "// (tests/translations/registry_strings_main.cpp): their words, listed for Qt Linguist's\n"
      "// lupdate. Not compiled; do not edit.\n"
      "#include <QtGlobal>\n\n");
  List("Settings", "kSettingWords", settings);
  std::printf("\n");
  List("ToneMapping", "kToneMappingWords", tone);
  std::printf("\n");
  List("Engine", "kEngineWords", engine);
  return 0;
}
