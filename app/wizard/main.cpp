// hdrfusion-calibration-wizard: guided camera calibration (docs/calibration_wizard.md).
//   hdrfusion-calibration-wizard [--source SPEC|FOLDER] [--sweep-folder DIR] [--report DIR]
//                                [--step STOPS] [--repeats N] [--method M] [--auto] [--screenshots DIR]
// --auto runs every page with its defaults and saves (exit 0), or stops at the first page
// that cannot go on (exit 1, the reason on stderr).
#include <QApplication>
#include <QCommandLineParser>
#include <QCoreApplication>
#include <QTimer>
#include <cstdio>

#include "calibration_wizard/calibration_wizard.h"
#include "gui/language/language.h"

namespace {

// The command line, parsed by whichever application object there is: --help and --version
// work without a display.
struct CommandLine {
  QCommandLineParser p;
  QCommandLineOption source{"source",
                            "openni:[device=SERIAL,mode=vga|qvga,unit=MS], synthetic[:response=NAME|FILE.json,"
                            "scene=room|desk|hall,size=WxH], or a recorded sweep folder",
                            "SPEC"};
  QCommandLineOption sweep{"sweep-folder", "Where the capture writes the sweep", "DIR"};
  QCommandLineOption report{"report", "Where the report is written", "DIR"};
  QCommandLineOption step{"step", "Stops between exposures (default 0.5)", "STOPS"};
  QCommandLineOption repeats{"repeats", "Frames per exposure (default 5)", "N"};
  QCommandLineOption method{"method", "debevec (default), robertson or emor", "METHOD"};
  QCommandLineOption basis{"emor-basis", "invemor.txt for --method emor", "FILE"};
  QCommandLineOption automatic{"auto", "Run every page with its defaults, save, and quit"};
  QCommandLineOption shots{"screenshots", "Save each page as a PNG into DIR", "DIR"};
  QCommandLineOption language{"language",
                              "Language of the wizard: en or de (default: the studio's choice, else the system's)",
                              "CODE"};
  CommandLine() {
    p.setApplicationDescription("Guided camera calibration: exposure sweep, response, noise, profile");
    p.addHelpOption();
    p.addVersionOption();
    p.addOptions({source, sweep, report, step, repeats, method, basis, automatic, shots, language});
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (qEnvironmentVariableIsEmpty("DISPLAY") && qEnvironmentVariableIsEmpty("WAYLAND_DISPLAY") &&
      qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) {
    QCoreApplication core(argc, argv);
    QCoreApplication::setApplicationVersion("0.1.0");
    CommandLine c;
    c.p.process(core);  // --help exits here
    std::fprintf(stderr,
                 "hdrfusion-calibration-wizard: no display here (DISPLAY is not set). Run it on a desktop, under "
                 "xvfb-run, or with QT_QPA_PLATFORM=offscreen together with --auto; headless, the same steps are "
                 "`hdrfusion capture-sweep` and `hdrfusion calibrate`.\n");
    return 3;
  }
  QApplication app(argc, argv);
  QApplication::setOrganizationName("HDRFusion");
  QApplication::setApplicationName("HDRFusion Calibration");
  QApplication::setApplicationVersion("0.1.0");
  CommandLine c;
  QCommandLineParser& p = c.p;
  p.process(app);
  // The language before any window exists: widgets take their words when they are made.
  if (!hdrf::language::StartInLanguage(app, p.isSet(c.language), p.value(c.language), "hdrfusion-calibration-wizard")) return 2;
  hdrf::wizard::WizardSettings o;
  o.source = p.value(c.source);
  o.sweep_folder = p.value(c.sweep);
  o.report_folder = p.value(c.report);
  o.automatic = p.isSet(c.automatic);
  o.screenshots = p.value(c.shots);
  if (p.isSet(c.step)) o.plan.step_stops = p.value(c.step).toDouble();
  if (p.isSet(c.repeats)) o.plan.repeats = p.value(c.repeats).toInt();
  if (p.isSet(c.method)) o.method = p.value(c.method);
  o.emor_basis = p.value(c.basis);
  try {
    o.plan.Check();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hdrfusion-calibration-wizard: %s\n", e.what());
    return 2;
  }
  hdrf::wizard::CalibrationWizard w(o);
  w.show();
  if (o.automatic)
    QTimer::singleShot(10 * 60 * 1000, &app, [] {
      std::fprintf(stderr, "hdrfusion-calibration-wizard: automatic run timed out\n");
      QApplication::exit(4);
    });
  QObject::connect(&w, &hdrf::wizard::CalibrationWizard::saved, [](const QString& profile, const QString& report) {
    std::printf("saved profile %s\nreport %s\n", profile.toLocal8Bit().constData(), report.toLocal8Bit().constData());
  });
  QObject::connect(&w, &QDialog::finished, &app, [&w](int) { QApplication::exit(w.exit_code()); });
  return app.exec();
}
