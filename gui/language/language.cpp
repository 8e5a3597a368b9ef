#include "gui/language/language.h"

#include <QCoreApplication>
#include <QDir>
#include <QLibraryInfo>
#include <QLocale>
#include <QRegularExpression>
#include <QSettings>
#include <QTranslator>
#include <cstdio>

#include "common/error.h"
#include "common/message.h"

namespace hdrf::language {

namespace {
constexpr const char* kPrefix = ":/i18n";

QSettings StudioSettings() { return QSettings(QStringLiteral("HDRFusion"), QStringLiteral("HDRFusion Studio")); }

// A number as the engine writes it ("12", "-0.25"), in the language's notation ("0,25").
QString LocalNumber(const QString& arg) {
  static const QRegularExpression number(QStringLiteral("^-?[0-9]+(\\.([0-9]+))?$"));
  const QRegularExpressionMatch m = number.match(arg);
  if (!m.hasMatch()) return arg;
  QLocale l;
  l.setNumberOptions(QLocale::OmitGroupSeparator);
  return l.toString(arg.toDouble(), 'f', int(m.capturedLength(2)));
}

// The translated wording with its arguments in place, or a null string where `message` is
// none of the engine's wordings. `depth` bounds messages within messages.
QString Translated(const std::string& message, int depth) {
  const std::optional<ParsedMessage> m = depth < 3 ? ParseMessage(message) : std::nullopt;
  if (!m) return {};
  QStringList args;
  for (const std::string& a : m->args) {
    const QString t = Translated(a, depth + 1);
    args << (t.isNull() ? LocalNumber(QString::fromStdString(Printable(a))) : t);
  }
  // %1..%9 replaced in one pass (an argument, a file name, may hold "%2" itself).
  const QString wording = QCoreApplication::translate("Engine", m->wording->english);
  QString out;
  for (qsizetype i = 0; i < wording.size(); ++i) {
    const QChar c = wording[i];
    const int n = i + 1 < wording.size() ? wording[i + 1].digitValue() : -1;
    if (c == QLatin1Char('%') && n >= 1 && n <= args.size()) {
      out += args[n - 1];
      ++i;
    } else {
      out += c;
    }
  }
  return out;
}
}  // namespace

QString EngineText(const std::string& message) {
  const QString t = Translated(message, 0);
  if (!t.isNull()) return t;
  return QCoreApplication::translate("hdrf::EngineText", "%1", "an engine message, quoted as written (English)")
      .arg(QString::fromStdString(Printable(message)));
}

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

}  // namespace hdrf::language
