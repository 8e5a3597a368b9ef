// The wizard's pages (calibration_wizard.h). Widgets carry object names (tests drive them).
#pragma once

#include <QWizardPage>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPlainTextEdit;
class QProgressBar;
class QPushButton;
class QRadioButton;
class QSpinBox;
class QTimer;

namespace hdrf::wizard {

class CalibrationWizard;
class PlotWidget;

class SourcePage : public QWizardPage {
  Q_OBJECT
 public:
  explicit SourcePage(CalibrationWizard* w);
  void initializePage() override;
  bool validatePage() override;
  int nextId() const override;
  QString Spec() const;  // the camera spec or folder the choices make

 private:
  void RefreshDevices();
  void UpdateEnabled();
  CalibrationWizard* w_;
  QRadioButton *live_, *folder_, *synthetic_;
  QComboBox *devices_, *mode_, *response_, *scene_, *size_;
  QDoubleSpinBox* unit_;
  QLineEdit *folder_edit_, *response_file_;
  QLabel* error_;
  QString live_extra_;  // ",key=value" settings of a preset live source with no field here
  bool preset_done_ = false;
};

class SetupPage : public QWizardPage {
  Q_OBJECT
 public:
  explicit SetupPage(CalibrationWizard* w);
  void initializePage() override;
  void cleanupPage() override;
  bool validatePage() override;
  bool isComplete() const override;

 private:
  void ApplyLocks();
  void Preview();
  void Plan();
  CalibrationWizard* w_;
  QCheckBox *lock_ae_, *lock_awb_;
  QLabel *lock_state_, *preview_, *plan_label_, *problem_;
  PlotWidget* histogram_;
  QDoubleSpinBox *preview_ms_, *step_, *min_ms_, *max_ms_;
  QSpinBox* repeats_;
  QPushButton* plan_button_;
  QTimer* timer_;
  bool planned_ = false, planning_ = false;
  double previewed_ms_ = -1;  // the exposure the preview last set
};

class CapturePage : public QWizardPage {
  Q_OBJECT
 public:
  explicit CapturePage(CalibrationWizard* w);
  void initializePage() override;
  bool isComplete() const override;
  bool validatePage() override;

 private:
  void Start(bool resume);
  void UpdateButtons();
  CalibrationWizard* w_;
  QLineEdit* folder_;
  QPushButton *start_, *cancel_, *resume_, *back_to_setup_;
  QProgressBar* progress_;
  QLabel *status_, *problem_, *frame_;
  QPlainTextEdit* log_;
  bool running_ = false, complete_ = false;
};

class FitPage : public QWizardPage {
  Q_OBJECT
 public:
  explicit FitPage(CalibrationWizard* w);
  void initializePage() override;
  bool isComplete() const override;

 private:
  void Fit();
  CalibrationWizard* w_;
  QComboBox* method_;
  QLineEdit* basis_;
  QPushButton* fit_;
  QProgressBar* progress_;
  QLabel *stage_, *summary_, *problem_;
  PlotWidget *response_, *derivative_, *noise_, *pcf_, *residuals_;
  bool running_ = false, fitted_ = false;
};

class ValidatePage : public QWizardPage {
  Q_OBJECT
 public:
  explicit ValidatePage(CalibrationWizard* w);
  void initializePage() override;
  bool isComplete() const override;

 private:
  CalibrationWizard* w_;
  QLabel *verdict_, *details_;
  PlotWidget* consistency_;
  bool usable_ = false;
};

class SavePage : public QWizardPage {
  Q_OBJECT
 public:
  explicit SavePage(CalibrationWizard* w);
  void initializePage() override;
  bool isComplete() const override;

 private:
  void Save();
  void UpdatePaths();
  CalibrationWizard* w_;
  QLineEdit *serial_, *report_;
  QLabel *profile_path_, *result_;
  QPushButton* save_;
  bool saved_ = false;
};

}  // namespace hdrf::wizard
