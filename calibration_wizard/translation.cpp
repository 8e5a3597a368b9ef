#include "calibration_wizard/translation.h"

#include <QCoreApplication>
#include <QDir>
#include <QLibraryInfo>
#include <QLocale>
#include <QSettings>
#include <QTranslator>
#include <cstdio>

namespace hdrf::wizard {

namespace {
constexpr const char* kPrefix = ":/i18n";

QSettings StudioSettings() { return QSettings(QStringLiteral("HDRFusion"), QStringLiteral("HDRFusion Studio")); }
}  // namespace

bool StartInLanguage(QCoreApplication& app, bool given, const QString& requested, const char* program) {
  if (given && !AvailableLanguages().contains(requested)) {
    std::fprintf(stderr, "%s: --language must be one of %s (got '%s')\n", program,
                 qPrintable(AvailableLanguages().join(QStringLiteral(", "))), qPrintable(requested));
    return false;
  }
  InstallTranslation(app, given ? requested : SavedLanguage());
  return true;
}

QString SavedLanguage() { return StudioSettings().value(QStringLiteral("language")).toString(); }

void SaveLanguage(const QString& code) {
  QSettings s = StudioSettings();
  if (code.isEmpty())
    s.remove(QStringLiteral("language"));
  else
    s.setValue(QStringLiteral("language"), code);
}

QStringList AvailableLanguages() {
  QStringList codes{QStringLiteral("en")};
  for (const QString& f : QDir(QString::fromLatin1(kPrefix)).entryList({QStringLiteral("hdrfusion_*.qm")}, QDir::Files,
                                                                      QDir::Name))
    codes << f.mid(10, f.size() - 13);  // "hdrfusion_de.qm" -> "de"
  return codes;
}

QString LanguageName(const QString& code) {
  const QLocale l(code);
  QString name = l.nativeLanguageName();
  if (!name.isEmpty()) name[0] = name[0].toUpper();
  return name.isEmpty() ? code : name;
}

QString InstallTranslation(QCoreApplication& app, const QString& code) {
  // The first of the user's languages that has a translation (English needs none).
  QString chosen = QStringLiteral("en");
  const QStringList available = AvailableLanguages();
  const QStringList wanted = code.isEmpty() ? QLocale::system().uiLanguages() : QStringList{code};
  for (const QString& w : wanted) {
    const QString lang = QLocale(w).name().section(QLatin1Char('_'), 0, 0);
    if (available.contains(lang)) {
      chosen = lang;
      break;
    }
  }
  app.setProperty("hdrf_language", QStringLiteral("en"));
  if (chosen == QLatin1String("en")) return chosen;
  auto* own = new QTranslator(&app);
  if (!own->load(QStringLiteral("hdrfusion_") + chosen, QString::fromLatin1(kPrefix))) {
    delete own;
    return QStringLiteral("en");
  }
  app.setProperty("hdrf_language", chosen);
  app.installTranslator(own);
  // Qt's own words (dialog buttons, file dialogs, the wizard's Back/Next), where installed.
  auto* qt = new QTranslator(&app);
  if (qt->load(QStringLiteral("qtbase_") + chosen, QLibraryInfo::path(QLibraryInfo::TranslationsPath)))
    app.installTranslator(qt);
  else
    delete qt;
  QLocale::setDefault(QLocale(chosen));
  return chosen;
}

}  // namespace hdrf::wizard
