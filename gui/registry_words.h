// The core's declarations (engine settings, tone-mapping operators) carry English words; the
// studio shows them in the user's language. Their translations are listed for Qt Linguist in
// gui/registry_strings.cpp, which tools/update_translations.sh writes from the declarations.
#pragma once

#include <QCoreApplication>
#include <string>

namespace hdrf::gui {

// A setting's label, help or advice (context "Settings").
inline QString SettingWords(const std::string& english) {
  return QCoreApplication::translate("Settings", english.c_str());
}
// An operator's or parameter's label or help, or a display preset's name (context "ToneMapping").
inline QString ToneWords(const std::string& english) {
  return QCoreApplication::translate("ToneMapping", english.c_str());
}

}  // namespace hdrf::gui
