#include "calibration_wizard/wizard_pages.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDateTime>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QFrame>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QImage>
#include <QLabel>
#include <QLineEdit>
#include <QPixmap>
#include <QPlainTextEdit>
#include <QPointer>
#include <QProgressBar>
#include <QPushButton>
#include <QRadioButton>
#include <QSpinBox>
#include <QTimer>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <map>

#include "calibration_wizard/calibration_plots.h"
#include "calibration_wizard/calibration_wizard.h"
#include "calibration_wizard/plot_widget.h"
#include "calibration_wizard/report.h"
#include "calibration_wizard/translation.h"
#include "common/error.h"
#include "io/sensor_json.h"
#include "io/sweep.h"
#include "sensors/profiles.h"
#include "sensors/sweep_cameras.h"

namespace hdrf::wizard {

namespace fs = std::filesystem;

namespace {

QString Q(const std::string& s) { return QString::fromStdString(s); }

QLabel* ProblemLabel(const char* name) {
  auto* l = new QLabel;
  l->setObjectName(name);
  l->setWordWrap(true);
  l->setStyleSheet("color: #b00000; font-weight: bold");
  l->setTextInteractionFlags(Qt::TextSelectableByMouse);
  l->hide();
  return l;
}

void ShowProblem(QLabel* l, const QString& text) {
  l->setText(text);
  l->setVisible(!text.isEmpty());
}

// "R 98 %, G 100 %, B 97 %"
QString CoverageText(const radiometry::LevelCoverage& c) {
  return QString("R %1 %, G %2 %, B %3 %")
      .arg(int(100 * c.share[0] + 0.5))
      .arg(int(100 * c.share[1] + 0.5))
      .arg(int(100 * c.share[2] + 0.5));
}

// A capture in `folder` that stopped before its last step (Resume can complete it).
bool UnfinishedCapture(const fs::path& folder) {
  try {
    if (folder.empty() || !fs::exists(folder / "capture.json")) return false;
    const io::CaptureRecord r = io::ReadCaptureRecord(folder);
    return r.steps_done < int(r.plan.exposures_ms.size());
  } catch (const std::exception&) {
    return false;  // not a record this tool can resume: Start says what is wrong with the folder
  }
}

QString HomePath(const QString& sub) { return QDir::home().filePath("HDRFusion/" + sub); }

// The colour frame with saturated pixels shown red and black ones blue (io::IsSaturated,
// io::IsBlack: what the plan meters), for the Set-up page's preview.
QImage Highlighted(const ColorImage& im, double* high, double* low) {
  QImage q(im.width(), im.height(), QImage::Format_RGB888);
  long h = 0, l = 0;
  for (int y = 0; y < im.height(); ++y) {
    uchar* row = q.scanLine(y);
    for (int x = 0; x < im.width(); ++x) {
      const Rgb8 v = im(x, y);
      uchar* o = row + 3 * x;
      if (io::IsSaturated(v)) {
        o[0] = 255, o[1] = 0, o[2] = 0, ++h;
      } else if (io::IsBlack(v)) {
        o[0] = 0, o[1] = 80, o[2] = 255, ++l;
      } else {
        o[0] = v.r, o[1] = v.g, o[2] = v.b;
      }
    }
  }
  const double n = double(std::max<std::size_t>(im.size(), 1));
  *high = double(h) / n;
  *low = double(l) / n;
  return q;
}

}  // namespace

// ---- Source ---------------------------------------------------------------------------------

SourcePage::SourcePage(CalibrationWizard* w) : w_(w) {
  setTitle(tr("1. Source"));
  setSubTitle(tr("Where the exposure sweep comes from: a camera (captured on the next pages), a sweep "
                 "recorded earlier, or the synthetic sensor (no hardware; its true response is known)."));
  auto* v = new QVBoxLayout(this);
  live_ = new QRadioButton(tr("Live camera (OpenNI2)"));
  live_->setObjectName("source_live");
  folder_ = new QRadioButton(tr("Recorded sweep folder"));
  folder_->setObjectName("source_folder");
  synthetic_ = new QRadioButton(tr("Synthetic sensor"));
  synthetic_->setObjectName("source_synthetic");

  auto* live_box = new QGroupBox;
  auto* lf = new QFormLayout(live_box);
  devices_ = new QComboBox;
  devices_->setObjectName("source_devices");
  devices_->setMinimumContentsLength(40);
  auto* refresh = new QPushButton(tr("Refresh"));
  auto* dev_row = new QHBoxLayout;
  dev_row->addWidget(devices_, 1);
  dev_row->addWidget(refresh);
  lf->addRow(tr("Device:"), dev_row);
  mode_ = new QComboBox;
  mode_->addItem(tr("VGA 640×480"), "vga");
  mode_->addItem(tr("QVGA 320×240"), "qvga");
  lf->addRow(tr("Mode:"), mode_);
  unit_ = new QDoubleSpinBox;
  unit_->setObjectName("source_unit");
  unit_->setRange(0, 10);
  unit_->setDecimals(4);
  unit_->setSpecialValueText(tr("from the profile (else the device's raw unit)"));
  unit_->setSuffix(tr(" ms"));
  unit_->setToolTip(tr("How long one step of the device's exposure setting is. Unknown: exposures are "
                       "recorded in the device's raw unit, which is assumed linear in time."));
  lf->addRow(tr("Exposure step:"), unit_);
  connect(refresh, &QPushButton::clicked, this, &SourcePage::RefreshDevices);

  auto* folder_box = new QGroupBox;
  auto* ff = new QHBoxLayout(folder_box);
  folder_edit_ = new QLineEdit;
  folder_edit_->setObjectName("source_folder_edit");
  folder_edit_->setPlaceholderText(tr("folder with rgb.txt, exposure.txt and sensor.json"));
  auto* browse = new QPushButton(tr("Browse…"));
  ff->addWidget(folder_edit_, 1);
  ff->addWidget(browse);
  connect(browse, &QPushButton::clicked, this, [this] {
    const QString d = QFileDialog::getExistingDirectory(this, tr("Sweep folder"), folder_edit_->text());
    if (!d.isEmpty()) folder_edit_->setText(d);
  });

  auto* syn_box = new QGroupBox;
  auto* sf = new QFormLayout(syn_box);
  response_ = new QComboBox;
  response_->setObjectName("source_response");
  response_->addItem(tr("Asus Xtion (measured)"), "xtion");
  response_->addItem(tr("sRGB"), "srgb");
  response_->addItem(tr("Gamma 2.2"), "gamma2.2");
  response_->addItem(tr("Gamma 1.8"), "gamma1.8");
  response_->addItem(tr("Linear"), "linear");
  response_->addItem(tr("From a sensor.json…"), "file");
  sf->addRow(tr("True response:"), response_);
  response_file_ = new QLineEdit;
  response_file_->setObjectName("source_response_file");
  response_file_->setPlaceholderText(tr("sensor.json whose response (and noise) the sensor takes"));
  sf->addRow(tr("Response file:"), response_file_);
  scene_ = new QComboBox;
  scene_->addItem(tr("Room"), "room");
  scene_->addItem(tr("Desk"), "desk");
  sf->addRow(tr("Scene:"), scene_);
  size_ = new QComboBox;
  size_->addItem("320×240", "320x240");
  size_->addItem("640×480", "640x480");
  size_->addItem("160×120", "160x120");
  sf->addRow(tr("Image size:"), size_);

  v->addWidget(live_);
  v->addWidget(live_box);
  v->addWidget(folder_);
  v->addWidget(folder_box);
  v->addWidget(synthetic_);
  v->addWidget(syn_box);
  error_ = ProblemLabel("source_error");
  v->addWidget(error_);
  v->addStretch(1);
  for (QRadioButton* b : {live_, folder_, synthetic_}) connect(b, &QRadioButton::toggled, this, &SourcePage::UpdateEnabled);
  connect(response_, &QComboBox::currentIndexChanged, this, &SourcePage::UpdateEnabled);
  synthetic_->setChecked(true);
}

void SourcePage::RefreshDevices() {
  devices_->clear();
  try {
    for (const sensors::DeviceEntry& d : sensors::ListDevices())
      devices_->addItem(Q(d.name + (d.serial.empty() ? " (in use?)" : " — " + d.serial)),
                        Q(d.serial.empty() ? d.uri : d.serial));
  } catch (const std::exception& e) {
    ShowProblem(error_, EngineText(e.what()));
  }
  if (devices_->count() == 0) devices_->addItem(tr("no camera connected"), QString());
  UpdateEnabled();
}

void SourcePage::UpdateEnabled() {
  devices_->parentWidget()->setEnabled(live_->isChecked());
  folder_edit_->parentWidget()->setEnabled(folder_->isChecked());
  response_->parentWidget()->setEnabled(synthetic_->isChecked());
  response_file_->setEnabled(response_->currentData().toString() == "file");
  ShowProblem(error_, "");
}

void SourcePage::initializePage() {
  RefreshDevices();
  if (preset_done_) return;
  preset_done_ = true;
  const QString s = w_->settings().source;
  if (s.startsWith("openni:")) {
    // Shown in the page's fields, so that what the operator changes there counts; settings
    // the page has no field for (gain) are kept as given.
    live_->setChecked(true);
    for (const QString& kv : s.mid(7).split(',', Qt::SkipEmptyParts)) {
      const QString k = kv.section('=', 0, 0), val = kv.section('=', 1);
      if (k == "device") {
        if (devices_->findData(val) < 0) devices_->addItem(val, val);
        devices_->setCurrentIndex(devices_->findData(val));
      } else if (k == "mode" && mode_->findData(val) >= 0) {
        mode_->setCurrentIndex(mode_->findData(val));
      } else if (k == "unit") {
        unit_->setValue(val.toDouble());
      } else {
        live_extra_ += "," + kv;
      }
    }
  } else if (s.startsWith("synthetic")) {
    synthetic_->setChecked(true);
    for (const QString& kv : s.mid(s.indexOf(':') + 1).split(',', Qt::SkipEmptyParts)) {
      const QString k = kv.section('=', 0, 0), val = kv.section('=', 1);
      if (k == "response") {
        const int i = response_->findData(val);
        if (i >= 0) {
          response_->setCurrentIndex(i);
        } else {
          response_->setCurrentIndex(response_->findData("file"));
          response_file_->setText(val);
        }
      } else if (k == "scene") {
        scene_->setCurrentIndex(std::max(0, scene_->findData(val)));
      } else if (k == "size") {
        if (size_->findData(val) < 0) size_->addItem(val, val);
        size_->setCurrentIndex(size_->findData(val));
      }
    }
  } else if (!s.isEmpty()) {
    folder_->setChecked(true);
    folder_edit_->setText(s);
  } else if (!devices_->currentData().toString().isEmpty()) {
    live_->setChecked(true);
  }
  if (w_->settings().automatic) QTimer::singleShot(0, w_, [this] { w_->PageDone("source"); });
}

QString SourcePage::Spec() const {
  if (live_->isChecked()) {
    QString spec = "openni:mode=" + mode_->currentData().toString();
    if (!devices_->currentData().toString().isEmpty()) spec += ",device=" + devices_->currentData().toString();
    if (unit_->value() > 0) spec += ",unit=" + QString::number(unit_->value(), 'g', 6);
    return spec + live_extra_;
  }
  if (folder_->isChecked()) return folder_edit_->text().trimmed();
  QString r = response_->currentData().toString();
  if (r == "file") r = response_file_->text().trimmed();
  return "synthetic:response=" + r + ",scene=" + scene_->currentData().toString() + ",size=" +
         size_->currentData().toString();
}

bool SourcePage::validatePage() {
  WizardState& st = w_->state();
  st.camera.reset();
  st.plan.reset();
  st.sweep.reset();
  st.outcome.reset();
  const QString spec = Spec();
  try {
    if (folder_->isChecked()) {
      if (spec.isEmpty()) throw Error(tr("Choose the sweep folder.").toStdString());
      st.sweep_folder = spec.toStdString();
      st.sweep = io::ReadSweep(st.sweep_folder);
      st.sweep_sensor = io::ReadSensorJson(st.sweep_folder / "sensor.json");
      st.sweep_sensor.response.reset();
      st.sweep_sensor.noise.reset();
    } else {
      if (live_->isChecked() && devices_->currentData().toString().isEmpty())
        throw Error(tr("No camera is connected: plug one in and press Refresh, or choose the synthetic sensor.")
                        .toStdString());
      st.camera = sensors::OpenSweepCamera(spec.toStdString());
      st.sweep_sensor = st.camera->sensor();
    }
  } catch (const std::exception& e) {
    ShowProblem(error_, EngineText(e.what()));
    w_->Fail(EngineText(e.what()));
    return false;
  }
  ShowProblem(error_, "");
  return true;
}

int SourcePage::nextId() const {
  return folder_->isChecked() ? CalibrationWizard::kFit : CalibrationWizard::kSetup;
}

// ---- Set-up ---------------------------------------------------------------------------------

SetupPage::SetupPage(CalibrationWizard* w) : w_(w) {
  setTitle(tr("2. Set-up"));
  setSubTitle(tr("Lock the automatic controls, point the camera, and check that the planned sweep covers every "
                 "level before capturing."));
  auto* grid = new QGridLayout(this);
  auto* todo = new QLabel(tr("<b>Before you capture</b><ul>"
                             "<li>Camera on a tripod or a table: it must not move during the sweep.</li>"
                             "<li>A static scene with dark and bright parts and many shades between "
                             "(not a white wall or a grey card); nobody walking through.</li>"
                             "<li>No flickering light: fluorescent tubes and dimmed LEDs change brightness with "
                             "the mains; daylight or incandescent light is steady.</li></ul>"));
  todo->setWordWrap(true);
  grid->addWidget(todo, 0, 0, 1, 2);
  auto* locks = new QGroupBox(tr("Automatic controls"));
  auto* lv = new QVBoxLayout(locks);
  lock_ae_ = new QCheckBox(tr("Lock auto exposure (off)"));
  lock_ae_->setObjectName("setup_lock_ae");
  lock_awb_ = new QCheckBox(tr("Lock white balance (off)"));
  lock_awb_->setObjectName("setup_lock_awb");
  lock_ae_->setChecked(true);
  lock_awb_->setChecked(true);
  lock_state_ = new QLabel;
  lock_state_->setObjectName("setup_lock_state");
  lock_state_->setWordWrap(true);
  lv->addWidget(lock_ae_);
  lv->addWidget(lock_awb_);
  lv->addWidget(lock_state_);
  grid->addWidget(locks, 1, 0);
  auto* plan_box = new QGroupBox(tr("Sweep plan"));
  auto* pf = new QFormLayout(plan_box);
  const io::SweepPlanOptions& o = w_->settings().plan;
  step_ = new QDoubleSpinBox;
  step_->setRange(0.1, 2);
  step_->setSingleStep(0.25);
  step_->setValue(o.step_stops);
  step_->setSuffix(tr(" stops"));
  pf->addRow(tr("Step between exposures:"), step_);
  repeats_ = new QSpinBox;
  repeats_->setObjectName("setup_repeats");
  repeats_->setRange(1, 50);
  repeats_->setValue(o.repeats);
  repeats_->setToolTip(tr("Frames per exposure: 3 or more measure the noise"));
  pf->addRow(tr("Frames per exposure:"), repeats_);
  min_ms_ = new QDoubleSpinBox;
  max_ms_ = new QDoubleSpinBox;
  for (QDoubleSpinBox* b : {min_ms_, max_ms_}) {
    b->setRange(0, 10000);
    b->setDecimals(3);
    b->setSuffix(tr(" ms"));
    b->setSpecialValueText(tr("metered from the scene"));
  }
  min_ms_->setValue(o.min_ms);
  max_ms_->setValue(o.max_ms);
  pf->addRow(tr("Shortest exposure:"), min_ms_);
  pf->addRow(tr("Longest exposure:"), max_ms_);
  plan_button_ = new QPushButton(tr("Check the plan"));
  plan_button_->setObjectName("setup_plan");
  pf->addRow(plan_button_);
  grid->addWidget(plan_box, 2, 0);
  auto* prev_box = new QGroupBox(tr("Preview (red: saturated, blue: black)"));
  auto* pv = new QGridLayout(prev_box);
  preview_ = new QLabel;
  preview_->setObjectName("setup_preview");
  preview_->setMinimumSize(320, 240);
  preview_->setAlignment(Qt::AlignCenter);
  histogram_ = new PlotWidget;
  histogram_->setObjectName("setup_histogram");
  preview_ms_ = new QDoubleSpinBox;
  preview_ms_->setRange(0.01, 10000);
  preview_ms_->setDecimals(2);
  preview_ms_->setValue(10);
  preview_ms_->setSuffix(tr(" ms"));
  pv->addWidget(preview_, 0, 0);
  pv->addWidget(histogram_, 0, 1);
  auto* pe = new QHBoxLayout;
  pe->addWidget(new QLabel(tr("Preview exposure:")));
  pe->addWidget(preview_ms_);
  pe->addStretch(1);
  pv->addLayout(pe, 1, 0, 1, 2);
  grid->addWidget(prev_box, 1, 1, 2, 1);
  plan_label_ = new QLabel;
  plan_label_->setObjectName("setup_plan_label");
  plan_label_->setWordWrap(true);
  grid->addWidget(plan_label_, 3, 0, 1, 2);
  problem_ = ProblemLabel("setup_problem");
  grid->addWidget(problem_, 4, 0, 1, 2);
  grid->setColumnStretch(1, 1);
  grid->setRowStretch(5, 1);
  timer_ = new QTimer(this);
  timer_->setInterval(200);
  connect(timer_, &QTimer::timeout, this, &SetupPage::Preview);
  auto replan = [this] {
    planned_ = false;
    plan_label_->clear();
    emit completeChanged();
  };
  connect(lock_ae_, &QCheckBox::toggled, this, [this, replan] { ApplyLocks(); replan(); });
  connect(lock_awb_, &QCheckBox::toggled, this, [this, replan] { ApplyLocks(); replan(); });
  for (QDoubleSpinBox* b : {step_, min_ms_, max_ms_}) connect(b, &QDoubleSpinBox::valueChanged, this, replan);
  connect(repeats_, &QSpinBox::valueChanged, this, replan);
  connect(plan_button_, &QPushButton::clicked, this, &SetupPage::Plan);
}

void SetupPage::ApplyLocks() {
  radiometry::SweepCamera* cam = w_->state().camera.get();
  if (!cam || w_->busy()) return;
  try {
    cam->SetAutomatic(!lock_ae_->isChecked(), !lock_awb_->isChecked());
    const radiometry::ColourLock l = cam->colour_lock();
    lock_state_->setText(tr("As the camera reports it: auto exposure <b>%1</b>, auto white balance <b>%2</b>.")
                             .arg(l.auto_exposure ? tr("on") : tr("off"), l.auto_white_balance ? tr("on") : tr("off")));
    ShowProblem(problem_, "");
  } catch (const std::exception& e) {
    ShowProblem(problem_, EngineText(e.what()));
  }
}

void SetupPage::Preview() {
  radiometry::SweepCamera* cam = w_->state().camera.get();
  if (!cam || w_->busy()) return;
  try {
    if (!cam->colour_lock().auto_exposure && preview_ms_->value() != previewed_ms_) {
      cam->SetExposure(preview_ms_->value());
      previewed_ms_ = preview_ms_->value();
    }
    const ColorImage im = cam->GrabLatest();
    double high = 0, low = 0;
    const QImage q = Highlighted(im, &high, &low);
    preview_->setPixmap(QPixmap::fromImage(q.scaled(preview_->size(), Qt::KeepAspectRatio, Qt::SmoothTransformation)));
    std::array<std::vector<double>, 3> count;
    for (auto& c : count) c.assign(256, 0);
    for (std::size_t p = 0; p < im.size(); ++p) {
      count[0][im[p].r] += 1;
      count[1][im[p].g] += 1;
      count[2][im[p].b] += 1;
    }
    std::vector<PlotSeries> s;
    std::vector<double> x(256);
    for (int i = 0; i < 256; ++i) x[std::size_t(i)] = i;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) s.push_back({names[c], x, count[std::size_t(c)], ChannelColor(c)});
    histogram_->SetTitles(tr("Histogram: %L1 % saturated, %L2 % black").arg(100 * high, 0, 'f', 1).arg(100 * low, 0, 'f', 1),
                          tr("level"), tr("pixels"));
    histogram_->SetLogY(true);
    histogram_->SetSeries(std::move(s));
  } catch (const std::exception& e) {
    timer_->stop();
    ShowProblem(problem_, EngineText(e.what()));
  }
}

