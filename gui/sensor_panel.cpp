#include "gui/sensor_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDateTime>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSpinBox>
#include <QStandardPaths>
#include <QVBoxLayout>

namespace hdrf::gui {

namespace {

const char* kWarnStyle = "QLabel { background: #fff0c0; color: #503000; padding: 3px; }";
const char* kBadStyle = "QLabel { background: #a02020; color: white; padding: 3px; }";

}  // namespace

SensorPanel::SensorPanel(QWidget* parent) : QWidget(parent) {
  auto* outer = new QVBoxLayout(this);
  outer->setContentsMargins(0, 0, 0, 0);
  layout_ = new QBoxLayout(QBoxLayout::TopToBottom);
  outer->addLayout(layout_);
  outer->addStretch(1);
  auto* layout = layout_;
  // The device.
  auto* cam = new QGroupBox(tr("Camera"));
  auto* cl = new QVBoxLayout(cam);
  devices_ = new QComboBox;
  devices_->setObjectName("sensor_devices");
  devices_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  devices_->setMinimumContentsLength(18);
  refresh_ = new QPushButton(tr("Refresh"));
  refresh_->setToolTip(tr("List the connected cameras again (the list also follows plug events)"));
  cl->addWidget(devices_);
  profile_ = new QLabel;
  profile_->setWordWrap(true);
  cl->addWidget(profile_);
  auto* row2 = new QHBoxLayout;
  mode_ = new QComboBox;
  mode_->addItem(tr("VGA 640×480, 30 Hz"), "vga");
  mode_->addItem(tr("QVGA 320×240, 30 Hz"), "qvga");
  open_ = new QPushButton(tr("Preview"));
  open_->setObjectName("sensor_open");
  open_->setToolTip(tr("Open this camera: its picture shows live; Start scans it"));
  row2->addWidget(mode_, 1);
  row2->addWidget(refresh_);
  row2->addWidget(open_);
  cl->addLayout(row2);
  status_ = new QLabel(tr("No camera open"));
  status_->setObjectName("sensor_status");
  status_->setWordWrap(true);
  cl->addWidget(status_);
  layout->addWidget(cam);
  // Exposure.
  auto* ex = new QGroupBox(tr("Exposure"));
  auto* ef = new QFormLayout(ex);
  ae_ = new QCheckBox(tr("Auto exposure"));
  awb_ = new QCheckBox(tr("Auto white balance"));
  ae_->setObjectName("sensor_ae");
  awb_->setObjectName("sensor_awb");
  exposure_ = new QDoubleSpinBox;
  exposure_->setObjectName("sensor_exposure");
  exposure_->setKeyboardTracking(false);  // sent on Enter or arrow steps, not per keystroke
  exposure_->setRange(0.1, 1000.0);
  exposure_->setDecimals(1);
  exposure_->setSuffix(tr(" ms"));
  exposure_->setToolTip(tr("Exposure time (auto exposure off); in the device's raw unit when its profile gives no "
                           "millisecond unit"));
  gain_ = new QSpinBox;
  gain_->setObjectName("sensor_gain");
  gain_->setKeyboardTracking(false);
  gain_->setRange(100, 1600);
  gain_->setSingleStep(10);
  gain_->setToolTip(tr("Analogue gain; 100 is unity"));
  auto* flags = new QHBoxLayout;
  flags->addWidget(ae_);
  flags->addWidget(awb_);
  ef->addRow(flags);
  ef->addRow(tr("Exposure"), exposure_);
  ef->addRow(tr("Gain"), gain_);
  layout->addWidget(ex);
  // Recording.
  auto* rec = new QGroupBox(tr("Record"));
  auto* rl = new QVBoxLayout(rec);
  auto* row3 = new QHBoxLayout;
  path_ = new QLineEdit;
  path_->setPlaceholderText(tr("a new folder in ~/HDRFusion/recordings"));
  path_->setToolTip(tr("A new sequence folder (colour PNG, 16-bit depth, exposure.txt, sensor.json), or FILE.oni"));
  auto* browse = new QPushButton(tr("…"));
  browse->setToolTip(tr("Choose where to record"));
  row3->addWidget(path_, 1);
  row3->addWidget(browse);
  rl->addLayout(row3);
  record_ = new QPushButton(tr("Record"));
  record_->setObjectName("sensor_record");
  rl->addWidget(record_);
  recording_label_ = new QLabel;
  recording_label_->setObjectName("sensor_recording");
  recording_label_->setWordWrap(true);
  rl->addWidget(recording_label_);
  layout->addWidget(rec);

  connect(refresh_, &QPushButton::clicked, this, &SensorPanel::refresh);
  connect(devices_, &QComboBox::currentIndexChanged, this, &SensorPanel::ShowProfileNote);
  connect(open_, &QPushButton::clicked, this, [this] {
    if (devices_->currentIndex() >= 0) emit openCamera(SpecForSelection());
  });
  connect(ae_, &QCheckBox::toggled, this, [this](bool on) {
    sensors::LiveOptions c;
    c.auto_exposure = on;
    exposure_->setEnabled(!on && have_camera_);
    emit controls(c);
  });
  connect(awb_, &QCheckBox::toggled, this, [this](bool on) {
    sensors::LiveOptions c;
    c.auto_white_balance = on;
    emit controls(c);
  });
  connect(exposure_, &QDoubleSpinBox::valueChanged, this, &SensorPanel::SendExposure);
  connect(gain_, &QSpinBox::valueChanged, this, [this](int g) {
    sensors::LiveOptions c;
    c.gain = g;
    emit controls(c);
  });
  connect(browse, &QPushButton::clicked, this, [this] {
    const QString p = QFileDialog::getSaveFileName(this, tr("Record to (a new folder, or FILE.oni)"), recording_path());
    if (!p.isEmpty()) path_->setText(p);
  });
  connect(record_, &QPushButton::clicked, this, [this] {
    if (recording_) {
      emit stopRecording();
      return;
    }
    const QString p = recording_path();
    recording_ = true;
    record_->setText(tr("Stop recording"));
    recording_label_->setStyleSheet({});
    recording_label_->setText(tr("Starting: %1").arg(QDir::toNativeSeparators(p)));
    emit startRecording(p);
  });
  ShowNoCamera(tr("No camera open"));
}

void SensorPanel::ShowProfileNote(int i) {
  if (i < 0 || i >= int(sensors_.size())) {
    profile_->clear();
    profile_->setStyleSheet({});
    return;
  }
  const SensorListing& l = sensors_[std::size_t(i)];
  if (l.entry.serial.empty()) {
    profile_->setText(tr("This device did not answer (in use by another program?)"));
    profile_->setStyleSheet(kWarnStyle);
  } else if (l.own_profile) {
    profile_->setText(tr("Calibrated: its own profile is used"));
    profile_->setStyleSheet({});
  } else {
    profile_->setText(tr("Not calibrated: the built-in Xtion profile is used; its response is not this "
                         "camera's own (Tools → Calibrate camera… for true radiance)"));
    profile_->setStyleSheet(kWarnStyle);
  }
}

void SensorPanel::resizeEvent(QResizeEvent* e) {
  // Three columns where the panel is wide (docked beside the status), one where it is narrow.
  layout_->setDirection(width() >= 720 ? QBoxLayout::LeftToRight : QBoxLayout::TopToBottom);
  QWidget::resizeEvent(e);
}

QString SensorPanel::SpecForSelection() const {
  const int i = devices_->currentIndex();
  QString spec = "openni:";
  if (i >= 0 && i < int(sensors_.size())) {
    const auto& e = sensors_[std::size_t(i)].entry;
    spec += "device=" + QString::fromStdString(e.serial.empty() ? e.uri : e.serial) + ",";
  }
  return spec + "mode=" + mode_->currentData().toString();
}

int SensorPanel::device_count() const { return devices_->count(); }
QString SensorPanel::device_text(int i) const { return devices_->itemText(i); }
QString SensorPanel::status_text() const { return status_->text(); }
QString SensorPanel::recording_text() const { return recording_label_->text(); }

QString SensorPanel::NextRecordingFolder() const {
  return QStandardPaths::writableLocation(QStandardPaths::HomeLocation) + "/HDRFusion/recordings/scan-" +
         QDateTime::currentDateTime().toString("yyyyMMdd-hhmmss");
}

QString SensorPanel::recording_path() const {
  return path_->text().trimmed().isEmpty() ? NextRecordingFolder() : path_->text().trimmed();
}

void SensorPanel::SetRecordingPath(const QString& p) { path_->setText(p); }

void SensorPanel::ShowSensors(const std::vector<SensorListing>& sensors) {
  const QString keep = devices_->currentIndex() >= 0 && devices_->currentIndex() < int(sensors_.size())
                           ? QString::fromStdString(sensors_[std::size_t(devices_->currentIndex())].entry.uri)
                           : QString();
  sensors_ = sensors;
  QSignalBlocker block(devices_);
  devices_->clear();
  int select = 0;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    const auto& e = sensors[i].entry;
    // The serial first: it tells two cameras of one model apart, and stays visible when the
    // list is narrow.
    QString text = e.serial.empty() ? QString::fromStdString(e.name)
                                    : QString::fromStdString(e.serial) + " — " + QString::fromStdString(e.name);
    if (sensors[i].in_use) text += tr(" (open)");
    devices_->addItem(text, QString::fromStdString(e.uri));
    devices_->setItemData(int(i), QString::fromStdString(e.vendor + " " + e.name + ", " + e.uri), Qt::ToolTipRole);
    if (QString::fromStdString(e.uri) == keep) select = int(i);
  }
  if (sensors.empty()) devices_->addItem(tr("No camera connected"));
  devices_->setEnabled(!sensors.empty());
  open_->setEnabled(!sensors.empty());
  devices_->setCurrentIndex(sensors.empty() ? 0 : select);
  block.unblock();
  ShowProfileNote(devices_->currentIndex());
}

