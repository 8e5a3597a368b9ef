// hdrfusion-studio: the desktop scanning studio. With no argument it opens on the built-in
// synthetic sensor; Start scans. Scriptable for tests and documentation:
//   hdrfusion-studio [--source SPEC] [--frames N] [--device cpu|cuda] [--screenshot FILE] [--start]
//                    [--tone OP[,KEY=VALUE...]]
#include <QApplication>
#include <QCommandLineParser>
#include <QScreen>
#include <QTimer>
#include <cstdio>

#include "gui/language/language.h"
#include "gui/main_window.h"
#include "gui/vtk_view.h"

namespace {

// The command line, read the same way with or without a display.
struct CommandLine {
  QCommandLineParser p;
  QCommandLineOption source{"source",
                            "Sequence folder, FILE.oni, openni:device=SERIAL,mode=vga|qvga (a live camera), or "
                            "synthetic:key=value,... (default: the synthetic room)",
                            "SPEC"};
  QCommandLineOption frames{"frames", "Stop after N frames", "N"};
  QCommandLineOption device{"device", "cpu or cuda", "DEVICE"};
  QCommandLineOption shot{"screenshot", "Run, save the window to FILE (and FILE.json), and quit", "FILE"};
  QCommandLineOption start{"start", "Start scanning at once"};
  QCommandLineOption tone{"tone",
                          "Tone mapping: an operator (mantiuk08, mantiuk06, reinhard, exposure, linear), then "
                          "parameters as key=value, comma-separated (see hdrfusion tonemap --list)",
                          "OP[,KEY=VALUE...]"};
  QCommandLineOption project{"project", "Open a saved scan (.hdrproj); Start continues it", "FILE"};
  QCommandLineOption no_recovery{"no-recovery-offer", "Do not offer scans a crash left (autosaves)"};
  QCommandLineOption language{"language",
                              "Language of the window: en or de (default: the one chosen under View → Language, "
                              "else the system's)",
                              "CODE"};
  CommandLine() {
    p.setApplicationDescription("HDRFusion Studio: HDR RGB-D scanning");
    p.addHelpOption();
    p.addVersionOption();
    p.addOptions({source, frames, device, shot, start, tone, project, no_recovery, language});
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (qEnvironmentVariableIsEmpty("DISPLAY") && qEnvironmentVariableIsEmpty("WAYLAND_DISPLAY") &&
      qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) {
    // --help and --version still answer (and a wrong option is still named) without a display.
    QCoreApplication core(argc, argv);
    QCoreApplication::setApplicationVersion("0.1.0");
    CommandLine cl;
    cl.p.process(core);
    std::fprintf(stderr,
                 "hdrfusion-studio: no display here (DISPLAY is not set). Run it on a desktop or under "
                 "xvfb-run; for a headless scan use `hdrfusion scan` (tools/demo.sh does this).\n");
    return 3;
  }
  hdrf::gui::VtkView::SetDefaultSurfaceFormat();  // before QApplication (VTK needs 3.2 core)
  QApplication app(argc, argv);
  QApplication::setOrganizationName("HDRFusion");
  QApplication::setApplicationName("HDRFusion Studio");
  QApplication::setApplicationVersion("0.1.0");
  CommandLine cl;
  QCommandLineParser& p = cl.p;
  p.process(app);
  // The language before any window exists: widgets take their words when they are made.
  if (!hdrf::language::StartInLanguage(app, p.isSet(cl.language), p.value(cl.language), "hdrfusion-studio")) return 2;
  const QCommandLineOption &source = cl.source, &frames = cl.frames, &device = cl.device, &shot = cl.shot,
                           &start = cl.start, &tone = cl.tone, &project = cl.project, &no_recovery = cl.no_recovery;
  hdrf::gui::StudioOptions o;
  o.source = p.value(source);
  bool frames_ok = true;
  o.frames = p.isSet(frames) ? p.value(frames).toInt(&frames_ok) : 0;
  if (!frames_ok || (p.isSet(frames) && o.frames < 1)) {
    std::fprintf(stderr, "hdrfusion-studio: --frames must be a whole number of frames, at least 1 (got '%s')\n",
                 p.value(frames).toLocal8Bit().constData());
    return 2;
  }
  o.device = p.value(device);
  o.screenshot = p.value(shot);
  o.autostart = p.isSet(start);
  o.tone = p.value(tone);
  o.project = p.value(project);
  o.offer_recovery = !p.isSet(no_recovery);
  if (!o.device.isEmpty() && o.device != "cpu" && o.device != "cuda") {
    std::fprintf(stderr, "hdrfusion-studio: --device must be cpu or cuda\n");
    return 2;
  }
  try {
    hdrf::gui::MainWindow w(o);
    // 1680x1050 where the screen has room, else the screen's free area (a 1366x768 laptop).
    QSize size(1680, 1050);
    if (const QScreen* screen = QGuiApplication::primaryScreen())
      size = size.boundedTo(screen->availableGeometry().size());
    w.resize(size);
    w.show();
    if (!o.screenshot.isEmpty()) {
      // A safety net for scripted runs: never hang a test or a docs build.
      QTimer::singleShot(10 * 60 * 1000, &app, [] {
        std::fprintf(stderr, "hdrfusion-studio: scripted run timed out\n");
        QApplication::exit(4);
      });
    }
    return app.exec();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hdrfusion-studio: %s\n", e.what());
    return 1;
  }
}