void SetupPage::initializePage() {
  planned_ = false;
  previewed_ms_ = -1;
  plan_label_->clear();
  ShowProblem(problem_, "");
  ApplyLocks();
  Preview();
  timer_->start();
  if (w_->settings().automatic) QTimer::singleShot(0, this, &SetupPage::Plan);
}

void SetupPage::cleanupPage() { timer_->stop(); }

bool SetupPage::validatePage() {
  timer_->stop();
  return planned_;
}

bool SetupPage::isComplete() const { return planned_ && !planning_; }

void SetupPage::Plan() {
  radiometry::SweepCamera* cam = w_->state().camera.get();
  if (!cam || planning_) return;
  io::SweepPlanOptions o = w_->settings().plan;
  o.step_stops = step_->value();
  o.repeats = repeats_->value();
  o.min_ms = min_ms_->value();
  o.max_ms = max_ms_->value();
  planning_ = true;
  planned_ = false;
  plan_button_->setEnabled(false);
  plan_label_->setText(tr("Metering the scene and taking a preview sweep…"));
  ShowProblem(problem_, "");
  emit completeChanged();
  auto plan = std::make_shared<io::SweepPlan>();
  w_->RunTask([cam, o, plan] { *plan = io::PlanSweep(*cam, o); },
              [this, plan](const QString& error) {
                planning_ = false;
                plan_button_->setEnabled(true);
                if (!error.isEmpty()) {
                  plan_label_->clear();
                  ShowProblem(problem_, error);
                  emit completeChanged();
                  w_->Fail(error);
                  return;
                }
                w_->state().plan = *plan;
                planned_ = true;
                const auto& e = plan->exposures_ms;
                QString text = tr("<b>Plan:</b> %1 exposures from %2 to %3 ms, %4 frames each (%5 frames). "
                                  "Levels covered by the preview sweep: %6.")
                                   .arg(e.size())
                                   .arg(e.front(), 0, 'g', 4)
                                   .arg(e.back(), 0, 'g', 4)
                                   .arg(plan->options.repeats)
                                   .arg(int(e.size()) * plan->options.repeats)
                                   .arg(CoverageText(plan->coverage));
                for (const std::string& wmsg : plan->warnings) text += "<br>⚠ " + EngineText(wmsg).toHtmlEscaped();
                plan_label_->setText(text);
                emit completeChanged();
                w_->PageDone("setup");
              });
}

