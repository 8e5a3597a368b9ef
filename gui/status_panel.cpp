#include "gui/status_panel.h"

#include <QFont>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPixmap>
#include <QStringList>
#include <QVBoxLayout>

#include "gui/language/language.h"
#include "gui/exposure_plot.h"
#include "gui/stage_images.h"

namespace hdrf::gui {

namespace {

// A label's style sheet set only when it changes (setting one re-polishes the widget).
void SetStyle(QLabel* l, const QString& sheet) {
  if (l->styleSheet() != sheet) l->setStyleSheet(sheet);
}

}  // namespace

StatusPanel::StatusPanel(QWidget* parent) : QWidget(parent) {
  auto* l = new QVBoxLayout(this);
  frames_ = new QLabel(tr("No frame yet"));
  health_ = new QLabel(tr("Tracking: -"));
  health_->setObjectName("health");
  health_->setWordWrap(true);
  reloc_caption_ = new QLabel;
  reloc_caption_->setWordWrap(true);
  reloc_caption_->hide();
  reloc_hint_ = new QLabel;
  reloc_hint_->setObjectName("reloc_hint");
  reloc_hint_->hide();
  error_ = new QLabel;
  error_->setObjectName("error");
  error_->setWordWrap(true);
  error_->setStyleSheet("QLabel { color: white; background: #a02020; padding: 4px; }");
  error_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  error_->hide();
  // Stage times as a grid of plain labels made once (a rich-text table re-laid out its whole
  // document on every frame): names left, times right-aligned, two column pairs.
  stages_ = new QWidget;
  auto* grid = new QGridLayout(stages_);
  grid->setContentsMargins(0, 0, 0, 0);
  grid->setHorizontalSpacing(6);
  grid->setVerticalSpacing(0);
  grid->setColumnMinimumWidth(2, 10);
  const QString stage_names[] = {tr("convert"), tr("normalize"), tr("track"), tr("compensate"), tr("integrate"), tr("ray cast")};
  for (int i = 0; i < 6; ++i) {
    grid->addWidget(new QLabel(stage_names[i]), i / 2, 3 * (i % 2));
    stage_ms_[i] = new QLabel;
    stage_ms_[i]->setAlignment(Qt::AlignRight | Qt::AlignVCenter);
    grid->addWidget(stage_ms_[i], i / 2, 3 * (i % 2) + 1);
  }
  auto* total = new QLabel(tr("total"));
  QFont bold = total->font();
  bold.setBold(true);
  total->setFont(bold);
  grid->addWidget(total, 3, 0);
  stage_ms_[6] = new QLabel;
  stage_ms_[6]->setFont(bold);
  stage_ms_[6]->setAlignment(Qt::AlignRight | Qt::AlignVCenter);
  grid->addWidget(stage_ms_[6], 3, 1, 1, 4);
  grid->setColumnStretch(5, 1);
  memory_ = new QLabel;
  memory_->setObjectName("memory");
  memory_->setWordWrap(true);
  plot_ = new ExposurePlot;
  // Text on the left, the exposure plot beside it: the panel stays short enough for a
  // 1366x768 screen.
  auto* text = new QVBoxLayout;
  for (QWidget* x : {static_cast<QWidget*>(frames_), static_cast<QWidget*>(health_),
                     static_cast<QWidget*>(reloc_caption_), static_cast<QWidget*>(reloc_hint_),
                     static_cast<QWidget*>(error_), static_cast<QWidget*>(stages_), static_cast<QWidget*>(memory_)})
    text->addWidget(x);
  text->addStretch(1);
  auto* row = new QHBoxLayout;
  row->addLayout(text, 3);
  row->addWidget(plot_, 2);
  l->addLayout(row);
}

QString StatusPanel::Key(const Snapshot& s) {
  const auto& r = s.report;
  return QStringList{QString::number(int(r.state)), QString::number(r.fused), QString::number(r.quality < 0.5),
                     QString::number(r.depth_beyond_far > 0.25), QString::fromStdString(r.why),
                     QString::number(s.reloc_hint_frame), QString::number(s.volume_full.empty())}
      .join(QLatin1Char('|'));
}

void StatusPanel::Show(const Snapshot& s) {
  key_ = Key(s);
  const auto& r = s.report;
  frames_->setText(tr("Frame %1%2 on the %3")
                       .arg(r.index + 1)
                       .arg(s.frames_total > 0 ? QStringLiteral(" / %1").arg(s.frames_total) : QString())
                       .arg(QString::fromStdString(s.device).toUpper()));
  const QString far = r.depth_beyond_far > 0.25
                          ? "\n" + tr("%1 % of the view lies beyond %L2 m, past the model's ray cast: tracking uses "
                                       "nearer surfaces (volume.raycast_far_m)")
                                        .arg(int(100 * r.depth_beyond_far))
                                        .arg(s.raycast_far_m, 0, 'f', 1)
                          : QString();
  using pipeline::FrameState;
  const QString why = language::EngineText(r.why);
  if (r.state == FrameState::kWaiting) {
    health_->setText(tr("WAITING: %1").arg(why) + far);
    SetStyle(health_, "QLabel { color: white; background: #a07010; padding: 3px; font-weight: bold; }");
  } else if (r.state == FrameState::kLost) {
    health_->setText(tr("TRACKING LOST: %1 (frame not fused)").arg(why) + far);
    SetStyle(health_, "QLabel { color: white; background: #c03030; padding: 3px; font-weight: bold; }");
  } else if (!r.fused) {
    health_->setText(tr("FOUND AGAIN, CONFIRMING: %1 (frame not fused)").arg(why) + far);
    SetStyle(health_, "QLabel { color: white; background: #a07010; padding: 3px; font-weight: bold; }");
  } else {
    // The quality figure warns before a loss: below one half the operator should slow down.
    const bool slow = r.quality < 0.5;
    health_->setText((slow ? tr("Tracking quality %1 %: SLOW DOWN (%2 % of pixels matched)")
                           : tr("Tracking quality %1 % (%2 % of pixels matched)"))
                         .arg(int(100 * r.quality))
                         .arg(int(100 * r.tracking.inlier_share)) +
                     (r.state == FrameState::kRelocalised ? "\n" + tr("Relocalised from an earlier view") : QString()) +
                     far);
    SetStyle(health_, far.isEmpty() && !slow ? "QLabel { color: white; background: #207040; padding: 3px; }"
                                                  : "QLabel { color: white; background: #a07010; padding: 3px; }");
  }
  if (!s.reloc_hint.empty() && s.reloc_hint_frame != reloc_hint_frame_) {
    reloc_hint_frame_ = s.reloc_hint_frame;
    reloc_hint_->setPixmap(QPixmap::fromImage(FromColor(s.reloc_hint))
                               .scaled(240, 180, Qt::KeepAspectRatio, Qt::SmoothTransformation));
    reloc_hint_->setToolTip(tr("The scan's view at frame %1").arg(s.reloc_hint_frame + 1));
    reloc_caption_->setText(tr("Point the camera where the scan saw this (frame %1):").arg(s.reloc_hint_frame + 1));
    reloc_hint_->show();
    reloc_caption_->show();
  } else if (s.reloc_hint.empty()) {
    reloc_hint_frame_ = -1;
    reloc_hint_->hide();
    reloc_caption_->hide();
  }
  const auto& m = r.ms;
  const double ms[] = {m.convert, m.normalize, m.track, m.compensate, m.integrate, m.raycast};
  for (int i = 0; i < 6; ++i) stage_ms_[i]->setText(tr("%L1 ms").arg(ms[i], 0, 'f', 1));
  stage_ms_[6]->setText(tr("%L1 ms (%L2 frames/s)").arg(m.total(), 0, 'f', 1).arg(m.total() > 0 ? 1000.0 / m.total() : 0.0, 0, 'f', 1));
  memory_->setText(tr("Volume: %L1 of %L2 MiB in %3 bricks")
                       .arg(double(s.volume_bytes) / (1024.0 * 1024.0), 0, 'f', 1)
                       .arg(s.volume_budget_mb, 0, 'f', 0)
                       .arg(s.bricks));
  if (s.gpu_budget_mb > 0 && s.device == "cuda")
    memory_->setText(memory_->text() + "\n" +
                     tr("GPU: %L1 of %L2 MiB, %3 bricks; host memory: %4 bricks (%5 moved out, %6 back)")
                         .arg(double(s.streaming.gpu_bytes) / (1024.0 * 1024.0), 0, 'f', 1)
                         .arg(s.gpu_budget_mb, 0, 'f', 0)
                         .arg(s.streaming.gpu_bricks)
                         .arg(s.streaming.host_bricks)
                         .arg(s.streaming.swapped_out)
                         .arg(s.streaming.swapped_in));
  if (!s.volume_full.empty()) {
    memory_->setText(memory_->text() + "\n" +
                     tr("VOLUME FULL: %1. New surfaces are not added; the model is kept and can be saved and "
                        "exported.").arg(QString::fromStdString(s.volume_full)));
    SetStyle(memory_, "QLabel { color: white; background: #b06010; padding: 3px; }");
  } else {
    SetStyle(memory_, QString());
  }
}

void StatusPanel::ShowExposure(const Snapshot& s) {
  plot_->SetSeries(s.exposure_estimated.span(), s.exposure_reported.span());
}

void StatusPanel::ShowPreview(int frames_in_model) {
  frames_->setText(frames_in_model > 0 ? tr("Live preview (not scanning); the model holds %1 frames").arg(frames_in_model)
                                       : tr("Live preview (not scanning)"));
}

void StatusPanel::ShowError(const QString& message) {
  error_->setText(message);
  error_->setToolTip(message);
  error_->show();
  stages_->hide();
  memory_->hide();
}
void StatusPanel::HideError() {
  error_->hide();
  stages_->show();
  memory_->show();
}
void StatusPanel::ClearError() {
  HideError();
  error_->clear();
}

QString StatusPanel::health_text() const { return health_->text(); }
QString StatusPanel::error_text() const {
  return error_->isVisible() || !error_->text().isEmpty() ? error_->text() : QString();
}

std::optional<bool> StatusPanel::ErrorFits(const QWidget* frame) const {
  if (!error_->isVisible()) return std::nullopt;
  const QRect in_frame(error_->mapTo(frame, QPoint(0, 0)), error_->size());
  return error_->height() >= error_->heightForWidth(error_->width()) && frame->rect().contains(in_frame);
}

}  // namespace hdrf::gui
