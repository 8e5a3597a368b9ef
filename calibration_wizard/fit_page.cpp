#include "calibration_wizard/wizard_pages.h"

#include <QComboBox>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPointer>
#include <QProgressBar>
#include <QPushButton>
#include <QVBoxLayout>
#include <algorithm>

#include "calibration_wizard/calibration_plots.h"
#include "calibration_wizard/calibration_wizard.h"
#include "calibration_wizard/plot_widget.h"
#include "gui/language/language.h"
#include "common/error.h"
#include "calibration_wizard/page_support.h"

namespace hdrf::wizard {

using namespace page;

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
    ShowProblem(problem_, language::EngineText(e.what()));
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

}  // namespace hdrf::wizard