// ---- Capture --------------------------------------------------------------------------------

CapturePage::CapturePage(CalibrationWizard* w) : w_(w) {
  setTitle(tr("3. Capture"));
  setSubTitle(tr("Each exposure is taken several times and checked for motion and flicker; a step that fails is "
                 "taken again. Frames are written as they come: a capture cancelled or cut short can be resumed."));
  auto* v = new QVBoxLayout(this);
  auto* row = new QHBoxLayout;
  row->addWidget(new QLabel(tr("Sweep folder:")));
  folder_ = new QLineEdit;
  folder_->setObjectName("capture_folder");
  row->addWidget(folder_, 1);
  v->addLayout(row);
  auto* buttons = new QHBoxLayout;
  start_ = new QPushButton(tr("Start capture"));
  start_->setObjectName("capture_start");
  cancel_ = new QPushButton(tr("Cancel"));
  cancel_->setObjectName("capture_cancel");
  resume_ = new QPushButton(tr("Resume"));
  resume_->setObjectName("capture_resume");
  back_to_setup_ = new QPushButton(tr("Back to Set-up"));
  back_to_setup_->setObjectName("capture_back_to_setup");
  back_to_setup_->hide();
  for (QPushButton* b : {start_, cancel_, resume_, back_to_setup_}) buttons->addWidget(b);
  buttons->addStretch(1);
  v->addLayout(buttons);
  progress_ = new QProgressBar;
  progress_->setObjectName("capture_progress");
  v->addWidget(progress_);
  status_ = new QLabel;
  status_->setObjectName("capture_status");
  status_->setWordWrap(true);
  v->addWidget(status_);
  problem_ = ProblemLabel("capture_problem");
  v->addWidget(problem_);
  auto* row2 = new QHBoxLayout;
  log_ = new QPlainTextEdit;
  log_->setObjectName("capture_log");
  log_->setReadOnly(true);
  row2->addWidget(log_, 1);
  frame_ = new QLabel(tr("The last frame captured shows here."));
  frame_->setObjectName("capture_frame");
  frame_->setAlignment(Qt::AlignCenter);
  frame_->setMinimumSize(400, 300);
  frame_->setFrameShape(QFrame::StyledPanel);
  row2->addWidget(frame_);
  v->addLayout(row2, 1);
  connect(start_, &QPushButton::clicked, this, [this] { Start(false); });
  connect(resume_, &QPushButton::clicked, this, [this] { Start(true); });
  connect(cancel_, &QPushButton::clicked, this, [this] { w_->cancel_flag() = true; });
  connect(back_to_setup_, &QPushButton::clicked, w_, &QWizard::back);
  connect(folder_, &QLineEdit::textChanged, this, &CapturePage::UpdateButtons);
}

