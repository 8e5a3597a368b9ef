// One live 2-D view: an 8-bit display image, the value under the cursor in physical units
// (radiance, metres, ...), an optional colour scale bar, and saving as PNG or, for HDR
// views, OpenEXR (the data behind the display image, not the display image).
#pragma once

#include <QImage>
#include <QWidget>
#include <functional>

class QLabel;

namespace hdrf::gui {

class ImageView : public QWidget {
  Q_OBJECT
 public:
  explicit ImageView(const QString& name, QWidget* parent = nullptr);

  // `value(x, y)` describes the pixel (x, y) of the image; `save_exr(path)` writes the HDR
  // data (empty: the view has none, only PNG is offered).
  void SetImage(const QImage& image, std::function<QString(int, int)> value,
                std::function<void(const QString&)> save_exr = {});
  // A vertical scale bar beside the image: `colours` from bottom (min) to top (max).
  void SetScaleBar(const QVector<QRgb>& colours, double min, double max, const QString& unit);

  const QImage& image() const { return image_; }
  const QString& name() const { return name_; }
  QString ValueAt(int x, int y) const;   // what the readout shows for pixel (x, y)
  QString readout() const;               // the readout's current text
  bool SavePng(const QString& path) const;
  bool HasHdr() const { return bool(save_exr_); }
  void SaveExr(const QString& path) const;  // throws hdrf::Error
  // Distinct grey levels seen in a coarse scan of the image (0 when empty): the test's
  // "non-empty, non-uniform" check.
  int DistinctLevels() const;
  // Where the image is drawn in the view (scaled to fit, aspect kept); empty before a frame.
  QRect ImageRect() const;

 signals:
  void status(const QString& message);

 protected:
  void paintEvent(QPaintEvent*) override;
  void mouseMoveEvent(QMouseEvent*) override;
  void contextMenuEvent(QContextMenuEvent*) override;

 private:
  QString name_;
  QImage image_;
  std::function<QString(int, int)> value_;
  std::function<void(const QString&)> save_exr_;
  QVector<QRgb> bar_;
  double bar_min_ = 0, bar_max_ = 0;
  QString bar_unit_;
  QLabel* readout_;
};

}  // namespace hdrf::gui
