#include "calibration_wizard/wizard_pages.h"

#include <QLabel>
#include <QTimer>
#include <QVBoxLayout>

#include "calibration_wizard/calibration_plots.h"
#include "calibration_wizard/calibration_wizard.h"
#include "calibration_wizard/plot_widget.h"
#include "gui/language/language.h"
#include "calibration_wizard/page_support.h"

namespace hdrf::wizard {

using namespace page;

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
    for (const std::string& r : c.reasons) text += "<li>" + language::EngineText(r).toHtmlEscaped() + "</li>";
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

}  // namespace hdrf::wizard