void CapturePage::initializePage() {
  complete_ = false;
  QString f = w_->settings().sweep_folder;
  // A fresh folder by default; one that already holds a finished sweep (the operator came
  // back to capture again) gets a new name rather than a refusal.
  const fs::path shown = folder_->text().toStdString();
  std::error_code ec;
  const bool used = !shown.empty() && fs::exists(shown) && !fs::is_empty(shown, ec) &&
                    !UnfinishedCapture(shown);
  if (f.isEmpty() && (folder_->text().isEmpty() || used))
    f = HomePath("sweeps/sweep-" + QDateTime::currentDateTime().toString("yyyyMMdd-HHmmss"));
  if (!f.isEmpty()) folder_->setText(f);
  ShowProblem(problem_, "");
  back_to_setup_->hide();
  if (const auto& plan = w_->state().plan) {
    progress_->setRange(0, int(plan->exposures_ms.size()));
    progress_->setValue(0);
    status_->setText(tr("%1 exposures from %2 to %3 ms, %4 frames each.")
                         .arg(plan->exposures_ms.size())
                         .arg(plan->exposures_ms.front(), 0, 'g', 4)
                         .arg(plan->exposures_ms.back(), 0, 'g', 4)
                         .arg(plan->options.repeats));
  }
  UpdateButtons();
  if (w_->settings().automatic) QTimer::singleShot(0, this, [this] { Start(fs::exists(folder_->text().toStdString() + "/capture.json")); });
}

