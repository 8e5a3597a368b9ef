// The studio's status panel: the frame and device, the tracking's health (state, quality, the
// reason a frame was not fused, where to point the camera after a loss), the stage times, the
// model's memory and the exposure plot; an error takes the place of the times while shown.
#pragma once

#include <QString>
#include <QWidget>
#include <array>
#include <optional>

#include "gui/scan_worker.h"

class QLabel;

namespace hdrf::gui {

class ExposurePlot;

class StatusPanel : public QWidget {
  Q_OBJECT
 public:
  explicit StatusPanel(QWidget* parent = nullptr);

  // A scan snapshot's status (frame, health, relocalisation hint, stage times, memory).
  void Show(const Snapshot& s);
  // The exposure ratios of the scan so far.
  void ShowExposure(const Snapshot& s);
  // The live preview's line in place of the frame line (the model holds `frames_in_model`).
  void ShowPreview(int frames_in_model);
  // What must reach the panel at once: the tracking's state and its warnings (a snapshot
  // whose key differs from the one shown is shown without waiting for the panel's rate).
  static QString Key(const Snapshot& s);
  const QString& key_shown() const { return key_; }

  // An error takes the place of the stage times and the memory line while it is shown: the
  // panel keeps the height of its usual content, and a message of three lines or more beside
  // them was cut off at both ends (1366x768). The whole message is also the label's tooltip,
  // and can be selected and copied.
  void ShowError(const QString& message);
  void HideError();
  void ClearError();

  QString health_text() const;
  QString error_text() const;                     // "" when none was shown
  // The error shown whole (its label as tall as its text needs, inside `frame`); none when no
  // error is shown.
  std::optional<bool> ErrorFits(const QWidget* frame) const;

 private:
  QLabel *frames_ = nullptr, *health_ = nullptr, *reloc_caption_ = nullptr, *reloc_hint_ = nullptr;
  QLabel *error_ = nullptr, *memory_ = nullptr;
  QWidget* stages_ = nullptr;             // the stage times' grid
  std::array<QLabel*, 7> stage_ms_{};     // its six stages and the total
  ExposurePlot* plot_ = nullptr;
  QString key_;
  int reloc_hint_frame_ = -1;
};

}  // namespace hdrf::gui
