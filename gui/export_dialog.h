// The studio's Export dialog: the scan as textured HDR assets (docs/export.md) -- formats,
// up axis, texture density, triangle budget, an optional render -- with progress, cancel
// and a preview of the result (the textured mesh rendered from the scan's first camera).
// The work runs on the scan worker's thread (ScanWorker::ExportAsset).
#pragma once

#include <QDialog>
#include <QImage>

#include "io/asset_export.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QSpinBox;

namespace hdrf::gui {

class ExportDialog : public QDialog {
  Q_OBJECT
 public:
  // `tone` is the tone mapping in force ("OP[,key=value...]"): the PNG texture, the preview
  // and the PLY colours go through it.
  ExportDialog(const QString& tone, QWidget* parent = nullptr);
  io::AssetOptions Options() const;
  QString Folder() const;
  bool busy() const { return busy_; }
  QString status_text() const;
  const QImage& preview() const { return preview_image_; }

 public slots:
  void OnProgress(double fraction, const QString& stage);
  void OnDone(bool ok, const QString& message, const QImage& preview);

 signals:
  void exportRequested(const QString& folder, const hdrf::io::AssetOptions& options);
  void cancelRequested();

 private:
  void Start();
  void SetBusy(bool busy);
  QString tone_;
  QLineEdit* folder_ = nullptr;
  QCheckBox *ply_ = nullptr, *obj_ = nullptr, *glb_ = nullptr, *render_ = nullptr;
  QComboBox* up_ = nullptr;
  QDoubleSpinBox* texel_ = nullptr;
  QSpinBox *triangles_ = nullptr, *render_w_ = nullptr, *render_h_ = nullptr;
  QProgressBar* progress_ = nullptr;
  QLabel *status_ = nullptr, *preview_ = nullptr;
  QPushButton *export_ = nullptr, *cancel_ = nullptr, *close_ = nullptr;
  QImage preview_image_;
  bool busy_ = false;
};

}  // namespace hdrf::gui

Q_DECLARE_METATYPE(hdrf::io::AssetOptions)