void CapturePage::UpdateButtons() {
  const bool resumable = UnfinishedCapture(folder_->text().toStdString());
  start_->setEnabled(!running_ && !complete_);
  resume_->setEnabled(!running_ && !complete_ && resumable);
  cancel_->setEnabled(running_);
  folder_->setEnabled(!running_);
}

void CapturePage::Start(bool resume) {
  WizardState& st = w_->state();
  if (!st.camera || !st.plan || running_) return;
  const fs::path folder = folder_->text().trimmed().toStdString();
  if (folder.empty()) {
    ShowProblem(problem_, tr("Choose the sweep folder."));
    return;
  }
  running_ = true;
  ShowProblem(problem_, "");
  back_to_setup_->hide();
  UpdateButtons();
  log_->appendPlainText(resume ? tr("Resuming the capture in %1").arg(Q(folder.string()))
                               : tr("Capturing to %1").arg(Q(folder.string())));
  radiometry::SweepCamera* cam = st.camera.get();
  const io::SweepPlan plan = *st.plan;
  auto result = std::make_shared<io::CaptureResult>();
  auto at = std::make_shared<io::CaptureProblem::FixAt>(io::CaptureProblem::FixAt::kCapture);
  QPointer<CapturePage> self(this);
  auto progress = [self](const io::CaptureStatus& s) {
    QMetaObject::invokeMethod(self, [self, s] {
      if (!self) return;
      self->progress_->setRange(0, s.steps);
      self->progress_->setValue(s.frames_written > 0 && s.note.empty() ? s.step + 1 : s.step);
      self->status_->setText(tr("Step %1 of %2 at %3 ms; %4 frames written; %5 steps taken again.")
                                 .arg(s.step + 1)
                                 .arg(s.steps)
                                 .arg(s.exposure_ms, 0, 'g', 4)
                                 .arg(s.frames_written)
                                 .arg(s.recaptures));
      if (!s.note.empty()) self->log_->appendPlainText(EngineText(s.note));
      if (s.frame) {
        self->log_->appendPlainText(tr("Step %1: %2 ms, done").arg(s.step + 1).arg(s.exposure_ms, 0, 'g', 4));
        const ColorImage& f = *s.frame;
        const QImage q(reinterpret_cast<const uchar*>(f.data()), f.width(), f.height(), 3 * f.width(), QImage::Format_RGB888);
        self->frame_->setPixmap(QPixmap::fromImage(q.scaled(self->frame_->size() - QSize(8, 8), Qt::KeepAspectRatio,
                                                            Qt::SmoothTransformation)));
      }
    }, Qt::QueuedConnection);
  };
  std::atomic<bool>* cancel = &w_->cancel_flag();
  w_->RunTask(
      [cam, plan, folder, resume, result, at, progress, cancel] {
        try {
          io::SweepCapture capture = resume ? io::SweepCapture::Resume(*cam, folder) : io::SweepCapture(*cam, plan, folder);
          *result = capture.Run(progress, cancel);
        } catch (const io::CaptureProblem& p) {
          *at = p.fix_at();
          throw;
        }
      },
      [this, folder, result, at](const QString& error) {
        running_ = false;
        if (!error.isEmpty()) {
          ShowProblem(problem_, error);
          back_to_setup_->setVisible(*at == io::CaptureProblem::FixAt::kSetup);
          log_->appendPlainText(tr("Stopped: %1").arg(error));
          UpdateButtons();
          w_->Fail(error);
          return;
        }
        if (result->cancelled) {
          log_->appendPlainText(tr("Cancelled: %1 of %2 steps (%3 frames) kept in %4. Resume to complete it.")
                                    .arg(result->steps_done)
                                    .arg(result->steps)
                                    .arg(result->frames)
                                    .arg(Q(folder.string())));
          UpdateButtons();
          return;
        }
        try {
          WizardState& st = w_->state();
          st.sweep_folder = folder;
          st.sweep = io::ReadSweep(folder);
        } catch (const std::exception& e) {
          ShowProblem(problem_, EngineText(e.what()));
          UpdateButtons();
          w_->Fail(EngineText(e.what()));
          return;
        }
        complete_ = true;
        progress_->setValue(progress_->maximum());
        log_->appendPlainText(tr("Complete: %1 steps, %2 frames, %3 steps taken again.")
                                  .arg(result->steps_done)
                                  .arg(result->frames)
                                  .arg(result->recaptures));
        UpdateButtons();
        emit completeChanged();
        w_->PageDone("capture");
      });
}

