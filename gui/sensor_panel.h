// The live camera panel: the connected devices (refreshed on plug events), the capture mode,
// a preview, the camera's exposure controls (auto exposure and white balance, exposure in
// milliseconds where the profile gives the unit, else in the device's raw unit, gain), and
// recording with its size, duration and dropped frames. The panel only asks: every request
// goes to the scan thread as a signal, and what the camera really does comes back in
// ShowStatus.
#pragma once

#include <QWidget>
#include <optional>
#include <vector>

#include "gui/scan_worker.h"

class QBoxLayout;
class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QSpinBox;

namespace hdrf::gui {

class SensorPanel : public QWidget {
  Q_OBJECT
 public:
  explicit SensorPanel(QWidget* parent = nullptr);

  // The source spec for the chosen device and mode ("openni:device=SERIAL,mode=vga").
  QString SpecForSelection() const;
  int device_count() const;
  QString device_text(int i) const;
  QString status_text() const;
  QString recording_text() const;
  bool recording() const { return recording_; }
  // Where the next recording goes (a fresh timestamped folder unless the user chose one).
  QString recording_path() const;
  void SetRecordingPath(const QString& p);

 public slots:
  void ShowSensors(const std::vector<hdrf::gui::SensorListing>& sensors);
  void ShowStatus(const hdrf::gui::LiveStatus& s);
  void ShowNoCamera(const QString& why);  // the camera went away, or OpenNI2 is unavailable
  void RecordingFinished(bool ok, const QString& message);

 signals:
  void refresh();
  void openCamera(const QString& spec);  // preview this device (and scan it with Start)
  void controls(const hdrf::sensors::LiveOptions& c);
  void startRecording(const QString& path);
  void stopRecording();

 protected:
  void resizeEvent(QResizeEvent* e) override;

 private:
  void SendExposure();
  void ShowProfileNote(int device_index);
  QString NextRecordingFolder() const;

  QBoxLayout* layout_ = nullptr;
  QComboBox *devices_ = nullptr, *mode_ = nullptr;
  QPushButton *open_ = nullptr, *record_ = nullptr, *refresh_ = nullptr;
  QLabel *profile_ = nullptr, *status_ = nullptr, *recording_label_ = nullptr;
  QCheckBox *ae_ = nullptr, *awb_ = nullptr;
  QDoubleSpinBox* exposure_ = nullptr;
  QSpinBox* gain_ = nullptr;
  QLineEdit* path_ = nullptr;
  std::vector<SensorListing> sensors_;
  std::optional<double> ms_per_unit_;
  bool recording_ = false, have_camera_ = false;
};

}  // namespace hdrf::gui
