// A plot for the wizard's pages and its report: lines and points over linear or log axes,
// with ticks, axis titles and a legend. Paints itself on screen and renders into an image
// (the report's PNGs) through the same code.
#pragma once

#include <QColor>
#include <QString>
#include <QWidget>
#include <vector>

class QPainter;

namespace hdrf::wizard {

struct PlotSeries {
  QString name;                    // in the legend ("" for none)
  std::vector<double> x, y;        // NaN in y leaves a gap
  QColor color;
  bool points = false;             // dots instead of a line
  bool dashed = false;
  double radius = 1.8;             // of the dots
};

class PlotWidget : public QWidget {
  Q_OBJECT
 public:
  explicit PlotWidget(QWidget* parent = nullptr);
  void SetTitles(const QString& title, const QString& x_title, const QString& y_title);
  void SetLogX(bool on) { log_x_ = on; }
  void SetLogY(bool on) { log_y_ = on; }
  void SetSeries(std::vector<PlotSeries> series);
  // A horizontal reference line (a limit), drawn dashed grey with its label.
  void AddReference(double y, const QString& label);
  void Clear();
  const std::vector<PlotSeries>& series() const { return series_; }
  const QString& title() const { return title_; }

  // Paints the plot into `rect` (screen and report share this).
  void Render(QPainter& p, const QRect& rect) const;
  QImage ToImage(int width, int height) const;
  QSize sizeHint() const override { return {420, 260}; }
  QSize minimumSizeHint() const override { return {260, 170}; }

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  QString title_, x_title_, y_title_;
  bool log_x_ = false, log_y_ = false;
  std::vector<PlotSeries> series_;
  std::vector<std::pair<double, QString>> refs_;
};

// The channel colours of every plot (R, G, B).
QColor ChannelColor(int c);

}  // namespace hdrf::wizard
