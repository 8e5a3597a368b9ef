#include "calibration_wizard/wizard_pages.h"

#include <QDateTime>
#include <QFormLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QTimer>

#include "calibration_wizard/calibration_wizard.h"
#include "calibration_wizard/report.h"
#include "gui/language/language.h"
#include "sensors/profiles.h"
#include "calibration_wizard/page_support.h"

namespace hdrf::wizard {

using namespace page;

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
    w_->Fail(language::EngineText(e.what()));
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
