// The German translation: complete against the sources (Qt Linguist's lupdate run over them
// finds nothing unfinished), the core's words listed for it, and the studio's window and the
// calibration wizard made in German with no English left in sight. The language follows the
// system and the choice made in the studio. Runs on a real X server (the studio's 3-D view
// needs one); without DISPLAY this binary re-runs itself under xvfb-run.
#include <gtest/gtest.h>

#include <QAbstractButton>
#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QDir>
#include <QDockWidget>
#include <QElapsedTimer>
#include <QFile>
#include <QGroupBox>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QMenuBar>
#include <QRegularExpression>
#include <QSet>
#include <QSettings>
#include <QTabBar>
#include <QTemporaryDir>
#include <QTest>
#include <QTextDocument>
#include <QTranslator>
#include <QWizard>
#include <QXmlStreamReader>
#include <map>
#include <set>
#include <string>

#include "calibration_wizard/calibration_wizard.h"
#include "gui/language/language.h"
#include "common/message.h"
#include "gui/main_window.h"
#include "gui/registry_words.h"
#include "gui/vtk_view.h"
#include "pipeline/settings.h"
#include "support/test_support.h"
#include "tonemap/operator.h"

#if !defined(HDRF_SOURCE_DIR) || !defined(HDRF_LUPDATE) || !defined(HDRF_REGISTRY_STRINGS) || !defined(HDRF_STUDIO_BINARY)
#error "HDRF_SOURCE_DIR, HDRF_LUPDATE, HDRF_REGISTRY_STRINGS and HDRF_STUDIO_BINARY must be defined"
#endif

