#include "gui/main_window.h"

#include "gui/export_dialog.h"
#include "io/project.h"

#include "calibration_wizard/calibration_wizard.h"
#include "gui/language/language.h"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QComboBox>
#include <QDateTime>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QLocale>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QLineEdit>
#include <QPixmap>
#include <QMenuBar>
#include <QMessageBox>
#include <QProgressDialog>
#include <QPushButton>
#include <QScrollArea>
#include <QScreen>
#include <QScrollBar>
#include <QSettings>
#include <QActionGroup>
#include <QSlider>
#include <QSpinBox>
#include <QStatusBar>
#include <QTimer>
#include <QVBoxLayout>
#include <cmath>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <omp.h>
#include <unistd.h>

#include "common/cuda_runtime.h"
#include "common/error.h"
#include "gui/display_pacer.h"
#include "gui/exposure_plot.h"
#include "gui/tone_panel.h"
#include "gui/image_view.h"
#include "gui/sensor_panel.h"
#include "gui/stage_images.h"
#include "gui/stage_views.h"
#include "gui/status_panel.h"
#include "gui/window_report.h"
#include "gui/settings_form.h"
#include "gui/vtk_view.h"
#include "io/exr.h"
#include "tonemap/display.h"

namespace hdrf::gui {

namespace {
// This thread's CPU time, milliseconds.
double ThreadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
}
}  // namespace

namespace {

// A panel in a scroll area: a long form never makes the window taller than the screen.
QScrollArea* Scrolled(QWidget* w) {
  auto* area = new QScrollArea;
  area->setWidget(w);
  area->setWidgetResizable(true);
  area->setFrameShape(QFrame::NoFrame);
  area->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  // Never narrower than the content (nothing cut off at the right).
  area->setMinimumWidth(w->minimumSizeHint().width() + area->verticalScrollBar()->sizeHint().width() + 4);
  return area;
}

const char* kSynthRoom = "synthetic:scene=room,frames=300,ae=flicker";
const char* kSynthDesk = "synthetic:scene=desk,frames=300,ae=smooth";

}  // namespace

