#include "gui/main_window.h"

#include "gui/export_dialog.h"
#include "io/project.h"

#include "calibration_wizard/calibration_wizard.h"
#include "calibration_wizard/translation.h"

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

// The views' pictures are 32-bit RGB, the format Qt paints without converting it first.
QImage FromColor(const ColorImage& c) {
  QImage img(c.width(), c.height(), QImage::Format_RGB32);
  for (int y = 0; y < c.height(); ++y) {
    auto* row = reinterpret_cast<QRgb*>(img.scanLine(y));
    for (int x = 0; x < c.width(); ++x) row[x] = qRgb(c(x, y).r, c(x, y).g, c(x, y).b);
  }
  return img;
}

// A scalar image to grey over [lo, hi]; `valid(v)` false draws dark blue (no data).
template <typename F>
QImage Grey(const Image<float>& im, float lo, float hi, F valid) {
  QImage img(im.width(), im.height(), QImage::Format_RGB32);
  for (int y = 0; y < im.height(); ++y) {
    auto* row = reinterpret_cast<QRgb*>(img.scanLine(y));
    for (int x = 0; x < im.width(); ++x) {
      const float v = im(x, y);
      if (!valid(v)) {
        row[x] = qRgb(0, 0, 40);
        continue;
      }
      const int g = int(std::lround(255.f * std::clamp((v - lo) / (hi - lo), 0.f, 1.f)));
      row[x] = qRgb(g, g, g);
    }
  }
  return img;
}

QString Rad(Float3 r) {
  return QObject::tr("radiance %1 %2 %3").arg(r.x, 0, 'g', 4).arg(r.y, 0, 'g', 4).arg(r.z, 0, 'g', 4);
}

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

void MainWindow::OpenProject(const QString& path) {
  HideError();
  latest_.reset();
  shown_.reset();
  QMetaObject::invokeMethod(worker_, [w = worker_, path] { w->OpenProject(path); }, Qt::QueuedConnection);
}

void MainWindow::SaveProject(const QString& path) {
  QString file = path;
  if (file.isEmpty()) {
    file = QFileDialog::getSaveFileName(this, tr("Save the scan as a project"),
                                        project_path_.isEmpty() ? QStringLiteral("scan.hdrproj") : project_path_,
                                        tr("HDRFusion projects (*.hdrproj)"));
    if (file.isEmpty()) return;
    if (!file.endsWith(QStringLiteral(".hdrproj"))) file += QStringLiteral(".hdrproj");
  }
  QMetaObject::invokeMethod(worker_, [w = worker_, file] { w->SaveProject(file); }, Qt::QueuedConnection);
}

QMessageBox* MainWindow::recovery_offer() const { return recovery_offer_.data(); }

