#include "calibration_wizard/wizard_pages.h"

#include <QDateTime>
#include <QFrame>
#include <QHBoxLayout>
#include <QImage>
#include <QLabel>
#include <QLineEdit>
#include <QPixmap>
#include <QPlainTextEdit>
#include <QPointer>
#include <QProgressBar>
#include <QPushButton>
#include <QTimer>
#include <QVBoxLayout>

#include "calibration_wizard/calibration_wizard.h"
#include "gui/language/language.h"
#include "common/error.h"
#include "io/sweep.h"
#include "calibration_wizard/page_support.h"

namespace hdrf::wizard {

namespace fs = std::filesystem;
using namespace page;

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
      if (!s.note.empty()) self->log_->appendPlainText(language::EngineText(s.note));
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
          ShowProblem(problem_, language::EngineText(e.what()));
          UpdateButtons();
          w_->Fail(language::EngineText(e.what()));
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

}  // namespace hdrf::wizard
