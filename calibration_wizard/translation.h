// The programs' language: English in the sources, German from translations/hdrfusion_de.ts
// (compiled into the programs' resources), Qt's own dialogs and buttons from Qt's
// translations. Used by the studio and the calibration wizard alike.
#pragma once

#include <QCoreApplication>
#include <QString>
#include <QStringList>
#include <string>

class QCoreApplication;

namespace hdrf::wizard {

// The languages the programs speak, as ISO 639-1 codes: "en" and every compiled translation.
QStringList AvailableLanguages();
// The language's own name ("English", "Deutsch").
QString LanguageName(const QString& code);
// Installs the translations for `code` ("de", "en"); "" follows the system's UI languages.
// Returns the language now in use ("en" where no translation fits), also kept as the
// application's property "hdrf_language". Safe to call before
// any window exists only: widgets made earlier keep their words.
QString InstallTranslation(QCoreApplication& app, const QString& code);
// A program's language at start: `requested` (its --language, when `given`: one of
// AvailableLanguages(), else a message naming them goes to stderr and false comes back),
// otherwise the studio's saved choice, otherwise the system's. Call before any window exists.
bool StartInLanguage(QCoreApplication& app, bool given, const QString& requested, const char* program);

// The language chosen in the studio (View → Language), shared by both programs: a code, or
// "" to follow the system.
QString SavedLanguage();
void SaveLanguage(const QString& code);

// A message of the engine (a warning, a reason, an error naming a file), shown as the engine
// wrote it: in English, set apart in the user's language's quotation marks where that is
// not English. The engine's messages are shared with the command-line tools and logs.
inline QString EngineText(const QString& message) {
  return QCoreApplication::translate("hdrf::EngineText", "%1", "an engine message, quoted as written (English)")
      .arg(message);
}
inline QString EngineText(const std::string& message) { return EngineText(QString::fromStdString(message)); }

}  // namespace hdrf::wizard