// A scan that did not end normally left its last autosave: offered once, without blocking
// (open it, keep it for later, or delete it).
void MainWindow::OfferRecovery() {
  const std::vector<std::filesystem::path> found = io::FindRecoveryFiles();
  if (found.empty()) return;
  const QString file = QString::fromStdString(found.front().string());
  const QDateTime when = QFileInfo(file).lastModified();
  auto* box = new QMessageBox(QMessageBox::Question, tr("Recover a scan"),
                              tr("A scan that did not finish was autosaved on %1:\n%2\n\nOpen it to continue or export "
                                 "it?")
                                  .arg(QLocale().toString(when, QLocale::ShortFormat), file),
                              QMessageBox::NoButton, this);
  QPushButton* open = box->addButton(tr("Open"), QMessageBox::AcceptRole);
  QPushButton* discard = box->addButton(tr("Delete it"), QMessageBox::DestructiveRole);
  box->addButton(tr("Later"), QMessageBox::RejectRole);
  box->setAttribute(Qt::WA_DeleteOnClose);
  connect(box, &QMessageBox::buttonClicked, this, [this, box, open, discard, file](QAbstractButton* b) {
    if (b == open) {
      OpenProject(file);
    } else if (b == discard) {
      std::error_code ec;
      std::filesystem::remove(file.toStdString(), ec);
    }
    box->close();
  });
  recovery_offer_ = box;
  box->setWindowModality(Qt::NonModal);
  box->show();
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
  struct V {
    const char* key;
    QString title;
    Qt::DockWidgetArea area;
  };
  // Two columns of views right of the 3-D view: what the camera delivers and the radiance
  // made of it, then what the engine derives and the model.
  const V defs[] = {{"colour", tr("Colour (as delivered)"), Qt::RightDockWidgetArea},
                    {"depth", tr("Depth"), Qt::RightDockWidgetArea},
                    {"radiance", tr("Radiance (tone-mapped)"), Qt::RightDockWidgetArea},
                    {"nr", tr("Normalized radiance"), Qt::RightDockWidgetArea},
                    {"confidence", tr("Confidence (PCF)"), Qt::RightDockWidgetArea},
                    {"model_radiance", tr("Model radiance (ray cast)"), Qt::RightDockWidgetArea},
                    {"model_normals", tr("Model normals (ray cast)"), Qt::RightDockWidgetArea}};
  for (const V& d : defs) {
    auto* v = new ImageView(d.title, this);
    connect(v, &ImageView::status, this, [this](const QString& m) { statusBar()->showMessage(m, 5000); });
    auto* dock = new QDockWidget(d.title, this);
    dock->setObjectName(QString("dock_") + d.key);
    dock->setWidget(v);
    dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable |
                      QDockWidget::DockWidgetClosable);
    addDockWidget(d.area, dock);
    views_[d.key] = v;
    docks_[d.key] = dock;
  }
  splitDockWidget(docks_["colour"], docks_["confidence"], Qt::Horizontal);
  splitDockWidget(docks_["colour"], docks_["depth"], Qt::Vertical);
  splitDockWidget(docks_["depth"], docks_["radiance"], Qt::Vertical);
  splitDockWidget(docks_["radiance"], docks_["nr"], Qt::Vertical);
  splitDockWidget(docks_["confidence"], docks_["model_radiance"], Qt::Vertical);
  splitDockWidget(docks_["model_radiance"], docks_["model_normals"], Qt::Vertical);
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
  auto* w = new QWidget;
  auto* l = new QVBoxLayout(w);
  frames_label_ = new QLabel(tr("No frame yet"));
  health_ = new QLabel(tr("Tracking: -"));
  health_->setObjectName("health");
  health_->setWordWrap(true);
  reloc_caption_ = new QLabel;
  reloc_caption_->setWordWrap(true);
  reloc_caption_->hide();
  reloc_hint_ = new QLabel;
  reloc_hint_->setObjectName("reloc_hint");
  reloc_hint_->hide();
  error_ = new QLabel;
  error_->setObjectName("error");
  error_->setWordWrap(true);
  error_->setStyleSheet("QLabel { color: white; background: #a02020; padding: 4px; }");
  error_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  error_->hide();
  // Stage times as a grid of plain labels made once (a rich-text table re-laid out its whole
  // document on every frame): names left, times right-aligned, two column pairs.
  stages_ = new QWidget;
  auto* grid = new QGridLayout(stages_);
  grid->setContentsMargins(0, 0, 0, 0);
  grid->setHorizontalSpacing(6);
  grid->setVerticalSpacing(0);
  grid->setColumnMinimumWidth(2, 10);
  const QString stage_names[] = {tr("convert"), tr("normalize"), tr("track"), tr("compensate"), tr("integrate"), tr("ray cast")};
  for (int i = 0; i < 6; ++i) {
    grid->addWidget(new QLabel(stage_names[i]), i / 2, 3 * (i % 2));
    stage_ms_[i] = new QLabel;
    stage_ms_[i]->setAlignment(Qt::AlignRight | Qt::AlignVCenter);
    grid->addWidget(stage_ms_[i], i / 2, 3 * (i % 2) + 1);
  }
  auto* total = new QLabel(tr("total"));
  QFont bold = total->font();
  bold.setBold(true);
  total->setFont(bold);
  grid->addWidget(total, 3, 0);
  stage_ms_[6] = new QLabel;
  stage_ms_[6]->setFont(bold);
  stage_ms_[6]->setAlignment(Qt::AlignRight | Qt::AlignVCenter);
  grid->addWidget(stage_ms_[6], 3, 1, 1, 4);
  grid->setColumnStretch(5, 1);
  memory_ = new QLabel;
  memory_->setObjectName("memory");
  memory_->setWordWrap(true);
  plot_ = new ExposurePlot;
  // Text on the left, the exposure plot beside it: the panel stays short enough for a
  // 1366x768 screen.
  auto* text = new QVBoxLayout;
  for (QWidget* x : {static_cast<QWidget*>(frames_label_), static_cast<QWidget*>(health_),
                     static_cast<QWidget*>(reloc_caption_), static_cast<QWidget*>(reloc_hint_),
                     static_cast<QWidget*>(error_), static_cast<QWidget*>(stages_), static_cast<QWidget*>(memory_)})
    text->addWidget(x);
  text->addStretch(1);
  auto* row = new QHBoxLayout;
  row->addLayout(text, 3);
  row->addWidget(plot_, 2);
  l->addLayout(row);
  auto* dock = new QDockWidget(tr("Status"), this);
  dock->setObjectName("dock_status");
  dock->setWidget(w);
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
    HideError();
    error_->clear();
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