namespace hdrf {
namespace {

const std::string kSource = HDRF_SOURCE_DIR;
const QString kTs = QString::fromStdString(kSource + "/translations/hdrfusion_de.ts");

struct Message {
  QString context, source, translation;
  bool unfinished = false;
};

std::vector<Message> ReadTs(const QString& path) {
  QFile f(path);
  EXPECT_TRUE(f.open(QIODevice::ReadOnly)) << path.toStdString();
  QXmlStreamReader x(&f);
  std::vector<Message> out;
  QString context;
  Message m;
  while (!x.atEnd()) {
    x.readNext();
    if (!x.isStartElement()) continue;
    if (x.name() == QLatin1String("name")) context = x.readElementText();
    if (x.name() == QLatin1String("message")) m = Message{context, {}, {}, false};
    if (x.name() == QLatin1String("source")) m.source = x.readElementText();
    if (x.name() == QLatin1String("translation")) {
      const QString type = x.attributes().value(QLatin1String("type")).toString();
      m.unfinished = !type.isEmpty();  // unfinished, vanished or obsolete
      m.translation = x.readElementText();
      out.push_back(m);
    }
  }
  EXPECT_FALSE(x.hasError()) << x.errorString().toStdString();
  return out;
}

QStringList Placeholders(const QString& s) {
  QStringList p;
  for (const auto& m : QRegularExpression(QStringLiteral("%L?\\d")).globalMatch(s)) p << m.captured();
  p.sort();
  return p;
}

// lupdate over today's sources, into a copy of the .ts: every string the studio and the wizard
// show is there and translated, with the same placeholders.
TEST(Translations, GermanCoversEverySourceString) {
  QTemporaryDir tmp;
  const QString copy = tmp.filePath(QStringLiteral("de.ts"));
  ASSERT_TRUE(QFile::copy(kTs, copy));
  const auto r = test::RunCommand("cd '" + kSource + "' && " HDRF_LUPDATE
                                  " -no-obsolete -locations none -I . -I core gui calibration_wizard app/studio app/wizard"
                                  " -ts '" + copy.toStdString() + "' 2>&1");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto messages = ReadTs(copy);
  EXPECT_GT(messages.size(), 500u);
  int unfinished = 0;
  for (const Message& m : messages) {
    if (m.unfinished || m.translation.trimmed().isEmpty()) {
      ++unfinished;
      ADD_FAILURE() << "untranslated (" << m.context.toStdString() << "): " << m.source.toStdString()
                    << "\n  run tools/update_translations.sh and translate it in translations/hdrfusion_de.ts";
      continue;
    }
    EXPECT_EQ(Placeholders(m.source), Placeholders(m.translation))
        << m.source.toStdString() << " -> " << m.translation.toStdString();
  }
  EXPECT_EQ(unfinished, 0);
  // The .ts in the repository is what lupdate leaves: nothing vanished or added.
  const auto kept = ReadTs(kTs);
  EXPECT_EQ(kept.size(), messages.size()) << "translations/hdrfusion_de.ts is stale: run tools/update_translations.sh";
}

// gui/registry_strings.cpp lists exactly the words of today's settings and operators.
TEST(Translations, TheCoresWordsAreListedForLupdate) {
  const auto r = test::RunCommand(HDRF_REGISTRY_STRINGS);
  ASSERT_EQ(r.status, 0);
  QFile f(QString::fromStdString(kSource + "/gui/registry_strings.cpp"));
  ASSERT_TRUE(f.open(QIODevice::ReadOnly));
  EXPECT_TRUE(r.output == f.readAll().toStdString())
      << "gui/registry_strings.cpp is stale: run tools/update_translations.sh";
}

// Every word of the settings registry and of the tone-mapping declarations has a German
// translation (the form and the panel are generated from them at run time).
TEST(Translations, EverySettingAndOperatorWordHasAGermanTranslation) {
  QTranslator de;
  ASSERT_TRUE(de.load(QStringLiteral("hdrfusion_de"), QStringLiteral(":/i18n")));
  int checked = 0;
  const auto check = [&](const char* context, const std::string& english) {
    if (english.empty()) return;
    ++checked;
    EXPECT_FALSE(de.translate(context, english.c_str()).isEmpty()) << context << ": " << english;
  };
  for (const auto& s : pipeline::Settings()) {
    check("Settings", s.label);
    check("Settings", s.help);
    check("Settings", s.advice);
  }
  for (const auto& d : tonemap::Operators()) {
    check("ToneMapping", d.label);
    check("ToneMapping", d.help);
    for (const auto& p : d.params) check("ToneMapping", p.label), check("ToneMapping", p.help);
    for (const auto& p : d.presets) check("ToneMapping", p.label);
  }
  EXPECT_GT(checked, 150);
}

QStringList EnglishWords(const QString& shown);

// The engine's messages of normal operation (common/message.h) are shown in German: every
// wording translated with no English left, numbers in German notation, a message within a
// message translated too; anything else (an error naming a file) quoted as written.
TEST(Translations, EngineMessagesAreShownInGerman) {
  for (const Wording* w : AllWordings()) {
    const QString t = QCoreApplication::translate("Engine", w->english);
    EXPECT_NE(t, QString::fromUtf8(w->english)) << "untranslated: " << w->name;
    const QStringList english = EnglishWords(t);
    EXPECT_TRUE(english.isEmpty()) << w->name << ": English (" << english.join(QStringLiteral(", ")).toStdString()
                                   << ") in " << t.toStdString();
  }
  // Numbers: decimal commas, units kept.
  const std::string residual = Say(words::kIcpResidualHigh, {Num(3.14159, 1), Num(2.5, 1), Num(0.75, 2)});
  EXPECT_EQ(language::EngineText(residual),
            QStringLiteral("Punkt-zu-Fläche-Fehler 3,1 cm, 2,5-mal so groß wie die für diesen Scan üblichen 0,75 cm"));
  EXPECT_EQ(language::EngineText(Say(words::kConfirmingPose, {"1", "3"})),
            QStringLiteral("bestätige die Pose nach einem Verlust (1 von 3 Bildern)"));
  // The note the studio's status line gives where small frames lowered the pyramid levels.
  EXPECT_EQ(language::EngineText(Say(words::kLevelsLowered, {"3", "2", "160", "120", "80", "60"})),
            QStringLiteral("tracker.levels von 3 auf 2 gesenkt für Bilder von 160x120 (eine Pyramidenstufe unter "
                           "80x60 Pixeln führt den Tracker in die Irre)"));
  // A failed capture step: the failure and the advice are messages themselves; the folder
  // (holding "%2" and ": ") is kept as it is.
  const std::string failure = Say(words::kFlicker, {"12"});
  const std::string capture = Say(words::kCaptureFailed, {Sig(12.5), "4", "9", failure, "3", Say(words::kAdviceFlicker),
                                                          "3", "/tmp/sweep %2: x"});
  const QString shown = language::EngineText(capture);
  EXPECT_EQ(shown, QStringLiteral("Bei 12,5 ms (Schritt 4 von 9): die Helligkeit änderte sich zwischen den "
                                  "Wiederholungen um 12 %: flackerndes Licht, 3-mal in Folge. Leuchtstofflampen "
                                  "oder gedimmte LED-Lampen ausschalten (oder Tageslicht nutzen), dann fortsetzen. "
                                  "Die 3 bisher aufgenommenen Schritte bleiben in /tmp/sweep %2: x erhalten."));
  // Not one of the engine's wordings: quoted as the engine wrote it, control characters escaped.
  EXPECT_EQ(language::EngineText(std::string("/data/seq/rgb.txt:3: expected 'timestamp filename'\x1b")),
            QStringLiteral("„/data/seq/rgb.txt:3: expected 'timestamp filename'\\x1b“"));
}

// ---- What a German user sees ----

// Words that only English has (German shares "in", "an", "so", "was", "also", ...).
const QSet<QString> kEnglishOnly = {
    QStringLiteral("the"),   QStringLiteral("and"),   QStringLiteral("of"),    QStringLiteral("to"),
    QStringLiteral("is"),    QStringLiteral("with"),  QStringLiteral("from"),  QStringLiteral("for"),
    QStringLiteral("this"),  QStringLiteral("that"),  QStringLiteral("when"),  QStringLiteral("are"),
    QStringLiteral("be"),    QStringLiteral("by"),    QStringLiteral("its"),   QStringLiteral("or"),
    QStringLiteral("each"),  QStringLiteral("every"), QStringLiteral("than"),  QStringLiteral("which"),
    QStringLiteral("into"),  QStringLiteral("only"),  QStringLiteral("after"), QStringLiteral("before"),
    QStringLiteral("more"),  QStringLiteral("frames"), QStringLiteral("has"),  QStringLiteral("not"),
    QStringLiteral("no"),    QStringLiteral("yet"),   QStringLiteral("save"),  QStringLiteral("open"),
    QStringLiteral("show"),  QStringLiteral("view"),  QStringLiteral("file"),  QStringLiteral("camera"),
    QStringLiteral("settings"), QStringLiteral("colour"), QStringLiteral("depth")};

// The English words left in a visible text: markup, file names, keys, specs and values
// ("synthetic:scene=room,frames=300", "volume.voxel_m", "~/HDRFusion", "no-nr") are not
// words, nor is a message of the system or a device quoted verbatim („…“, “…”).
QStringList EnglishWords(const QString& shown) {
  QString t = shown;
  if (Qt::mightBeRichText(t)) {
    t.remove(QRegularExpression(QStringLiteral("<tt>.*?</tt>")));
    QTextDocument doc;
    doc.setHtml(t);
    t = doc.toPlainText();
  }
  t.remove(QRegularExpression(QStringLiteral("[„“][^“”]*[“”]")));
  t.remove(QRegularExpression(QStringLiteral("\\S*[=:/~._-]\\S*")));
  QStringList found;
  for (const auto& m : QRegularExpression(QStringLiteral("[A-Za-z]+")).globalMatch(t))
    if (kEnglishOnly.contains(m.captured().toLower())) found << m.captured();
  return found;
}

// Every text a widget shows or explains (label, button, title, tooltip, placeholder, items, tabs).
void Collect(QWidget* root, std::map<QString, QString>& out) {
  const auto add = [&](const QString& text, const QObject* o) {
    if (!text.trimmed().isEmpty()) out.emplace(text, QString::fromLatin1(o->metaObject()->className()) + " " + o->objectName());
  };
  QList<QWidget*> all = root->findChildren<QWidget*>();
  all.prepend(root);
  for (QWidget* w : all) {
    add(w->windowTitle(), w);
    add(w->toolTip(), w);
    if (auto* l = qobject_cast<QLabel*>(w)) add(l->text(), w);
    if (auto* b = qobject_cast<QAbstractButton*>(w)) add(b->text(), w);
    if (auto* g = qobject_cast<QGroupBox*>(w)) add(g->title(), w);
    if (auto* p = qobject_cast<QWizardPage*>(w)) add(p->title(), w), add(p->subTitle(), w);
    if (auto* z = qobject_cast<QWizard*>(w))
      for (auto b : {QWizard::BackButton, QWizard::NextButton, QWizard::FinishButton, QWizard::CancelButton})
        add(z->buttonText(b), w);
    if (auto* e = qobject_cast<QLineEdit*>(w)) add(e->placeholderText(), w);
    if (auto* c = qobject_cast<QComboBox*>(w))
      for (int i = 0; i < c->count(); ++i) {
        if (!c->isEditable()) add(c->itemText(i), w);
        add(c->itemData(i, Qt::ToolTipRole).toString(), w);
      }
    if (auto* t = qobject_cast<QTabBar*>(w))
      for (int i = 0; i < t->count(); ++i) add(t->tabText(i), w);
    for (QAction* a : w->actions()) {
      add(a->text(), a);
      if (a->menu())
        for (QAction* s : a->menu()->actions()) add(s->text(), s);
    }
  }
}

void ExpectNoEnglish(QWidget* root, int at_least) {
  std::map<QString, QString> shown;
  Collect(root, shown);
  EXPECT_GE(int(shown.size()), at_least);
  for (const auto& [text, where] : shown) {
    const QStringList english = EnglishWords(text);
    EXPECT_TRUE(english.isEmpty()) << "English (" << english.join(QStringLiteral(", ")).toStdString() << ") in "
                                   << where.toStdString() << ": " << text.toStdString();
  }
}

// The studio in German: menus, docks, controls, the settings form (expert part included)
// and the tone-mapping panel of every operator.
TEST(GermanStudio, TheWindowShowsNoEnglish) {
  gui::StudioOptions o;
  o.offer_recovery = false;
  gui::MainWindow w(o);
  w.resize(1366, 768);
  w.show();
  QApplication::processEvents();
  ExpectNoEnglish(&w, 150);
  for (QMenu* m : w.menuBar()->findChildren<QMenu*>()) ExpectNoEnglish(m, 1);
  auto* op = w.findChild<QComboBox*>(QStringLiteral("tone_operator"));
  ASSERT_NE(op, nullptr);
  for (int i = 0; i < op->count(); ++i) {
    op->setCurrentIndex(i);
    QApplication::processEvents();
    ExpectNoEnglish(&w, 150);
  }
}

// The calibration wizard in German: every page, as it looks once its work is done (a whole
// automatic run on the synthetic sensor), and the pages no run reaches as they were made.
TEST(GermanWizard, EveryPageShowsNoEnglish) {
  QTemporaryDir dir;
  wizard::WizardSettings s;
  s.automatic = true;
  s.source = QStringLiteral("synthetic:size=160x120");
  s.sweep_folder = dir.filePath(QStringLiteral("sweep"));
  s.report_folder = dir.filePath(QStringLiteral("report"));
  wizard::CalibrationWizard w(s);
  for (int id : w.pageIds()) ExpectNoEnglish(w.page(id), 1);
  int previous = -1, pages = 0;
  bool finished = false;
  QObject::connect(&w, &QWizard::currentIdChanged, [&](int id) {
    if (previous >= 0) ExpectNoEnglish(w.page(previous), 3), ++pages;
    previous = id;
  });
  QObject::connect(&w, &QDialog::finished, [&] { finished = true; });
  QString failed;
  QObject::connect(&w, &wizard::CalibrationWizard::failed, [&](const QString& m) { failed = m; });
  w.show();
  QElapsedTimer t;
  t.start();
  while (!finished && t.elapsed() < 180000) QTest::qWait(20);
  ASSERT_TRUE(finished);
  EXPECT_TRUE(failed.isEmpty()) << failed.toStdString();
  ExpectNoEnglish(w.page(previous), 3);
  EXPECT_EQ(pages + 1, int(w.pageIds().size()));
  ExpectNoEnglish(&w, 50);
}

// The language follows the system's, and the one chosen in the studio (View → Language)
// wins over it; --language over both.
TEST(Language, FollowsTheSystemAndTheStudiosChoice) {
  QTemporaryDir dir;
  const std::string config = dir.filePath(QStringLiteral("config")).toStdString();
  const auto language = [&](const std::string& env, const std::string& args) {
    const std::string shot = dir.filePath(QStringLiteral("shot.png")).toStdString();
    const auto r = test::RunCommand("env XDG_CONFIG_HOME='" + config + "' XDG_STATE_HOME='" + config + "' " + env + " " +
                                    HDRF_STUDIO_BINARY " --no-recovery-offer --frames 2 --source "
                                    "synthetic:scene=room,frames=2,size=160x120 --screenshot '" + shot + "' " + args +
                                    " 2>&1");
    EXPECT_EQ(r.status, 0) << r.output;
    QFile f(QString::fromStdString(shot + ".json"));
    if (!f.open(QIODevice::ReadOnly)) return std::string("(no report)");
    return QJsonDocument::fromJson(f.readAll()).object().value(QStringLiteral("language")).toString().toStdString();
  };
  EXPECT_EQ(language("LANGUAGE=de LC_ALL=de_DE.UTF-8 LANG=de_DE.UTF-8", ""), "de");
  EXPECT_EQ(language("LANGUAGE=fr LC_ALL=fr_FR.UTF-8 LANG=fr_FR.UTF-8", ""), "en");  // no French: English
  EXPECT_EQ(language("LANGUAGE=en LC_ALL=C.UTF-8 LANG=C.UTF-8", "--language de"), "de");
  // The studio's choice, kept in its settings, over the system's.
  {
    QSettings s(QString::fromStdString(config + "/HDRFusion/HDRFusion Studio.conf"), QSettings::IniFormat);
    s.setValue(QStringLiteral("language"), QStringLiteral("en"));
  }
  EXPECT_EQ(language("LANGUAGE=de LC_ALL=de_DE.UTF-8 LANG=de_DE.UTF-8", ""), "en");
  EXPECT_EQ(language("LANGUAGE=de LC_ALL=de_DE.UTF-8 LANG=de_DE.UTF-8", "--language de"), "de");
  // A language the programs do not have is refused, naming the ones they have.
  const auto bad = test::RunCommand("env XDG_CONFIG_HOME='" + config + "' " HDRF_STUDIO_BINARY " --language xx 2>&1");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.output.find("en, de"), std::string::npos) << bad.output;
}

}  // namespace
}  // namespace hdrf

int main(int argc, char** argv) {
  const bool display = hdrf::test::EnsureDisplay(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  if (!display) return RUN_ALL_TESTS();
  QTemporaryDir config;  // never the user's own settings
  qputenv("XDG_CONFIG_HOME", config.path().toUtf8());
  QTemporaryDir state;
  qputenv("XDG_STATE_HOME", state.path().toUtf8());
  hdrf::gui::VtkView::SetDefaultSurfaceFormat();
  QApplication app(argc, argv);
  QApplication::setOrganizationName("HDRFusionTest");
  QApplication::setApplicationName("TranslationTests");
  if (hdrf::language::InstallTranslation(app, QStringLiteral("de")) != QLatin1String("de")) {
    std::fprintf(stderr, "the German translation is not in the resources (:/i18n)\n");
    return 1;
  }
  return RUN_ALL_TESTS();
}