MainWindow::MainWindow(const StudioOptions& o, QWidget* parent) : QMainWindow(parent), opts_(o) {
  setWindowTitle(tr("HDRFusion Studio"));
  setObjectName("HDRFusionStudio");
  window_threads_ = omp_get_max_threads();
  tone_ = std::make_unique<ToneMapper>();
  BuildViews();
  BuildControls();
  BuildStatus();
  BuildSensorPanel();
  BuildMenus();
  ArrangeForScreen();
  default_state_ = saveState();
  LoadSettings();
  if (!o.source.isEmpty()) source_->setCurrentText(o.source);
  source_->lineEdit()->setCursorPosition(0);  // a long spec shows from its start
  if (source_->currentText().startsWith("openni:")) ShowCameraPanel();
  if (o.device == "cpu" || o.device == "cuda") engine_->SetValue("device", o.device.toStdString());
  // The Mantiuk operators run where the engine does (CUDA falls back to the CPU; set with
  // the engine settings in ApplyEngineSettings).
  if (!o.tone.isEmpty()) {
    // "mantiuk06,contrast=0.2": the operator, then parameters as on the CLI's --set.
    const tonemap::Spec spec = tonemap::ParseSpec(o.tone.toStdString());  // throws, naming what is wrong
    tone_panel_->SetChoice({spec.op, spec.values});
    tone_->Set(tone_panel_->choice());
  }
  // The scan thread.
  worker_ = new ScanWorker;
  worker_->SetPreviewStep(preview_.Start(full_detail_->isChecked()));
  worker_->moveToThread(&thread_);
  connect(&thread_, &QThread::finished, worker_, &QObject::deleteLater);
  connect(this, &MainWindow::configure, worker_, &ScanWorker::Configure);
  connect(this, &MainWindow::start, worker_, &ScanWorker::Start);
  connect(this, &MainWindow::pause, worker_, &ScanWorker::Pause);
  connect(this, &MainWindow::stop, worker_, &ScanWorker::Stop);
  connect(this, &MainWindow::reset, worker_, &ScanWorker::Reset);
  connect(this, &MainWindow::exportMesh, worker_, &ScanWorker::ExportMesh);
  connect(this, &MainWindow::exportTrajectory, worker_, &ScanWorker::ExportTrajectory);
  connect(this, &MainWindow::exportRender, worker_, &ScanWorker::ExportRender);
  connect(worker_, &ScanWorker::snapshot, this, &MainWindow::OnSnapshot);
  connect(worker_, &ScanWorker::meshUpdated, this, [this](std::shared_ptr<const mesh::Mesh> m, bool last) {
    mesh_latest_ = std::move(m);
    mesh_latest_last_ = last;
    if (last && finish_on_last_mesh_) {
      UpdateMesh();
      QTimer::singleShot(300, this, &MainWindow::FinishScripted);
    }
  });
  connect(worker_, &ScanWorker::failed, this, &MainWindow::OnFailed);
  connect(worker_, &ScanWorker::stateChanged, this, [this](bool running, const QString& msg) {
    scanning_ = running;
    pacer_.Restart();  // the frame the scan stopped at (or its first) at once
    // While scanning the window tone maps on its own thread alone: its OpenMP threads would
    // only contend with the scan's for the cores (and the pacer measures this thread).
    omp_set_num_threads(running ? 1 : window_threads_);
    worker_->SetImagesIntervalMs(0);  // every frame's until the pacer has measured
    // Each scan's preview starts at every other voxel (UpdateMesh coarsens it on a slow display).
    if (running) worker_->SetPreviewStep(preview_.Start(full_detail_->isChecked()));
    view3d_->SetRenderScale(running ? preview_.render_scale() : 1.0);  // stopped: every pixel
    statusBar()->showMessage(msg);
    start_->setEnabled(!running);
    pause_->setEnabled(running);
  });
  connect(worker_, &ScanWorker::exportDone, this, [this](bool ok, const QString& msg) {
    statusBar()->showMessage(msg, 10000);
    if (!ok && !msg.contains(tr("cancelled"))) QMessageBox::warning(this, tr("Export"), msg);
  });
  connect(worker_, &ScanWorker::finished, this, [this](int) {
    if (opts_.screenshot.isEmpty()) return;
    // The shot once the surface of the last frame is drawn (it may have come already).
    if (mesh_latest_last_) {
      QTimer::singleShot(300, this, &MainWindow::FinishScripted);
    } else {
      finish_on_last_mesh_ = true;
      QTimer::singleShot(60000, this, &MainWindow::FinishScripted);
    }
  });
  connect(worker_, &ScanWorker::projectSaved, this, [this](bool ok, const QString& path, const QString& msg) {
    if (!ok) {
      OnFailed(msg);
      return;
    }
    project_path_ = path;
    setWindowTitle(tr("HDRFusion Studio — %1").arg(QFileInfo(path).fileName()));
    statusBar()->showMessage(msg, 15000);
    if (!recovered_from_.isEmpty() && path != recovered_from_) {
      std::error_code ec;
      std::filesystem::remove(recovered_from_.toStdString(), ec);
      recovered_from_.clear();
    }
  });
  connect(worker_, &ScanWorker::projectOpened, this,
          [this](const ScanSettings& s, const QString& path, const QString& msg) {
            project_path_ = path;
            setWindowTitle(tr("HDRFusion Studio — %1").arg(QFileInfo(path).fileName()));
            // A recovered autosave is not the user's project: Save asks where, and the
            // autosave goes once the scan is saved there.
            if (std::filesystem::path(path.toStdString()).parent_path() == io::RecoveryFolder()) {
              recovered_from_ = path;
              project_path_.clear();
              setWindowTitle(tr("HDRFusion Studio — recovered scan (not saved)"));
            }
            // The form and the source show what the project was scanned with.
            if (source_->findText(QString::fromStdString(s.source)) < 0) source_->addItem(QString::fromStdString(s.source));
            source_->setCurrentText(QString::fromStdString(s.source));
            engine_->SetOptions(s.pipeline);
            statusBar()->showMessage(msg, 30000);
          });
  ConnectSensors();
  thread_.start();
  render_timer_ = new QTimer(this);
  connect(render_timer_, &QTimer::timeout, this, [this] { Render(); });
  render_timer_->start(40);
  ApplyEngineSettings();
  if (!o.project.isEmpty()) OpenProject(o.project);
  if (o.autostart || !o.screenshot.isEmpty()) QTimer::singleShot(0, this, &MainWindow::StartScan);
  if (o.offer_recovery && o.screenshot.isEmpty()) QTimer::singleShot(0, this, &MainWindow::OfferRecovery);
}

