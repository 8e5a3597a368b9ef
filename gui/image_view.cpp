#include "gui/image_view.h"

#include <QContextMenuEvent>
#include <QFileDialog>
#include <QLabel>
#include <QMenu>
#include <QMessageBox>
#include <QLocale>
#include <QFontMetrics>
#include <QPainter>
#include <QSet>
#include <QVBoxLayout>

#include "common/error.h"

namespace hdrf::gui {

namespace {
constexpr int kBarWidth = 46;
}

ImageView::ImageView(const QString& name, QWidget* parent) : QWidget(parent), name_(name) {
  setMouseTracking(true);
  setMinimumSize(160, 120);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addStretch(1);
  readout_ = new QLabel(this);
  readout_->setObjectName("readout");
  readout_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  readout_->setStyleSheet("QLabel { background: rgba(0,0,0,150); color: white; padding: 2px; }");
  layout->addWidget(readout_);
  setContextMenuPolicy(Qt::DefaultContextMenu);
}

void ImageView::SetImage(const QImage& image, std::function<QString(int, int)> value,
                         std::function<void(const QString&)> save_exr) {
  image_ = image;
  value_ = std::move(value);
  save_exr_ = std::move(save_exr);
  update();
}

void ImageView::SetScaleBar(const QVector<QRgb>& colours, double min, double max, const QString& unit) {
  bar_ = colours;
  bar_min_ = min;
  bar_max_ = max;
  bar_unit_ = unit;
  update();
}

QRect ImageView::ImageRect() const {
  if (image_.isNull()) return {};
  const int avail_w = width() - (bar_.isEmpty() ? 0 : kBarWidth), avail_h = height() - readout_->height();
  const QSize s = image_.size().scaled(std::max(1, avail_w), std::max(1, avail_h), Qt::KeepAspectRatio);
  return {(avail_w - s.width()) / 2, (avail_h - s.height()) / 2, s.width(), s.height()};
}

void ImageView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.fillRect(rect(), QColor(32, 32, 32));
  if (image_.isNull()) {
    p.setPen(Qt::gray);
    p.drawText(rect(), Qt::AlignCenter, tr("%1: no frame yet").arg(name_));
    return;
  }
  const QRect r = ImageRect();
  p.drawImage(r, image_);
  if (!bar_.isEmpty()) {
    const int x0 = width() - kBarWidth + 3, h = std::max(20, r.height() - 20), y0 = r.top() + 10;
    for (int i = 0; i < h; ++i) {
      const int idx = int((bar_.size() - 1) * (1.0 - double(i) / (h - 1)));
      p.setPen(QColor::fromRgb(bar_[idx]));
      p.drawLine(x0, y0 + i, x0 + 12, y0 + i);
    }
    p.setPen(Qt::white);
    // A label wider than the space beside the bar ("1e-06") is drawn smaller, not cut off.
    const auto label = [&](int y, double v) {
      const QString text = QLocale().toString(v, 'g', 2);
      const int room = width() - (x0 + 14) - 1;
      QFont f = p.font();
      const bool points = f.pointSizeF() > 0;
      for (int step = 0; step < 8 && QFontMetrics(f).horizontalAdvance(text) > room; ++step) {
        if (points) f.setPointSizeF(std::max(5.0, f.pointSizeF() - 0.5));
        else f.setPixelSize(std::max(7, f.pixelSize() - 1));
      }
      p.save();
      p.setFont(f);
      // Still too wide: it ends at the view's edge, over the bar, rather than past it.
      const int advance = QFontMetrics(f).horizontalAdvance(text);
      p.drawText(advance > room ? width() - 1 - advance : x0 + 14, y, text);
      p.restore();
    };
    label(y0 + 8, bar_max_);
    label(y0 + h, bar_min_);
    p.drawText(x0, y0 + h + 14, bar_unit_);
  }
}

QString ImageView::ValueAt(int x, int y) const {
  if (image_.isNull() || x < 0 || y < 0 || x >= image_.width() || y >= image_.height()) return {};
  return QStringLiteral("(%1, %2)  ").arg(x).arg(y) + (value_ ? value_(x, y) : QString());
}

QString ImageView::readout() const { return readout_->text(); }

void ImageView::mouseMoveEvent(QMouseEvent* e) {
  const QRect r = ImageRect();
  if (r.isEmpty() || !r.contains(e->pos())) return;
  const int x = int((e->position().x() - r.left()) * image_.width() / r.width());
  const int y = int((e->position().y() - r.top()) * image_.height() / r.height());
  readout_->setText(ValueAt(x, y));
}

bool ImageView::SavePng(const QString& path) const { return !image_.isNull() && image_.save(path, "PNG"); }

void ImageView::SaveExr(const QString& path) const {
  if (!save_exr_) throw Error(name_.toStdString() + " has no HDR data to save as OpenEXR");
  save_exr_(path);
}

int ImageView::DistinctLevels() const {
  if (image_.isNull()) return 0;
  QSet<int> seen;
  const int step = std::max(1, std::min(image_.width(), image_.height()) / 64);
  for (int y = 0; y < image_.height(); y += step)
    for (int x = 0; x < image_.width(); x += step) seen.insert(qGray(image_.pixel(x, y)));
  return int(seen.size());
}

void ImageView::contextMenuEvent(QContextMenuEvent* e) {
  QMenu menu(this);
  QAction* png = menu.addAction(tr("Save %1 as PNG…").arg(name_));
  QAction* exr = save_exr_ ? menu.addAction(tr("Save %1 as OpenEXR (HDR)…").arg(name_)) : nullptr;
  png->setEnabled(!image_.isNull());
  QAction* chosen = menu.exec(e->globalPos());
  if (!chosen) return;
  const bool hdr = chosen == exr;
  const QString path = QFileDialog::getSaveFileName(this, chosen->text(), name_ + (hdr ? ".exr" : ".png"),
                                                    hdr ? tr("OpenEXR (*.exr)") : tr("PNG (*.png)"));
  if (path.isEmpty()) return;
  try {
    if (hdr) SaveExr(path);
    else if (!SavePng(path)) throw Error(path.toStdString() + ": cannot write the PNG");
    emit status(tr("Saved %1").arg(path));
  } catch (const std::exception& err) {
    QMessageBox::warning(this, tr("Save failed"), QString::fromStdString(err.what()));
  }
}

}  // namespace hdrf::gui
