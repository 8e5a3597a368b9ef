// A small live plot: the exposure ratio the engine estimated against the one the sensor
// reported, per frame, in stops (log2), over the last frames.
#pragma once

#include <QWidget>
#include <span>
#include <vector>

namespace hdrf::gui {

class ExposurePlot : public QWidget {
  Q_OBJECT
 public:
  explicit ExposurePlot(QWidget* parent = nullptr);
  // Reported values may be NaN (the sensor did not say).
  void SetSeries(std::span<const double> estimated, std::span<const double> reported);
  int points() const { return int(est_.size()); }

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  std::vector<double> est_, rep_;
};

}  // namespace hdrf::gui