MainWindow::~MainWindow() {
  hotplug_.reset();  // no more events into this window
  // A user's scan with frames not saved is autosaved for the next start; a scripted run
  // (screenshots for tests and docs) leaves nothing behind.
  if (worker_)
    QMetaObject::invokeMethod(worker_, opts_.screenshot.isEmpty() ? &ScanWorker::Shutdown : &ScanWorker::Pause,
                              Qt::BlockingQueuedConnection);
  thread_.quit();
  thread_.wait();
}

void MainWindow::BuildViews() {
  view3d_ = new VtkView(this);
  setCentralWidget(view3d_);
  stage_views_.Build(this);
  for (ImageView* v : views_)
    connect(v, &ImageView::status, this, [this](const QString& m) { statusBar()->showMessage(m, 5000); });
}

// The default sizes of the panels, and on a screen under 1000 px of free height (a 1366x768
// laptop) fewer views side by side: there seven views cannot stand in two columns above the
// status panel and stay legible, so they share tabs in pairs. The Live camera panel shares a
// tab with the status panel at every size (it comes to the front when a camera is chosen).
void MainWindow::ArrangeForScreen() {
  const QScreen* screen = QGuiApplication::primaryScreen();
  const bool compact = screen && screen->availableGeometry().height() < 1000;
  if (compact) {
    tabifyDockWidget(docks_["colour"], docks_["depth"]);
    tabifyDockWidget(docks_["radiance"], docks_["nr"]);
    tabifyDockWidget(docks_["model_radiance"], docks_["model_normals"]);
    for (const char* k : {"colour", "radiance", "model_radiance"}) docks_[k]->raise();
  }
  const int column = compact ? 245 : 270;
  resizeDocks({docks_["controls"], docks_["colour"], docks_["confidence"]}, {compact ? 330 : 360, column, column},
              Qt::Horizontal);
  resizeDocks({docks_["status"]}, {compact ? 170 : 190}, Qt::Vertical);
}

void MainWindow::BuildControls() {
  auto* w = new QWidget;
  auto* layout = new QVBoxLayout(w);
  // Source and transport.
  auto* src = new QGroupBox(tr("Source"));
  auto* sl = new QVBoxLayout(src);
  source_ = new QComboBox;
  source_->setEditable(true);
  source_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  source_->setMinimumContentsLength(24);
  source_->addItems({kSynthRoom, kSynthDesk});
  source_->setToolTip(tr("A sequence folder, a recording FILE.oni, a live camera openni:device=SERIAL,mode=vga "
                         "(the Live camera panel fills it in), or synthetic:key=value,... (keys scene=, seed=, "
                         "frames=, ae=, exposure=, size=)"));
  auto* browse = new QPushButton(tr("Sequence folder…"));
  connect(browse, &QPushButton::clicked, this, [this] {
    const QString dir = QFileDialog::getExistingDirectory(this, tr("Recorded sequence"));
    if (!dir.isEmpty()) {
      source_->setCurrentText(dir);
      ApplyEngineSettings();
    }
  });
  sl->addWidget(source_);
  sl->addWidget(browse);
  auto* transport = new QHBoxLayout;
  start_ = new QPushButton(tr("Start"));
  pause_ = new QPushButton(tr("Pause"));
  stop_ = new QPushButton(tr("Stop"));
  reset_ = new QPushButton(tr("Reset"));
  pause_->setEnabled(false);
  for (auto* b : {start_, pause_, stop_, reset_}) transport->addWidget(b);
  sl->addLayout(transport);
  connect(start_, &QPushButton::clicked, this, &MainWindow::StartScan);
  connect(pause_, &QPushButton::clicked, this, &MainWindow::PauseScan);
  connect(stop_, &QPushButton::clicked, this, &MainWindow::StopScan);
  connect(reset_, &QPushButton::clicked, this, &MainWindow::ResetScan);
  layout->addWidget(src);
  // Engine.
  auto* eng = new QGroupBox(tr("Engine (applies on Reset)"));
  auto* el = new QVBoxLayout(eng);
  engine_ = new SettingsForm;
  el->addWidget(engine_);
  layout->addWidget(eng);
  // Tone mapping.
  auto* tone = new QGroupBox(tr("Tone mapping (OpenColorIO %1 / %2)").arg(tone_->display(), tone_->view()));
  auto* tf = new QVBoxLayout(tone);
  tone_panel_ = new TonePanel;
  tf->addWidget(tone_panel_);
  connect(tone_panel_, &TonePanel::changed, this, [this](const ToneChoice& c) {
    try {
      tone_->Set(c);
    } catch (const std::exception& e) {
      statusBar()->showMessage(QString::fromUtf8(e.what()), 8000);
      return;
    }
    shown_.reset();  // redraw with the new mapping; the scan itself runs on
    mesh_shown_.reset();
  });
  layout->addWidget(tone);
  layout->addStretch(1);
  auto* dock = new QDockWidget(tr("Controls"), this);
  dock->setObjectName("dock_controls");
  dock->setWidget(Scrolled(w));
  addDockWidget(Qt::LeftDockWidgetArea, dock);
  docks_["controls"] = dock;
  // The controls take the window's whole height; status and camera panels sit under the views.
  setCorner(Qt::BottomLeftCorner, Qt::LeftDockWidgetArea);
  setCorner(Qt::TopLeftCorner, Qt::LeftDockWidgetArea);
}