void SensorPanel::ShowStatus(const LiveStatus& s) {
  have_camera_ = true;
  ms_per_unit_ = s.ms_per_unit;
  record_->setEnabled(true);
  for (QWidget* w : {static_cast<QWidget*>(ae_), static_cast<QWidget*>(awb_), static_cast<QWidget*>(gain_)})
    w->setEnabled(s.has_camera_settings);
  {
    const QSignalBlocker b1(ae_), b2(awb_), b3(exposure_), b4(gain_);
    ae_->setChecked(s.exposure.auto_exposure);
    awb_->setChecked(s.exposure.auto_white_balance);
    exposure_->setEnabled(s.has_camera_settings && !s.exposure.auto_exposure);
    if (s.ms_per_unit) {
      exposure_->setDecimals(1);
      exposure_->setSuffix(tr(" ms"));
      exposure_->setRange(*s.ms_per_unit, 1000.0);
      exposure_->setSingleStep(1.0);
    } else {
      exposure_->setDecimals(0);
      exposure_->setSuffix(tr(" (raw unit)"));
      exposure_->setRange(1, 100000);
      exposure_->setSingleStep(10);
    }
    // What the camera reports, unless the operator is typing a value.
    if (!exposure_->hasFocus())
      exposure_->setValue(s.ms_per_unit ? s.exposure.exposure_raw * *s.ms_per_unit : s.exposure.exposure_raw);
    if (!gain_->hasFocus()) gain_->setValue(s.exposure.gain);
  }
  QString exposure;
  if (!s.has_camera_settings)
    exposure = tr("no camera settings (exposure cannot be controlled)");
  else if (s.exposure.auto_exposure)
    exposure = tr("auto exposure (the engine estimates each frame's)");
  else if (s.ms_per_unit)
    exposure = tr("exposure %L1 ms, gain %L2").arg(s.exposure.exposure_raw * *s.ms_per_unit, 0, 'f', 1).arg(s.exposure.gain);
  else
    exposure = tr("exposure %1 (raw), gain %2").arg(s.exposure.exposure_raw).arg(s.exposure.gain);
  status_->setText(tr("%1: %2; %L3 frames/s; %4 dropped")
                       .arg(QString::fromStdString(s.device.name), exposure)
                       .arg(s.fps, 0, 'f', 1)
                       .arg(s.dropped));
  status_->setStyleSheet(s.dropped > 0 ? kWarnStyle : "");
  status_->setToolTip(s.dropped > 0 ? tr("Dropped: frames the camera sent that were not read in time (the scan is "
                                         "slower than the camera, or the link lost them)")
                                    : QString());
  // The panel's own state decides whether it records (a snapshot shown late must not
  // bring back a recording that has just ended).
  if (s.recording && recording_) {
    const auto& r = s.recording_stats;
    recording_label_->setText(tr("Recording to %1: %2 frames, %L3 MB, %L4 s, %5 dropped")
                                  .arg(QDir::toNativeSeparators(QString::fromStdString(s.recording_path)))
                                  .arg(r.written)
                                  .arg(r.bytes / 1e6, 0, 'f', 1)
                                  .arg(r.seconds, 0, 'f', 1)
                                  .arg(r.dropped));
    recording_label_->setStyleSheet(r.dropped > 0 ? kWarnStyle : "");
  }
}

void SensorPanel::ShowNoCamera(const QString& why) {
  have_camera_ = false;
  status_->setText(why);
  status_->setStyleSheet({});
  for (QWidget* w : {static_cast<QWidget*>(ae_), static_cast<QWidget*>(awb_), static_cast<QWidget*>(gain_),
                     static_cast<QWidget*>(exposure_), static_cast<QWidget*>(record_)})
    w->setEnabled(false);
}

void SensorPanel::RecordingFinished(bool ok, const QString& message) {
  recording_ = false;
  record_->setText(tr("Record"));
  recording_label_->setText(message);
  recording_label_->setStyleSheet(ok ? "" : kBadStyle);
  // The automatic folder name moves on; a chosen one is kept for the operator to change.
}

void SensorPanel::SendExposure() {
  sensors::LiveOptions c;
  c.auto_exposure = false;
  if (ms_per_unit_)
    c.exposure_ms = exposure_->value();
  else
    c.exposure_raw = int(exposure_->value());
  emit controls(c);
}

}  // namespace hdrf::gui