bool CapturePage::isComplete() const { return complete_ && !running_; }
bool CapturePage::validatePage() { return complete_; }

// ---- Fit ------------------------------------------------------------------------------------

FitPage::FitPage(CalibrationWizard* w) : w_(w) {
  setTitle(tr("4. Fit"));
  setSubTitle(tr("The camera response, its noise level function and the pixel confidence, fitted to the sweep."));
  auto* v = new QVBoxLayout(this);
  auto* row = new QHBoxLayout;
  row->addWidget(new QLabel(tr("Method:")));
  method_ = new QComboBox;
  method_->setObjectName("fit_method");
  method_->addItem(tr("Debevec & Malik (recommended)"), "debevec");
  method_->addItem(tr("Robertson et al."), "robertson");
  method_->addItem(tr("EMoR (Grossberg & Nayar)"), "emor");
  method_->setCurrentIndex(std::max(0, method_->findData(w_->settings().method)));
  row->addWidget(method_);
  basis_ = new QLineEdit(w_->settings().emor_basis);
  basis_->setObjectName("fit_basis");
  basis_->setPlaceholderText(tr("invemor.txt (EMoR basis)"));
  row->addWidget(basis_, 1);
  fit_ = new QPushButton(tr("Fit again"));
  fit_->setObjectName("fit_run");
  row->addWidget(fit_);
  v->addLayout(row);
  auto* prow = new QHBoxLayout;
  progress_ = new QProgressBar;
  progress_->setRange(0, 100);
  stage_ = new QLabel;
  prow->addWidget(progress_, 1);
  prow->addWidget(stage_, 1);
  v->addLayout(prow);
  summary_ = new QLabel;
  summary_->setObjectName("fit_summary");
  summary_->setWordWrap(true);
  v->addWidget(summary_);
  problem_ = ProblemLabel("fit_problem");
  v->addWidget(problem_);
  auto* grid = new QGridLayout;
  response_ = new PlotWidget;
  response_->setObjectName("plot_response");
  derivative_ = new PlotWidget;
  derivative_->setObjectName("plot_derivative");
  noise_ = new PlotWidget;
  noise_->setObjectName("plot_noise");
  pcf_ = new PlotWidget;
  pcf_->setObjectName("plot_pcf");
  residuals_ = new PlotWidget;
  residuals_->setObjectName("plot_residuals");
  grid->addWidget(response_, 0, 0);
  grid->addWidget(derivative_, 0, 1);
  grid->addWidget(residuals_, 0, 2);
  grid->addWidget(noise_, 1, 0);
  grid->addWidget(pcf_, 1, 1);
  v->addLayout(grid, 1);
  connect(fit_, &QPushButton::clicked, this, &FitPage::Fit);
  connect(method_, &QComboBox::currentIndexChanged, this, [this] {
    basis_->setEnabled(method_->currentData().toString() == "emor");
  });
  basis_->setEnabled(method_->currentData().toString() == "emor");
}