void MainWindow::BuildStatus() {
  status_ = new StatusPanel;
  auto* dock = new QDockWidget(tr("Status"), this);
  dock->setObjectName("dock_status");
  dock->setWidget(status_);
  addDockWidget(Qt::BottomDockWidgetArea, dock);
  docks_["status"] = dock;
}

void MainWindow::BuildSensorPanel() {
  sensor_panel_ = new SensorPanel;
  auto* dock = new QDockWidget(tr("Live camera"), this);
  dock->setObjectName("dock_sensor");
  dock->setWidget(Scrolled(sensor_panel_));
  dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable | QDockWidget::DockWidgetClosable);
  addDockWidget(Qt::BottomDockWidgetArea, dock);
  docks_["sensor"] = dock;
  // A tab beside the status panel: the picture and the model stay in sight while the camera
  // is set up, and the wide, short space suits the panel's three columns.
  tabifyDockWidget(docks_["status"], dock);
  docks_["status"]->raise();
  connect(sensor_panel_, &SensorPanel::openCamera, this, [this](const QString& spec) {
    source_->setCurrentText(spec);
    ShowCameraPanel();
    ResetScan();
  });
}

void MainWindow::ConnectSensors() {
  // Every camera request is a queued call on the scan thread (its command queue).
  connect(sensor_panel_, &SensorPanel::refresh, worker_, &ScanWorker::ListSensors);
  connect(sensor_panel_, &SensorPanel::controls, worker_, &ScanWorker::SetCameraControls);
  connect(sensor_panel_, &SensorPanel::startRecording, worker_, &ScanWorker::StartRecording);
  connect(sensor_panel_, &SensorPanel::stopRecording, worker_, &ScanWorker::StopRecording);
  connect(worker_, &ScanWorker::sensorsListed, sensor_panel_, &SensorPanel::ShowSensors);
  connect(worker_, &ScanWorker::recordingDone, this, [this](bool ok, const QString& msg) {
    sensor_panel_->RecordingFinished(ok, msg);
    statusBar()->showMessage(msg, 15000);
  });
  connect(worker_, &ScanWorker::cameraLost, this, [this](const QString& msg) {
    camera_lost_ = true;
    OnFailed(msg);
    sensor_panel_->ShowNoCamera(msg);
    start_->setText(tr("Resume"));
  });
  connect(worker_, &ScanWorker::cameraBack, this, [this](const QString& msg) {
    camera_lost_ = false;
    status_->ClearError();
    start_->setText(tr("Start"));
    statusBar()->showMessage(msg, 15000);
  });
  try {
    hotplug_ = std::make_unique<sensors::HotplugMonitor>([this](const std::string& uri, bool connected) {
      const QString u = QString::fromStdString(uri);
      QMetaObject::invokeMethod(this, [this, u, connected] { OnPlug(u, connected); }, Qt::QueuedConnection);
    });
    QMetaObject::invokeMethod(worker_, &ScanWorker::ListSensors, Qt::QueuedConnection);
  } catch (const std::exception& e) {
    sensor_panel_->ShowNoCamera(tr("Live cameras are unavailable: %1").arg(QString::fromStdString(e.what())));
  }
}

void MainWindow::OnPlug(const QString& uri, bool connected) {
  statusBar()->showMessage(connected ? tr("Camera connected: %1").arg(uri) : tr("Camera disconnected: %1").arg(uri), 10000);
  if (connected)
    QMetaObject::invokeMethod(worker_, "DeviceConnected", Qt::QueuedConnection, Q_ARG(QString, uri));
  else
    QMetaObject::invokeMethod(worker_, &ScanWorker::ListSensors, Qt::QueuedConnection);
}

