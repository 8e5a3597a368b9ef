#include "calibration_wizard/wizard_pages.h"

#include <QLabel>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QPushButton>
#include <QRadioButton>
#include <QTimer>
#include <QVBoxLayout>
#include <algorithm>

#include "calibration_wizard/calibration_wizard.h"
#include "gui/language/language.h"
#include "common/error.h"
#include "io/sensor_json.h"
#include "io/sweep.h"
#include "sensors/sweep_cameras.h"
#include "calibration_wizard/page_support.h"

namespace hdrf::wizard {

using namespace page;

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
    ShowProblem(error_, language::EngineText(e.what()));
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
    ShowProblem(error_, language::EngineText(e.what()));
    w_->Fail(language::EngineText(e.what()));
    return false;
  }
  ShowProblem(error_, "");
  return true;
}

int SourcePage::nextId() const {
  return folder_->isChecked() ? CalibrationWizard::kFit : CalibrationWizard::kSetup;
}

}  // namespace hdrf::wizard