void FitPage::initializePage() {
  fitted_ = false;
  Fit();
}

bool FitPage::isComplete() const { return fitted_ && !running_; }

void FitPage::Fit() {
  WizardState& st = w_->state();
  if (!st.sweep || running_) return;
  radiometry::CalibrationSettings settings;
  settings.method = method_->currentData().toString().toStdString();
  try {
    if (settings.method == "emor") {
      if (basis_->text().trimmed().isEmpty()) throw SettingError("EMoR", tr("needs its basis file invemor.txt").toStdString());
      settings.basis = radiometry::EmorBasis::Load(basis_->text().trimmed().toStdString());
    }
  } catch (const std::exception& e) {
    ShowProblem(problem_, EngineText(e.what()));
    return;
  }
  running_ = true;
  fitted_ = false;
  st.outcome.reset();
  fit_->setEnabled(false);
  ShowProblem(problem_, "");
  summary_->clear();
  emit completeChanged();
  const radiometry::Sweep* sweep = &*st.sweep;
  auto out = std::make_shared<radiometry::CalibrationOutcome>();
  QPointer<FitPage> self(this);
  auto progress = [self](const std::string& stage, double f) {
    QMetaObject::invokeMethod(self, [self, stage, f] {
      if (!self) return;
      self->progress_->setValue(int(100 * f));
      self->stage_->setText(QString::fromStdString(stage));
    }, Qt::QueuedConnection);
  };
  std::atomic<bool>* cancel = &w_->cancel_flag();
  w_->RunTask([sweep, settings, out, progress, cancel] { *out = radiometry::RunCalibration(*sweep, settings, progress, cancel); },
              [this, out](const QString& error) {
                running_ = false;
                fit_->setEnabled(true);
                if (!error.isEmpty()) {
                  ShowProblem(problem_, error + "\n" + tr("Go back and capture a new sweep (or choose another folder)."));
                  emit completeChanged();
                  w_->Fail(error);
                  return;
                }
                w_->state().outcome = *out;
                progress_->setValue(100);
                stage_->setText(tr("done"));
                ShowResponse(*response_, *out);
                ShowDerivative(*derivative_, *out);
                ShowNoise(*noise_, *out);
                ShowPcf(*pcf_, *out);
                ShowResiduals(*residuals_, *out);
                QString text = tr("<b>%1</b>: rms log residual R %L2, G %L3, B %L4.")
                                   .arg(Q(out->fit.method))
                                   .arg(out->fit.rms_log_residual[0], 0, 'f', 4)
                                   .arg(out->fit.rms_log_residual[1], 0, 'f', 4)
                                   .arg(out->fit.rms_log_residual[2], 0, 'f', 4);
                if (out->noise_fit)
                  text += tr(" Noise: σs %L1 / %L2 / %L3, σc %L4 / %L5 / %L6.")
                              .arg(out->noise.sigma_s[0], 0, 'f', 4)
                              .arg(out->noise.sigma_s[1], 0, 'f', 4)
                              .arg(out->noise.sigma_s[2], 0, 'f', 4)
                              .arg(out->noise.sigma_c[0], 0, 'f', 5)
                              .arg(out->noise.sigma_c[1], 0, 'f', 5)
                              .arg(out->noise.sigma_c[2], 0, 'f', 5);
                else
                  text += tr(" Noise not fitted: %1").arg(Q(out->noise_error).toHtmlEscaped());
                summary_->setText(text);
                fitted_ = true;
                emit completeChanged();
                w_->PageDone("fit");
              });
}

// ---- Validate -------------------------------------------------------------------------------

ValidatePage::ValidatePage(CalibrationWizard* w) : w_(w) {
  setTitle(tr("5. Validate"));
  setSubTitle(tr("Every exposure against the merge of all, and the middle exposure held back and predicted from a "
                 "fit without it."));
  auto* v = new QVBoxLayout(this);
  verdict_ = new QLabel;
  verdict_->setObjectName("validate_verdict");
  QFont f = verdict_->font();
  f.setPointSizeF(f.pointSizeF() * 1.6);
  f.setBold(true);
  verdict_->setFont(f);
  v->addWidget(verdict_);
  details_ = new QLabel;
  details_->setObjectName("validate_details");
  details_->setWordWrap(true);
  details_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  v->addWidget(details_);
  consistency_ = new PlotWidget;
  consistency_->setObjectName("plot_consistency");
  v->addWidget(consistency_, 1);
}