void MainWindow::ShowCameraPanel() {
  docks_["colour"]->raise();
  docks_["sensor"]->show();
  docks_["sensor"]->raise();

}

ScanSettings MainWindow::CurrentSettings() const {
  ScanSettings s;
  s.source = source_->currentText().toStdString();
  s.pipeline = engine_->Options();  // throws SettingError naming the setting
  return s;
}

void MainWindow::ApplyEngineSettings() {
  status_->HideError();
  try {
    emit configure(CurrentSettings());
    tone_->SetDevice(engine_->Value("device") == "cuda" ? Device::kCuda : Device::kCpu);
    shown_.reset();
  } catch (const Error& e) {
    OnFailed(tr("Engine settings: %1").arg(QString::fromStdString(e.what())));
  }
}

void MainWindow::StartScan() {
  status_->HideError();
  emit start();
}
void MainWindow::PauseScan() { emit pause(); }
void MainWindow::StopScan() { emit stop(); }
void MainWindow::ResetScan() {
  latest_.reset();
  shown_.reset();
  ApplyEngineSettings();
}

void MainWindow::OnSnapshot(std::shared_ptr<const Snapshot> s) {
  latest_ = std::move(s);  // older ones not shown yet are simply dropped
  if (latest_->has_images) images_snap_ = latest_;
  if (!latest_->preview) {
    const qint64 now = QDateTime::currentMSecsSinceEpoch();
    if (stats_.scan_first_ms < 0) stats_.scan_first_ms = now, stats_.scan_first_frame = latest_->report.index;
    stats_.scan_last_ms = now;
    stats_.scan_last_frame = latest_->report.index;
  }
  if (!opts_.screenshot.isEmpty() && opts_.frames > 0 && latest_->report.index + 1 >= opts_.frames) {
    emit pause();
    // The shot once the surface at the stop is drawn (the mesher's last refresh), or after 60 s.
    finish_on_last_mesh_ = true;
    QTimer::singleShot(60000, this, &MainWindow::FinishScripted);
  } else if (opts_.frames > 0 && latest_->report.index + 1 >= opts_.frames) {
    emit pause();
  }
}

void MainWindow::OnFailed(const QString& message) {
  status_->ShowError(message);
  docks_["status"]->show();
  statusBar()->showMessage(message);
  if (!opts_.screenshot.isEmpty()) QTimer::singleShot(300, this, &MainWindow::FinishScripted);
}

QString MainWindow::health_text() const { return status_->health_text(); }
QString MainWindow::error_text() const { return status_->error_text(); }
std::optional<bool> MainWindow::error_fits() const { return status_->ErrorFits(docks_["status"]); }

void MainWindow::RenderPreview(const std::shared_ptr<const Snapshot>& s) {
  stage_views_.ShowCamera(s);
  status_->ShowPreview(s->report.index + 1);
  if (!s->trajectory.empty()) view3d_->SetTrajectory(s->trajectory.span(), s->camera);
}

void MainWindow::TellShownViews() { worker_->SetShownViews(stage_views_.Shown()); }

void MainWindow::UpdateMesh() {
  const qint64 now = QDateTime::currentMSecsSinceEpoch();
  if (!mesh_latest_ || mesh_latest_ == mesh_shown_) return;
  if (mesh_shown_ && now - mesh_time_ms_ < 300 && !mesh_latest_last_) return;
  // How long the display took to redraw the preview shown: a slow one is coarsened.
  if (scanning_ && mesh_shown_ && !mesh_shown_last_ && view3d_->redraws() > 0) {
    worker_->SetPreviewStep(preview_.Redrawn(view3d_->last_redraw_ms()));
    view3d_->SetRenderScale(preview_.render_scale());
  }
  mesh_shown_ = mesh_latest_;
  mesh_shown_last_ = mesh_latest_last_;
  mesh_time_ms_ = now;
  ++stats_.mesh_updates;
  if (stats_.scan_first_ms >= 0 && now <= stats_.scan_last_ms + 100) ++stats_.mesh_updates_in_scan;
  const double t0 = ThreadCpuMs();
  view3d_->SetMesh(*mesh_shown_, tone_->MapColours(mesh_shown_->radiance));
  stats_.mesh_handover_ms += ThreadCpuMs() - t0;
}

