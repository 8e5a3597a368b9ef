// The programs' language: English in the sources, German from translations/hdrfusion_de.ts
// (compiled into the programs' resources), Qt's own dialogs and buttons from Qt's
// translations. A library of its own (hdrfusion_language), used by the studio and the
// calibration wizard alike.
#pragma once

#include <QCoreApplication>
#include <QString>
#include <QStringList>
#include <string>

class QCoreApplication;

namespace hdrf::language {

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

// A message of the engine (a reason a frame was not fused, a sweep plan's warning, a
// calibration's reason, a profile's warning): one of the engine's fixed wordings
// (common/message.h) is shown translated, with its arguments put back (numbers in the
// language's notation, an argument that is itself a message translated too). Any other
// message (an error naming a file and what is wrong in it) is shown as the engine wrote it:
// in English, set apart in the language's quotation marks where that is not English.
QString EngineText(const std::string& message);
inline QString EngineText(const QString& message) { return EngineText(message.toStdString()); }
inline QString EngineText(const char* message) { return EngineText(std::string(message ? message : "")); }

}  // namespace hdrf::language