void ValidatePage::initializePage() {
  const auto& out = w_->state().outcome;
  usable_ = false;
  if (!out) return;
  const radiometry::CalibrationCheck& c = out->check;
  static const char* kColour[3] = {"#186a2b", "#a06000", "#b00000"};
  const QString names[3] = {tr("Good"), tr("Marginal"), tr("Redo")};
  verdict_->setText(tr("Verdict: %1").arg(names[int(c.verdict)]));
  verdict_->setStyleSheet(QString("color: %1").arg(kColour[int(c.verdict)]));
  QString text = tr("Held back %L1 ms: predicted from the others within %L2 stops (median). Levels covered: %3. "
                    "Noise level function: %4.")
                     .arg(c.held_out.exposure_ms, 0, 'g', 4)
                     .arg(c.held_out.median_abs_stops, 0, 'f', 3)
                     .arg(CoverageText(c.coverage))
                     .arg(out->noise_saved() ? tr("saved") : tr("not saved"));
  if (!c.reasons.empty()) {
    text += "<ul>";
    for (const std::string& r : c.reasons) text += "<li>" + EngineText(r).toHtmlEscaped() + "</li>";
    text += "</ul>";
  }
  if (c.verdict == radiometry::Verdict::kRedo)
    text += tr("<b>This calibration cannot be saved.</b> Go back to Capture and take a new sweep: static camera and "
               "scene, auto exposure off, exposures from mostly dark to mostly saturated.");
  else if (c.verdict == radiometry::Verdict::kMarginal)
    text += tr("It can be saved; a new sweep may do better.");
  details_->setText(text);
  ShowConsistency(*consistency_, *out);
  usable_ = c.verdict != radiometry::Verdict::kRedo;
  emit completeChanged();
  if (usable_)
    QTimer::singleShot(0, w_, [this] { w_->PageDone("validate"); });
  else
    w_->Fail(tr("verdict redo: %1").arg(details_->text()));
}

bool ValidatePage::isComplete() const { return usable_; }

// ---- Save -----------------------------------------------------------------------------------

SavePage::SavePage(CalibrationWizard* w) : w_(w) {
  setTitle(tr("6. Save"));
  setSubTitle(tr("The profile is stored for the device's serial: the studio and the command-line tools use it "
                 "whenever that camera is connected. The report keeps the plots and figures."));
  auto* form = new QFormLayout(this);
  serial_ = new QLineEdit;
  serial_->setObjectName("save_serial");
  form->addRow(tr("Device serial:"), serial_);
  profile_path_ = new QLabel;
  profile_path_->setObjectName("save_profile_path");
  profile_path_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  form->addRow(tr("Profile file:"), profile_path_);
  report_ = new QLineEdit;
  report_->setObjectName("save_report");
  form->addRow(tr("Report folder:"), report_);
  save_ = new QPushButton(tr("Save profile and report"));
  save_->setObjectName("save_run");
  form->addRow(save_);
  result_ = new QLabel;
  result_->setObjectName("save_result");
  result_->setWordWrap(true);
  result_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  form->addRow(result_);
  connect(serial_, &QLineEdit::textChanged, this, &SavePage::UpdatePaths);
  connect(save_, &QPushButton::clicked, this, &SavePage::Save);
}

void SavePage::initializePage() {
  saved_ = false;
  const SensorInfo& s = w_->state().sweep_sensor;
  const QString serial = Q(s.device ? s.device->serial : std::string());
  serial_->setText(serial);
  report_->setText(!w_->settings().report_folder.isEmpty()
                       ? w_->settings().report_folder
                       : HomePath("calibrations/" + (serial.isEmpty() ? QString("camera") : serial) + "-" +
                                  QDateTime::currentDateTime().toString("yyyyMMdd-HHmmss")));
  result_->clear();
  UpdatePaths();
  if (w_->settings().automatic) QTimer::singleShot(0, this, &SavePage::Save);
}

void SavePage::UpdatePaths() {
  const std::string serial = serial_->text().trimmed().toStdString();
  profile_path_->setText(serial.empty() ? tr("(give the serial)") : Q(sensors::ProfilePath(serial).string()));
  save_->setEnabled(!serial.empty() && !saved_);
}

bool SavePage::isComplete() const { return saved_; }

void SavePage::Save() {
  WizardState& st = w_->state();
  const std::string serial = serial_->text().trimmed().toStdString();
  if (serial.empty() || !st.outcome) {
    result_->setText(tr("Give the device's serial to store the profile under."));
    w_->Fail(result_->text());
    return;
  }
  try {
    SensorInfo profile = st.outcome->Apply(st.sweep_sensor);
    if (!profile.device) profile.device = SensorInfo::Device{};
    profile.device->serial = serial;
    const QString source = st.camera ? Q(st.camera->description()) : Q(st.sweep_folder.string());
    st.report = WriteReport(report_->text().trimmed().toStdString(), st, source, profile);
    st.profile = sensors::SaveProfile(serial, profile);
  } catch (const std::exception& e) {
    result_->setText("<span style='color:#b00000'><b>" + Q(e.what()).toHtmlEscaped() + "</b></span>");
    w_->Fail(EngineText(e.what()));
    return;
  }
  saved_ = true;
  UpdatePaths();
  result_->setText(tr("Saved the profile %1 and the report %2.").arg(Q(st.profile.string()), Q(st.report.string())));
  emit completeChanged();
  emit w_->saved(Q(st.profile.string()), Q(st.report.string()));
  w_->PageDone("save");
}

}  // namespace hdrf::wizard