ExportDialog* MainWindow::OpenExportDialog() {
  if (!export_dialog_) {
    const ToneChoice tc = tone_panel_->choice();
    auto* dlg = new ExportDialog(QString::fromStdString(tonemap::FormatSpec({tc.op, tc.values})), this);
    dlg->setAttribute(Qt::WA_DeleteOnClose);
    connect(dlg, &ExportDialog::exportRequested, this, [this](const QString& folder, const io::AssetOptions& o) {
      worker_->ArmExport();
      QMetaObject::invokeMethod(worker_, [w = worker_, folder, o] { w->ExportAsset(folder, o); }, Qt::QueuedConnection);
    });
    connect(dlg, &ExportDialog::cancelRequested, this, [this] { worker_->CancelExport(); });
    connect(worker_, &ScanWorker::assetProgress, dlg, &ExportDialog::OnProgress);
    connect(worker_, &ScanWorker::assetDone, dlg, &ExportDialog::OnDone);
    export_dialog_ = dlg;
  }
  export_dialog_->show();
  export_dialog_->raise();
  return export_dialog_;
}

QString MainWindow::source_text() const { return source_->currentText(); }
bool MainWindow::start_enabled() const { return start_->isEnabled(); }

void MainWindow::BuildMenus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  QMenu* exp = file->addMenu(tr("&Export"));
  exp->addAction(tr("Textured HDR asset (OBJ, glTF, OpenEXR)…"), this, [this] { OpenExportDialog(); });
  exp->addAction(tr("HDR mesh (PLY)…"), this, [this] {
    const QString p = QFileDialog::getSaveFileName(this, tr("Export HDR mesh"), "mesh.ply", tr("PLY (*.ply)"));
    if (p.isEmpty()) return;
    auto* dlg = new QProgressDialog(tr("Extracting and writing the mesh…"), tr("Cancel"), 0, 100, this);
    dlg->setAttribute(Qt::WA_DeleteOnClose);
    dlg->setMinimumDuration(300);
    connect(dlg, &QProgressDialog::canceled, this, [this] { worker_->CancelExport(); });
    connect(worker_, &ScanWorker::exportProgress, dlg, [dlg](double f) { dlg->setValue(int(100 * f)); });
    connect(worker_, &ScanWorker::exportDone, dlg, [dlg](bool, const QString&) { dlg->close(); });
    const ToneChoice tc = tone_panel_->choice();
    emit exportMesh(p, QString::fromStdString(tonemap::FormatSpec({tc.op, tc.values})));
  });
  exp->addAction(tr("Trajectory (TUM)…"), this, [this] {
    const QString p = QFileDialog::getSaveFileName(this, tr("Export trajectory"), "trajectory.txt");
    if (!p.isEmpty()) emit exportTrajectory(p);
  });
  exp->addAction(tr("Model render (OpenEXR)…"), this, [this] {
    const QString p = QFileDialog::getSaveFileName(this, tr("Export model render"), "render.exr", tr("OpenEXR (*.exr)"));
    if (!p.isEmpty()) emit exportRender(p);
  });
  file->addAction(tr("&Open project…"), QKeySequence::Open, this, [this] {
    const QString path = QFileDialog::getOpenFileName(this, tr("Open a scan project"), project_path_,
                                                      tr("HDRFusion projects (*.hdrproj)"));
    if (!path.isEmpty()) OpenProject(path);
  });
  file->addAction(tr("&Save project"), QKeySequence::Save, this, [this] { SaveProject(project_path_); });
  file->addAction(tr("Save project &as…"), QKeySequence::SaveAs, this, [this] { SaveProject(QString()); });
  file->addSeparator();
  file->addAction(tr("Save window screenshot…"), this, [this] {
    const QString p = QFileDialog::getSaveFileName(this, tr("Screenshot"), "studio.png", tr("PNG (*.png)"));
    if (!p.isEmpty()) SaveScreenshot(p);
  });
  file->addSeparator();
  file->addAction(tr("&Quit"), QKeySequence::Quit, this, &QWidget::close);
  QMenu* scan = menuBar()->addMenu(tr("&Scan"));
  scan->addAction(tr("Start"), this, &MainWindow::StartScan);
  scan->addAction(tr("Pause"), this, &MainWindow::PauseScan);
  scan->addAction(tr("Stop"), this, &MainWindow::StopScan);
  scan->addAction(tr("Reset (apply engine settings)"), this, &MainWindow::ResetScan);
  QMenu* tools = menuBar()->addMenu(tr("&Tools"));
  QAction* calibrate = tools->addAction(tr("Calibrate camera…"), this, &MainWindow::OpenCalibrationWizard);
  calibrate->setObjectName("action_calibrate");
  QMenu* view = menuBar()->addMenu(tr("&View"));
  for (auto it = docks_.begin(); it != docks_.end(); ++it) view->addAction(it.value()->toggleViewAction());
  view->addSeparator();
  view->addAction(tr("Reset 3-D view"), this, [this] { view3d_->ResetView(); });
  // The 3-D view's surface while scanning: a coarse preview (the default) or every voxel.
  QAction* full_detail = full_detail_ = view->addAction(tr("Full surface detail while scanning"));
  full_detail->setObjectName("action_full_detail");
  full_detail->setCheckable(true);
  full_detail->setToolTip(tr("Off: while a scan runs the 3-D view shows a coarser surface (from every other voxel, "
                             "a quarter of the triangles; every fourth where the display cannot draw that quickly), "
                             "which leaves more of the processor to the scan; the whole surface follows when the scan "
                             "stops"));
  full_detail->setChecked(QSettings().value("view/full_detail_while_scanning", false).toBool());
  connect(full_detail, &QAction::toggled, this, [this](bool on) {
    worker_->SetPreviewStep(preview_.Start(on));
    QSettings().setValue("view/full_detail_while_scanning", on);
  });
  view->addAction(tr("Restore default layout"), this, [this] {
    restoreState(default_state_);
    for (QDockWidget* d : docks_) d->show();
  });
  // Language: the system's or one chosen here, for the studio and the wizard; it takes
  // effect when the studio starts again (every window is made in its language).
  view->addSeparator();
  QMenu* language = view->addMenu(tr("&Language"));
  language->setObjectName("menu_language");
  auto* languages = new QActionGroup(language);
  const QString saved = wizard::SavedLanguage();
  QStringList codes{QString()};
  codes << wizard::AvailableLanguages();
  for (const QString& code : codes) {
    QAction* a = language->addAction(code.isEmpty() ? tr("As the system") : wizard::LanguageName(code));
    a->setData(code);
    a->setCheckable(true);
    a->setChecked(code == saved);
    languages->addAction(a);
    connect(a, &QAction::triggered, this, [this, code] {
      if (code == wizard::SavedLanguage()) return;
      wizard::SaveLanguage(code);
      statusBar()->showMessage(tr("The language changes when the studio starts again."), 15000);
    });
  }
}

