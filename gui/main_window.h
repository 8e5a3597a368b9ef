// The studio's main window: the 3-D view in the centre, every 2-D view and the control and
// status panels as dock widgets (movable, floatable, closable, restored from the View menu,
// layout and settings kept with QSettings), the scan on its own thread.
#pragma once

#include <QMainWindow>
#include <QPointer>
#include <QMap>
#include <QThread>
#include <array>
#include <optional>
#include <memory>

#include "gui/display_pacer.h"
#include "gui/preview_detail.h"
#include "gui/scan_worker.h"
#include "gui/stage_views.h"
#include "gui/tone_mapper.h"
#include "sensors/openni_camera.h"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QSpinBox;
class QSlider;
class QTimer;
class QDockWidget;
class QMessageBox;

namespace hdrf::wizard {
class CalibrationWizard;
}

namespace hdrf::gui {

class SettingsForm;
class SensorPanel;
class StatusPanel;

class ImageView;
class VtkView;

struct StudioOptions {
  QString source;            // empty: the last one used (default: the synthetic room)
  int frames = 0;            // > 0: stop after this many frames
  QString screenshot;        // non-empty: run, save the window and a JSON report, quit
  QString device;            // "", "cpu" or "cuda"
  bool autostart = false;
  QString tone;              // non-empty: tone-mapping operator key, with optional ",key=value,..."
  QString project;           // non-empty: open this project (.hdrproj) at start
  bool offer_recovery = true;  // offer autosaves that a crash left (io::FindRecoveryFiles)
};

class MainWindow : public QMainWindow {
  Q_OBJECT
 public:
  explicit MainWindow(const StudioOptions& o, QWidget* parent = nullptr);
  ~MainWindow() override;

  // For tests: the views by name ("colour", "depth", "radiance", "nr", "confidence",
  // "model_radiance", "model_normals"), the 3-D view, the worker.
  ImageView* view(const QString& name) const { return views_.value(name, nullptr); }
  VtkView* view3d() const { return view3d_; }
  // The 3-D view shows the surface as the scan stopped (the mesher's last refresh).
  bool surface_final() const { return mesh_shown_ && mesh_shown_ == mesh_latest_ && mesh_latest_last_; }
  QDockWidget* dock(const QString& name) const { return docks_.value(name, nullptr); }
  SensorPanel* sensor_panel() const { return sensor_panel_; }
  std::shared_ptr<const Snapshot> latest() const { return latest_; }
  QString source_text() const;
  bool start_enabled() const;
  int frames_shown() const { return frames_shown_; }
  QString health_text() const;
  QString error_text() const;
  std::optional<bool> error_fits() const;  // the error shown whole (none shown: nullopt)
  QStringList view_names() const { return views_.keys(); }
  // How the scan ran as the window saw it and what the window's own work cost (the studio's
  // benchmark and the screenshot's JSON read it: gui/window_report.h): the scan's frames and
  // time between its first and last snapshot, the 3-D view's mesh updates (all, and in that
  // time), and milliseconds of the window thread's CPU in the 2-D views' refreshes and in
  // handing surfaces to the 3-D view.
  struct DisplayStats {
    qint64 scan_first_ms = -1, scan_last_ms = -1;
    int scan_first_frame = -1, scan_last_frame = -1, mesh_updates = 0, mesh_updates_in_scan = 0;
    double views_ms = 0, mesh_handover_ms = 0;
  };
  const DisplayStats& display_stats() const { return stats_; }
  double views_interval_ms() const { return pacer_.interval_ms(); }
  int preview_step() const { return preview_.step(); }
  ScanSettings CurrentSettings() const;
  // File > Export > Textured HDR asset: the dialog (one at a time), wired to the worker.
  class ExportDialog* OpenExportDialog();
  // Writes the window as PNG and per-view statistics as JSON beside it (PATH.json).
  bool SaveScreenshot(const QString& path);
  // Project files: File > Open project, Save project (an empty path asks for one).
  void OpenProject(const QString& path);
  void SaveProject(const QString& path);
  QString project_path() const { return project_path_; }
  // The offer of an autosave a crash left behind (null when none is shown).
  QMessageBox* recovery_offer() const;

 public slots:
  void StartScan();
  void PauseScan();
  void StopScan();
  void ResetScan();

