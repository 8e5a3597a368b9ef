#include "gui/window_report.h"

#include <QApplication>
#include <QDockWidget>
#include <QGuiApplication>
#include <QJsonArray>
#include <QScreen>
#include <QScrollArea>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "gui/image_view.h"
#include "gui/main_window.h"
#include "gui/vtk_view.h"

namespace hdrf::gui {

namespace {
// CPU seconds of this process's threads so far, summed by thread name (Linux; empty elsewhere).
QJsonObject CpuSecondsByThread() {
  QJsonObject out;
  const long tick = sysconf(_SC_CLK_TCK);
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    std::ifstream comm(e.path() / "comm"), stat(e.path() / "stat");
    std::string name, line;
    if (!std::getline(comm, name) || !std::getline(stat, line)) continue;
    // Fields after the name's closing parenthesis: state is the 3rd, utime the 14th, stime the 15th.
    std::istringstream in(line.substr(line.rfind(')') + 2));
    std::string field;
    double ticks = 0;
    for (int i = 3; i <= 15 && in >> field; ++i)
      if (i >= 14) ticks += std::stod(field);
    const QString key = QString::fromStdString(name);
    out[key] = out.value(key).toDouble() + ticks / double(tick);
  }
  return out;
}
}  // namespace

QJsonObject DescribeWindow(MainWindow& w, QSize window) {
  const MainWindow::DisplayStats& st = w.display_stats();
  QJsonObject report;
  QJsonObject views;
  for (const QString& name : w.view_names()) {
    const ImageView* view = w.view(name);
    QJsonObject v;
    v["width"] = view->image().width();
    v["height"] = view->image().height();
    v["distinct_levels"] = view->DistinctLevels();
    v["visible"] = w.dock(name)->isVisible();
    // On screen now (not behind another tab) and how large its picture is drawn there.
    v["on_screen"] = !view->visibleRegion().isEmpty();
    v["shown"] = QJsonArray{view->ImageRect().width(), view->ImageRect().height()};
    v["tabbed"] = !w.tabifiedDockWidgets(w.dock(name)).isEmpty();
    views[name] = v;
  }
  report["views"] = views;
  const QImage v3 = w.view3d()->Capture();
  QJsonObject v3d;
  v3d["triangles"] = qint64(w.view3d()->mesh_triangles());
  v3d["widget"] = QJsonArray{w.view3d()->width(), w.view3d()->height()};
  {
    ImageView probe("3d");
    probe.SetImage(v3, {});
    v3d["distinct_levels"] = probe.DistinctLevels();
  }
  v3d["width"] = v3.width();
  v3d["height"] = v3.height();
  report["view3d"] = v3d;
  report["frames_processed"] = w.latest() ? w.latest()->report.index + 1 : 0;
  // The scan's rate as the studio ran it (frames between the first and the last snapshot over
  // that time), and how often the 3-D view's surface was refreshed meanwhile.
  const double scan_s = double(st.scan_last_ms - st.scan_first_ms) / 1000.0;
  report["scan_seconds"] = scan_s;
  report["scan_fps"] = scan_s > 0 ? double(st.scan_last_frame - st.scan_first_frame) / scan_s : 0.0;
  report["mesh_updates"] = st.mesh_updates;
  report["mesh_updates_per_s"] = scan_s > 0 ? double(st.mesh_updates_in_scan) / scan_s : 0.0;
  report["frames_shown"] = w.frames_shown();
  // Where the window's time went, and every thread's CPU (the scan's, the window's, the
  // mesher's, software OpenGL's).
  QJsonObject display;
  display["views_cpu_ms"] = st.views_ms;
  display["views_interval_ms"] = w.views_interval_ms();
  display["mesh_handover_cpu_ms"] = st.mesh_handover_ms;
  display["preview_step"] = w.preview_step();  // the surface's lattice while the scan ran (last)
  display["redraws"] = w.view3d()->redraws();
  display["redraw_ms"] = w.view3d()->redraw_ms();
  report["display"] = display;
  report["cpu_seconds_by_thread"] = CpuSecondsByThread();
  report["health"] = w.health_text();
  report["error"] = w.error_text();
  // The error shown whole: its label as tall as its text needs at its width, and inside the
  // status panel.
  if (const std::optional<bool> fits = w.error_fits()) report["error_fits"] = *fits;
  report["window"] = QJsonArray{window.width(), window.height()};
  if (const QScreen* screen = QGuiApplication::primaryScreen())
    report["screen"] = QJsonArray{screen->availableGeometry().width(), screen->availableGeometry().height()};
  // The controls panel shows its content whole (never cut at the right).
  if (auto* area = qobject_cast<QScrollArea*>(w.dock("controls")->widget()))
    report["controls_fit"] = area->viewport()->width() >= area->widget()->minimumSizeHint().width();
  report["language"] = qApp->property("hdrf_language").toString();
  return report;
}

}  // namespace hdrf::gui