void MainWindow::OpenCalibrationWizard() {
  if (wizard_) {
    wizard_->raise();
    wizard_->activateWindow();
    return;
  }
  // The wizard opens its camera itself: a camera the studio has open shows as in use there
  // until the studio's preview or scan is stopped.
  wizard_ = new wizard::CalibrationWizard(wizard::WizardSettings{}, this);
  wizard_->setAttribute(Qt::WA_DeleteOnClose);
  connect(wizard_, &wizard::CalibrationWizard::saved, this, [this](const QString& profile, const QString&) {
    statusBar()->showMessage(tr("Calibration saved: %1 (used from now on for that camera)").arg(profile), 15000);
    QMetaObject::invokeMethod(worker_, &ScanWorker::ListSensors, Qt::QueuedConnection);
  });
  wizard_->show();
}

ScanSettings MainWindow::CurrentSettings() const {
  ScanSettings s;
  s.source = source_->currentText().toStdString();
  s.pipeline = engine_->Options();  // throws SettingError naming the setting
  return s;
}

void MainWindow::ApplyEngineSettings() {
  HideError();
  try {
    emit configure(CurrentSettings());
    tone_->SetDevice(engine_->Value("device") == "cuda" ? Device::kCuda : Device::kCpu);
    shown_.reset();
  } catch (const Error& e) {
    OnFailed(tr("Engine settings: %1").arg(QString::fromStdString(e.what())));
  }
}