 signals:
  void configure(const hdrf::gui::ScanSettings& s);
  void start();
  void pause();
  void stop();
  void reset();
  void exportMesh(const QString& path, const QString& tone);
  void exportTrajectory(const QString& path);
  void exportRender(const QString& path);
  void screenshotTaken(bool ok);

 protected:
  void closeEvent(QCloseEvent* e) override;

 private:
  void BuildViews();
  void BuildControls();
  void ArrangeForScreen();
  void BuildStatus();
  void BuildMenus();
  void BuildSensorPanel();
  void ConnectSensors();
  void OnPlug(const QString& uri, bool connected);
  void ShowCameraPanel();
  void OpenCalibrationWizard();  // Tools > Calibrate camera (one at a time)  // raises the camera panel and the colour view
  void LoadSettings();
  void SaveSettings() const;
  void OnSnapshot(std::shared_ptr<const Snapshot> s);
  // The latest snapshot into every visible view (timer; while scanning at the pacer's rate,
  // `now`: at once).
  void Render(bool now = false);
  void UpdateMesh();  // the latest surface into the 3-D view, a few times a second
  void TellShownViews();  // which stage images the views on screen need, to the worker
  void RenderPreview(const std::shared_ptr<const Snapshot>& s);
  void RenderSnapshot(const std::shared_ptr<const Snapshot>& s);  // the views of one scan snapshot
  void OnFailed(const QString& message);
  void ApplyEngineSettings();
  void FinishScripted();
  void OfferRecovery();

  StudioOptions opts_;
  QString project_path_;
  QString recovered_from_;  // the autosave opened from the recovery offer, until saved elsewhere
  QPointer<QMessageBox> recovery_offer_;
  QThread thread_;
  ScanWorker* worker_ = nullptr;
  std::unique_ptr<ToneMapper> tone_;
  std::shared_ptr<const Snapshot> latest_, shown_, status_shown_;
  std::shared_ptr<const Snapshot> images_snap_;  // the latest snapshot that carries stage images
  QPointer<wizard::CalibrationWizard> wizard_;
  QPointer<class ExportDialog> export_dialog_;
  std::shared_ptr<const mesh::Mesh> mesh_shown_, mesh_latest_;
  bool mesh_latest_last_ = false;  // mesh_latest_ is the surface at the scan's stop
  bool mesh_shown_last_ = false;   // mesh_shown_ is (a preview while scanning, when false)
  qint64 mesh_time_ms_ = 0;
  bool finish_on_last_mesh_ = false;
  QTimer* render_timer_ = nullptr;
  QMap<QString, ImageView*> views_;
  QMap<QString, QDockWidget*> docks_;
  StageViews stage_views_{views_, docks_};  // fills views_ and their docks in docks_
  VtkView* view3d_ = nullptr;
  QAction* full_detail_ = nullptr;  // View: full surface detail while scanning
  PreviewDetail preview_;  // the surface's detail while scanning
  QComboBox* source_ = nullptr;
  class TonePanel* tone_panel_ = nullptr;
  SettingsForm* engine_ = nullptr;  // generated from the settings registry
  SensorPanel* sensor_panel_ = nullptr;
  std::unique_ptr<sensors::HotplugMonitor> hotplug_;  // events come on OpenNI2's threads
  QPushButton *start_ = nullptr, *pause_ = nullptr, *stop_ = nullptr, *reset_ = nullptr;
  StatusPanel* status_ = nullptr;
  // The status panel while scanning: a change of the tracking's state (a loss, a warning) at
  // once, its figures (frame, times, memory) at most every kStatusMs (text no one can read
  // at the scan's rate costs the window's thread a text layout a frame).
  static constexpr int kStatusMs = 200;
  qint64 status_ms_ = 0;
  int frames_shown_ = 0;
  DisplayStats stats_;
  // The 2-D views' refresh while scanning: the window's thread under kWindowShare of the
  // machine (its other work, the 3-D view's redraws, counts against it too).
  static constexpr double kWindowShare = 0.03;
  DisplayPacer pacer_{kWindowShare, QThread::idealThreadCount()};
  bool scanning_ = false;
  int window_threads_ = 1;  // OpenMP threads of the window's thread when not scanning
  bool scripted_done_ = false;
  bool camera_lost_ = false;  // the live camera is away: late snapshots do not redraw its panel
  QByteArray default_state_;
};

}  // namespace hdrf::gui