void MainWindow::Render(bool now) {
  TellShownViews();
  UpdateMesh();
  const auto s = latest_;
  if (!s || s == shown_) return;
  const double t0 = ThreadCpuMs();
  // The status (tracking health, frame, timings, memory): a change of the tracking's state
  // (StatusPanel::Key) with the snapshot that brings it, so a loss shows at once; its figures at most
  // every kStatusMs while scanning. The views, while a scan runs, at the pacer's rate (the
  // scan keeps the cores).
  const qint64 wall = QDateTime::currentMSecsSinceEpoch();
  if (!s->preview && s != status_shown_ &&
      (now || !scanning_ || wall - status_ms_ >= kStatusMs || StatusPanel::Key(*s) != status_->key_shown())) {
    status_->Show(*s);
    status_shown_ = s;
    status_ms_ = wall;
  }
  if (!now && !s->preview && scanning_ && !pacer_.Due(wall)) {
    stats_.views_ms += ThreadCpuMs() - t0;
    return;
  }
  shown_ = s;
  ++frames_shown_;
  if (scanning_) {
    pacer_.Refreshed(wall, t0);
    // The scan copies the stage images twice per refresh (the views are at most half an
    // interval old); the frame shown is the last that carries them (its colour, status and
    // images all of one frame).
    worker_->SetImagesIntervalMs(int(pacer_.interval_ms() / 2));
  }
  RenderSnapshot(s->preview || s->has_images || !images_snap_ ? s : images_snap_);
  stats_.views_ms += ThreadCpuMs() - t0;
}

void MainWindow::RenderSnapshot(const std::shared_ptr<const Snapshot>& s) {
  if (s->live && !camera_lost_) sensor_panel_->ShowStatus(*s->live);
  if (s->preview) {
    RenderPreview(s);
    return;
  }
  stage_views_.ShowStages(s, *tone_);
  // 3-D view: the trajectory every frame (first: the view starts from the camera's pose),
  // the mesh a few times a second.
  view3d_->SetTrajectory(s->trajectory.span(), s->camera);
  view3d_->SetRegion(s->volume_bounds[0], s->volume_bounds[1]);
  status_->ShowExposure(*s);
}

bool MainWindow::SaveScreenshot(const QString& path) {
  Render(/*now=*/true);
  QApplication::processEvents();
  const QImage shot = grab().toImage();
  bool ok = shot.save(path, "PNG");
  const QJsonObject report = DescribeWindow(*this, shot.size());
  QFile f(path + ".json");
  ok = ok && f.open(QIODevice::WriteOnly) && f.write(QJsonDocument(report).toJson()) > 0;
  return ok;
}

void MainWindow::FinishScripted() {
  if (scripted_done_) return;
  scripted_done_ = true;
  const bool ok = SaveScreenshot(opts_.screenshot);
  std::fprintf(stderr, "hdrfusion-studio: %s %s (%d frames shown)\n", ok ? "saved" : "could not save",
               qPrintable(opts_.screenshot), frames_shown_);
  emit screenshotTaken(ok);
  QApplication::exit(ok ? 0 : 1);
}

void MainWindow::LoadSettings() {
  QSettings s;
  restoreGeometry(s.value("window/geometry").toByteArray());
  restoreState(s.value("window/state").toByteArray());
  if (s.contains("source")) source_->setCurrentText(s.value("source").toString());
  engine_->Load(s);
  // Tone mapping: the operator's key and the values set for it ("tone/<op>/<key>").
  ToneChoice tc;
  tc.op = s.value("tone/op", QString::fromStdString(tc.op)).toString().toStdString();
  s.beginGroup(QStringLiteral("tone/") + QString::fromStdString(tc.op));
  for (const QString& k : s.childKeys()) tc.values[k.toStdString()] = s.value(k).toDouble();
  s.endGroup();
  tone_panel_->SetChoice(tc);
  try {
    tone_->Set(tone_panel_->choice());
  } catch (const std::exception&) {
    tone_->Set({});
  }
}

void MainWindow::SaveSettings() const {
  QSettings s;
  s.setValue("window/geometry", saveGeometry());
  s.setValue("window/state", saveState());
  s.setValue("source", source_->currentText());
  engine_->Save(s);
  const ToneChoice tc = tone_panel_->choice();
  s.setValue("tone/op", QString::fromStdString(tc.op));
  s.remove(QStringLiteral("tone/") + QString::fromStdString(tc.op));
  for (const auto& [k, v] : tc.values) s.setValue(QStringLiteral("tone/%1/%2").arg(QString::fromStdString(tc.op), QString::fromStdString(k)), v);
}

void MainWindow::closeEvent(QCloseEvent* e) {
  SaveSettings();
  e->accept();
}

}  // namespace hdrf::gui