void MainWindow::StartScan() {
  HideError();
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
    if (scan_first_ms_ < 0) scan_first_ms_ = now, scan_first_frame_ = latest_->report.index;
    scan_last_ms_ = now;
    scan_last_frame_ = latest_->report.index;
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

// An error takes the place of the stage times and the memory line in the status panel while
// it is shown: the panel keeps the height of its usual content, and a message of three lines
// or more beside them was cut off at both ends (1366x768). The whole message is also the
// label's tooltip and in the status bar, and can be selected and copied.
void MainWindow::ShowError(const QString& message) {
  error_->setText(message);
  error_->setToolTip(message);
  error_->show();
  stages_->hide();
  memory_->hide();
}
void MainWindow::HideError() {
  error_->hide();
  stages_->show();
  memory_->show();
}

void MainWindow::OnFailed(const QString& message) {
  ShowError(message);
  docks_["status"]->show();
  statusBar()->showMessage(message);
  if (!opts_.screenshot.isEmpty()) QTimer::singleShot(300, this, &MainWindow::FinishScripted);
}

QString MainWindow::health_text() const { return health_->text(); }
QString MainWindow::error_text() const { return error_->isVisible() || !error_->text().isEmpty() ? error_->text() : QString(); }

// The camera's own images: the colour as delivered and the depth (also the live preview).
void MainWindow::RenderColourAndDepth(const std::shared_ptr<const Snapshot>& s) {
  auto visible = [this](const char* k) { return docks_[k]->isVisible(); };
  if (visible("colour")) {
    views_["colour"]->SetImage(FromColor(s->color), [s](int x, int y) {
      const Rgb8 c = s->color(x, y);
      return QStringLiteral("RGB %1 %2 %3 (8-bit)").arg(c.r).arg(c.g).arg(c.b);
    });
  }
  if (visible("depth") && !s->images.depth.empty()) {
    float hi = 0.5f;
    for (std::size_t i = 0; i < s->images.depth.size(); ++i) hi = std::max(hi, s->images.depth[i]);
    hi = std::min(hi, 8.f);
    const ColorImage cd = tonemap::ColorizeDepth(s->images.depth, 0.f, hi);
    QVector<QRgb> bar;
    DepthImage ramp(1, 64);
    for (int i = 0; i < 64; ++i) ramp(0, i) = std::max(1e-3f, hi * float(i) / 63.f);
    const ColorImage rc = tonemap::ColorizeDepth(ramp, 0.f, hi);
    for (int i = 0; i < 64; ++i) bar.push_back(qRgb(rc(0, i).r, rc(0, i).g, rc(0, i).b));
    views_["depth"]->SetScaleBar(bar, 0, hi, "m");
    views_["depth"]->SetImage(FromColor(cd), [s](int x, int y) {
      const float z = s->images.depth(x, y);
      return z > 0 ? tr("depth %L1 m").arg(z, 0, 'f', 3) : tr("no depth");
    });
  }
}

void MainWindow::RenderPreview(const std::shared_ptr<const Snapshot>& s) {
  RenderColourAndDepth(s);
  const int in_model = s->report.index + 1;
  frames_label_->setText(in_model > 0 ? tr("Live preview (not scanning); the model holds %1 frames").arg(in_model)
                                      : tr("Live preview (not scanning)"));
  if (!s->trajectory.empty()) view3d_->SetTrajectory(s->trajectory.span(), s->camera);
}

void MainWindow::TellShownViews() {
  const auto on = [this](const char* k) { return docks_[k]->isVisible() && !views_[k]->visibleRegion().isEmpty(); };
  pipeline::ViewSet v;
  v.radiance = on("radiance");
  v.confidence = on("confidence");
  v.nr = on("nr");
  v.depth = on("depth");
  v.render = on("model_radiance") || on("model_normals");
  worker_->SetShownViews(v);
}

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
  ++mesh_updates_;
  if (scan_first_ms_ >= 0 && now <= scan_last_ms_ + 100) ++mesh_updates_in_scan_;
  const double t0 = ThreadCpuMs();
  view3d_->SetMesh(*mesh_shown_, tone_->MapColours(mesh_shown_->radiance));
  mesh_handover_ms_ += ThreadCpuMs() - t0;
}

