#include "calibration_wizard/wizard_pages.h"

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QImage>
#include <QLabel>
#include <QPixmap>
#include <QPushButton>
#include <QSpinBox>
#include <QTimer>
#include <QVBoxLayout>

#include "calibration_wizard/calibration_wizard.h"
#include "calibration_wizard/plot_widget.h"
#include "gui/language/language.h"
#include "sensors/sweep_cameras.h"
#include "calibration_wizard/page_support.h"

namespace hdrf::wizard {

using namespace page;

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
    ShowProblem(problem_, language::EngineText(e.what()));
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
    ShowProblem(problem_, language::EngineText(e.what()));
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
                for (const std::string& wmsg : plan->warnings) text += "<br>⚠ " + language::EngineText(wmsg).toHtmlEscaped();
                plan_label_->setText(text);
                emit completeChanged();
                w_->PageDone("setup");
              });
}

}  // namespace hdrf::wizard