void MainWindow::Render(bool now) {
  TellShownViews();
  UpdateMesh();
  const auto s = latest_;
  if (!s || s == shown_) return;
  const double t0 = ThreadCpuMs();
  // The status (tracking health, frame, timings, memory): a change of the tracking's state
  // (StatusKey) with the snapshot that brings it, so a loss shows at once; its figures at most
  // every kStatusMs while scanning. The views, while a scan runs, at the pacer's rate (the
  // scan keeps the cores).
  const qint64 wall = QDateTime::currentMSecsSinceEpoch();
  if (!s->preview && s != status_shown_ &&
      (now || !scanning_ || wall - status_ms_ >= kStatusMs || StatusKey(*s) != status_key_)) {
    RenderStatus(s);
    status_shown_ = s;
    status_ms_ = wall;
  }
  if (!now && !s->preview && scanning_ && !pacer_.Due(wall)) {
    views_ms_ += ThreadCpuMs() - t0;
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
  views_ms_ += ThreadCpuMs() - t0;
}

void MainWindow::RenderSnapshot(const std::shared_ptr<const Snapshot>& s) {
  if (s->live && !camera_lost_) sensor_panel_->ShowStatus(*s->live);
  if (s->preview) {
    RenderPreview(s);
    return;
  }
  const auto& im = s->images;
  const double t = s->report.timestamp;  // the frame's own time: the curve filters at the real frame rate
  // 2-D views (hidden docks are skipped: they cost nothing).
  // A project just opened has a model but no live frame: its views keep what they showed.
  auto visible = [this, &im](const char* k) {
    const bool live_view = std::strcmp(k, "model_radiance") != 0 && std::strcmp(k, "model_normals") != 0;
    return docks_[k]->isVisible() && (!live_view || !im.radiance.empty());
  };
  if (!s->color.empty()) RenderColourAndDepth(s);
  if (visible("radiance")) {
    views_["radiance"]->SetImage(tone_->Map(im.radiance, ToneView::kLive, t), [s](int x, int y) { return Rad(s->images.radiance(x, y)); },
                                 [s](const QString& p) { io::WriteExr(p.toStdString(), s->images.radiance); });
  }
  // Grey ramps for the grey views' scale bars.
  const auto grey_bar = [] {
    QVector<QRgb> bar;
    for (int i = 0; i < 64; ++i) bar.push_back(qRgb(i * 4 + 3, i * 4 + 3, i * 4 + 3));
    return bar;
  };
  if (visible("nr")) {
    // Normalized radiance: deviations from the local mean in local standard deviations.
    views_["nr"]->SetScaleBar(grey_bar(), -3, 3, tr("std"));
    views_["nr"]->SetImage(Grey(im.nr, -3.f, 3.f, [](float v) { return v != 0.f; }), [s](int x, int y) {
      return QStringLiteral("NR %L1").arg(s->images.nr(x, y), 0, 'f', 3);
    });
  }
  if (visible("confidence")) {
    float mx = 1e-6f;
    for (std::size_t i = 0; i < im.confidence.size(); ++i) mx = std::max(mx, im.confidence[i]);
    views_["confidence"]->SetScaleBar(grey_bar(), 0, mx, tr("PCF"));
    views_["confidence"]->SetImage(Grey(im.confidence, 0.f, mx, [](float) { return true; }), [s](int x, int y) {
      return tr("PCF %L1 (max channel %L2)")
          .arg(s->images.confidence(x, y), 0, 'f', 3)
          .arg(s->images.max_confidence(x, y), 0, 'f', 3);
    });
  }
  if (visible("model_radiance") && !im.render.radiance.empty()) {
    views_["model_radiance"]->SetImage(
        tone_->Map(im.render.radiance, ToneView::kModel, t), [s](int x, int y) { return Rad(s->images.render.radiance(x, y)); },
        [s](const QString& p) { io::WriteExr(p.toStdString(), s->images.render.radiance); });
  }
  if (visible("model_normals") && !im.render.normal.empty()) {
    const auto& n = im.render.normal;
    QImage img(n.width(), n.height(), QImage::Format_RGB32);
    for (int y = 0; y < n.height(); ++y) {
      auto* row = reinterpret_cast<QRgb*>(img.scanLine(y));
      for (int x = 0; x < n.width(); ++x) {
        const Float3 v = n(x, y);
        const bool hit = Length(v) > 0;
        row[x] = hit ? qRgb(int(127.5f * (v.x + 1)), int(127.5f * (v.y + 1)), int(127.5f * (v.z + 1))) : qRgb(0, 0, 40);
      }
    }
    views_["model_normals"]->SetImage(img, [s](int x, int y) {
      const Float3 v = s->images.render.normal(x, y);
      const float d = s->images.render.depth(x, y);
      return d > 0 ? tr("normal %L1 %L2 %L3, depth %L4 m").arg(v.x, 0, 'f', 2).arg(v.y, 0, 'f', 2).arg(v.z, 0, 'f', 2).arg(d, 0, 'f', 3)
                   : tr("no surface");
    });
  }
  // 3-D view: the trajectory every frame (first: the view starts from the camera's pose),
  // the mesh a few times a second.
  view3d_->SetTrajectory(s->trajectory.span(), s->camera);
  view3d_->SetRegion(s->volume_bounds[0], s->volume_bounds[1]);
  plot_->SetSeries(s->exposure_estimated.span(), s->exposure_reported.span());
}

namespace {

// A label's style sheet set only when it changes (setting one re-polishes the widget).
void SetStyle(QLabel* l, const QString& sheet) {
  if (l->styleSheet() != sheet) l->setStyleSheet(sheet);
}

}  // namespace

// What must reach the status panel at once: the tracking's state and its warnings.
QString MainWindow::StatusKey(const Snapshot& s) {
  const auto& r = s.report;
  return QStringList{QString::number(int(r.state)), QString::number(r.fused), QString::number(r.quality < 0.5),
                     QString::number(r.depth_beyond_far > 0.25), QString::fromStdString(r.why),
                     QString::number(s.reloc_hint_frame), QString::number(s.volume_full.empty())}
      .join(QLatin1Char('|'));
}

void MainWindow::RenderStatus(const std::shared_ptr<const Snapshot>& s) {
  status_key_ = StatusKey(*s);
  const auto& r = s->report;
  frames_label_->setText(tr("Frame %1%2 on the %3")
                             .arg(r.index + 1)
                             .arg(s->frames_total > 0 ? QStringLiteral(" / %1").arg(s->frames_total) : QString())
                             .arg(QString::fromStdString(s->device).toUpper()));
  const QString far = r.depth_beyond_far > 0.25
                          ? "\n" + tr("%1 % of the view lies beyond %L2 m, past the model's ray cast: tracking uses "
                                       "nearer surfaces (volume.raycast_far_m)")
                                        .arg(int(100 * r.depth_beyond_far))
                                        .arg(s->raycast_far_m, 0, 'f', 1)
                          : QString();
  using pipeline::FrameState;
  const QString why = wizard::EngineText(r.why);
  if (r.state == FrameState::kWaiting) {
    health_->setText(tr("WAITING: %1").arg(why) + far);
    SetStyle(health_, "QLabel { color: white; background: #a07010; padding: 3px; font-weight: bold; }");
  } else if (r.state == FrameState::kLost) {
    health_->setText(tr("TRACKING LOST: %1 (frame not fused)").arg(why) + far);
    SetStyle(health_, "QLabel { color: white; background: #c03030; padding: 3px; font-weight: bold; }");
  } else if (!r.fused) {
    health_->setText(tr("FOUND AGAIN, CONFIRMING: %1 (frame not fused)").arg(why) + far);
    SetStyle(health_, "QLabel { color: white; background: #a07010; padding: 3px; font-weight: bold; }");
  } else {
    // The quality figure warns before a loss: below one half the operator should slow down.
    const bool slow = r.quality < 0.5;
    health_->setText((slow ? tr("Tracking quality %1 %: SLOW DOWN (%2 % of pixels matched)")
                           : tr("Tracking quality %1 % (%2 % of pixels matched)"))
                         .arg(int(100 * r.quality))
                         .arg(int(100 * r.tracking.inlier_share)) +
                     (r.state == FrameState::kRelocalised ? "\n" + tr("Relocalised from an earlier view") : QString()) +
                     far);
    SetStyle(health_, far.isEmpty() && !slow ? "QLabel { color: white; background: #207040; padding: 3px; }"
                                                  : "QLabel { color: white; background: #a07010; padding: 3px; }");
  }
  if (!s->reloc_hint.empty() && s->reloc_hint_frame != reloc_hint_frame_) {
    reloc_hint_frame_ = s->reloc_hint_frame;
    reloc_hint_->setPixmap(QPixmap::fromImage(FromColor(s->reloc_hint))
                               .scaled(240, 180, Qt::KeepAspectRatio, Qt::SmoothTransformation));
    reloc_hint_->setToolTip(tr("The scan's view at frame %1").arg(s->reloc_hint_frame + 1));
    reloc_caption_->setText(tr("Point the camera where the scan saw this (frame %1):").arg(s->reloc_hint_frame + 1));
    reloc_hint_->show();
    reloc_caption_->show();
  } else if (s->reloc_hint.empty()) {
    reloc_hint_frame_ = -1;
    reloc_hint_->hide();
    reloc_caption_->hide();
  }
  const auto& m = r.ms;
  const double ms[] = {m.convert, m.normalize, m.track, m.compensate, m.integrate, m.raycast};
  for (int i = 0; i < 6; ++i) stage_ms_[i]->setText(tr("%L1 ms").arg(ms[i], 0, 'f', 1));
  stage_ms_[6]->setText(tr("%L1 ms (%L2 frames/s)").arg(m.total(), 0, 'f', 1).arg(m.total() > 0 ? 1000.0 / m.total() : 0.0, 0, 'f', 1));
  memory_->setText(tr("Volume: %L1 of %L2 MiB in %3 bricks")
                       .arg(double(s->volume_bytes) / (1024.0 * 1024.0), 0, 'f', 1)
                       .arg(s->volume_budget_mb, 0, 'f', 0)
                       .arg(s->bricks));
  if (s->gpu_budget_mb > 0 && s->device == "cuda")
    memory_->setText(memory_->text() + "\n" +
                     tr("GPU: %L1 of %L2 MiB, %3 bricks; host memory: %4 bricks (%5 moved out, %6 back)")
                         .arg(double(s->streaming.gpu_bytes) / (1024.0 * 1024.0), 0, 'f', 1)
                         .arg(s->gpu_budget_mb, 0, 'f', 0)
                         .arg(s->streaming.gpu_bricks)
                         .arg(s->streaming.host_bricks)
                         .arg(s->streaming.swapped_out)
                         .arg(s->streaming.swapped_in));
  if (!s->volume_full.empty()) {
    memory_->setText(memory_->text() + "\n" +
                     tr("VOLUME FULL: %1. New surfaces are not added; the model is kept and can be saved and "
                        "exported.").arg(QString::fromStdString(s->volume_full)));
    SetStyle(memory_, "QLabel { color: white; background: #b06010; padding: 3px; }");
  } else {
    SetStyle(memory_, QString());
  }
}

bool MainWindow::SaveScreenshot(const QString& path) {
  Render(/*now=*/true);
  QApplication::processEvents();
  const QImage shot = grab().toImage();
  bool ok = shot.save(path, "PNG");
  QJsonObject report;
  QJsonObject views;
  for (auto it = views_.begin(); it != views_.end(); ++it) {
    QJsonObject v;
    v["width"] = it.value()->image().width();
    v["height"] = it.value()->image().height();
    v["distinct_levels"] = it.value()->DistinctLevels();
    v["visible"] = docks_[it.key()]->isVisible();
    // On screen now (not behind another tab) and how large its picture is drawn there.
    v["on_screen"] = !it.value()->visibleRegion().isEmpty();
    v["shown"] = QJsonArray{it.value()->ImageRect().width(), it.value()->ImageRect().height()};
    v["tabbed"] = !tabifiedDockWidgets(docks_[it.key()]).isEmpty();
    views[it.key()] = v;
  }
  report["views"] = views;
  const QImage v3 = view3d_->Capture();
  QJsonObject v3d;
  v3d["triangles"] = qint64(view3d_->mesh_triangles());
  v3d["widget"] = QJsonArray{view3d_->width(), view3d_->height()};
  {
    ImageView probe("3d");
    probe.SetImage(v3, {});
    v3d["distinct_levels"] = probe.DistinctLevels();
  }
  v3d["width"] = v3.width();
  v3d["height"] = v3.height();
  report["view3d"] = v3d;
  report["frames_processed"] = latest_ ? latest_->report.index + 1 : 0;
  // The scan's rate as the studio ran it (frames between the first and the last snapshot over
  // that time), and how often the 3-D view's surface was refreshed meanwhile.
  const double scan_s = double(scan_last_ms_ - scan_first_ms_) / 1000.0;
  report["scan_seconds"] = scan_s;
  report["scan_fps"] = scan_s > 0 ? double(scan_last_frame_ - scan_first_frame_) / scan_s : 0.0;
  report["mesh_updates"] = mesh_updates_;
  report["mesh_updates_per_s"] = scan_s > 0 ? double(mesh_updates_in_scan_) / scan_s : 0.0;
  report["frames_shown"] = frames_shown_;
  // Where the window's time went, and every thread's CPU (the scan's, the window's, the
  // mesher's, software OpenGL's).
  QJsonObject display;
  display["views_cpu_ms"] = views_ms_;
  display["views_interval_ms"] = pacer_.interval_ms();
  display["mesh_handover_cpu_ms"] = mesh_handover_ms_;
  display["preview_step"] = preview_.step();  // the surface's lattice while the scan ran (last)
  display["redraws"] = view3d_->redraws();
  display["redraw_ms"] = view3d_->redraw_ms();
  report["display"] = display;
  report["cpu_seconds_by_thread"] = CpuSecondsByThread();
  report["health"] = health_->text();
  report["error"] = error_->text();
  // The error shown whole: its label as tall as its text needs at its width, and inside the
  // status panel.
  if (error_->isVisible()) {
    const QRect in_panel(error_->mapTo(docks_["status"], QPoint(0, 0)), error_->size());
    report["error_fits"] = error_->height() >= error_->heightForWidth(error_->width()) &&
                           docks_["status"]->rect().contains(in_panel);
  }
  report["window"] = QJsonArray{shot.width(), shot.height()};
  if (const QScreen* screen = QGuiApplication::primaryScreen())
    report["screen"] = QJsonArray{screen->availableGeometry().width(), screen->availableGeometry().height()};
  // The controls panel shows its content whole (never cut at the right).
  if (auto* area = qobject_cast<QScrollArea*>(docks_["controls"]->widget()))
    report["controls_fit"] = area->viewport()->width() >= area->widget()->minimumSizeHint().width();
  report["language"] = qApp->property("hdrf_language").toString();
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
