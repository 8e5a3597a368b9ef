#include "calibration_wizard/plot_widget.h"

#include <QImage>
#include <QLocale>
#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <cmath>
#include <limits>

namespace hdrf::wizard {

namespace {

// 1, 2 or 5 times a power of ten: about `n` ticks over [lo, hi].
std::vector<double> NiceTicks(double lo, double hi, int n) {
  std::vector<double> t;
  if (!(hi > lo)) return t;
  const double raw = (hi - lo) / n, mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double step = raw / mag < 1.5 ? mag : raw / mag < 3.5 ? 2 * mag : raw / mag < 7.5 ? 5 * mag : 10 * mag;
  for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step) t.push_back(std::abs(v) < 1e-12 * step ? 0 : v);
  return t;
}

QString Label(double v) {
  const double a = std::abs(v);
  if (a != 0 && (a < 1e-3 || a >= 1e5)) return QLocale().toString(v, 'g', 2);
  return QLocale().toString(v, 'g', 4);
}

}  // namespace

QColor ChannelColor(int c) {
  static const QColor k[3] = {QColor(214, 40, 40), QColor(30, 150, 60), QColor(40, 90, 220)};
  return k[std::clamp(c, 0, 2)];
}

PlotWidget::PlotWidget(QWidget* parent) : QWidget(parent) {
  setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
}

void PlotWidget::SetTitles(const QString& title, const QString& x_title, const QString& y_title) {
  title_ = title;
  x_title_ = x_title;
  y_title_ = y_title;
  update();
}

void PlotWidget::SetSeries(std::vector<PlotSeries> series) {
  series_ = std::move(series);
  update();
}

void PlotWidget::AddReference(double y, const QString& label) {
  refs_.emplace_back(y, label);
  update();
}

void PlotWidget::Clear() {
  series_.clear();
  refs_.clear();
  update();
}

void PlotWidget::paintEvent(QPaintEvent*) {
  QPainter p(this);
  Render(p, rect());
}

QImage PlotWidget::ToImage(int width, int height) const {
  QImage im(width, height, QImage::Format_RGB32);
  im.fill(Qt::white);
  QPainter p(&im);
  Render(p, im.rect());
  return im;
}

void PlotWidget::Render(QPainter& p, const QRect& rect) const {
  p.save();
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(rect, Qt::white);
  const QFontMetrics fm(p.font());
  const int lh = fm.height();
  const QRect area = rect.adjusted(fm.horizontalAdvance("0.0000") + lh + 8, lh + 10, -12, -(2 * lh + 10));
  p.setPen(Qt::black);
  p.drawText(QRect(rect.left(), rect.top() + 2, rect.width(), lh), Qt::AlignCenter, title_);
  // Ranges over finite values (positive ones on log axes).
  auto tx = [&](double v) { return log_x_ ? std::log10(v) : v; };
  auto ty = [&](double v) { return log_y_ ? std::log10(v) : v; };
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const PlotSeries& s : series_)
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || (log_x_ && s.x[i] <= 0) || (log_y_ && s.y[i] <= 0))
        continue;
      x0 = std::min(x0, tx(s.x[i]));
      x1 = std::max(x1, tx(s.x[i]));
      y0 = std::min(y0, ty(s.y[i]));
      y1 = std::max(y1, ty(s.y[i]));
    }
  for (const auto& r : refs_)
    if (std::isfinite(r.first) && (!log_y_ || r.first > 0)) {
      y0 = std::min(y0, ty(r.first));
      y1 = std::max(y1, ty(r.first));
    }
  p.setPen(QColor(120, 120, 120));
  p.drawRect(area);
  if (!(x1 >= x0) || !(y1 >= y0)) {
    p.drawText(area, Qt::AlignCenter, tr("no data yet"));
    p.restore();
    return;
  }
  if (x1 == x0) x1 = x0 + 1, x0 -= 1;
  if (y1 == y0) y1 = y0 + 1, y0 -= 1;
  if (!log_y_ && y0 > 0 && y0 < 0.25 * (y1 - y0)) y0 = 0;  // keep zero in view when near
  const double pad = 0.04 * (y1 - y0);
  y0 -= pad;
  y1 += pad;
  auto px = [&](double v) { return area.left() + (tx(v) - x0) / (x1 - x0) * area.width(); };
  auto py = [&](double v) { return area.bottom() - (ty(v) - y0) / (y1 - y0) * area.height(); };
  // Ticks and grid.
  QPen grid(QColor(225, 225, 225));
  auto ticks = [&](double lo, double hi, bool log) {
    if (!log) return NiceTicks(lo, hi, 5);
    std::vector<double> t;
    // Decades; over a narrow range also 2 and 5 times each.
    const bool fine = hi - lo < 2.5;
    for (double e = std::floor(lo); e <= std::ceil(hi); e += std::max(1.0, std::round((hi - lo) / 6)))
      for (double m : {1.0, 2.0, 5.0}) {
        if (m != 1.0 && !fine) continue;
        const double v = e + std::log10(m);
        if (v >= lo - 1e-9 && v <= hi + 1e-9) t.push_back(v);
      }
    return t;
  };
  for (double t : ticks(x0, x1, log_x_)) {
    const double x = area.left() + (t - x0) / (x1 - x0) * area.width();
    p.setPen(grid);
    p.drawLine(QPointF(x, area.top()), QPointF(x, area.bottom()));
    p.setPen(Qt::black);
    p.drawText(QRectF(x - 40, area.bottom() + 3, 80, lh), Qt::AlignHCenter | Qt::AlignTop,
               Label(log_x_ ? std::pow(10.0, t) : t));
  }
  for (double t : ticks(y0, y1, log_y_)) {
    const double y = area.bottom() - (t - y0) / (y1 - y0) * area.height();
    p.setPen(grid);
    p.drawLine(QPointF(area.left(), y), QPointF(area.right(), y));
    p.setPen(Qt::black);
    p.drawText(QRectF(rect.left(), y - lh / 2.0, area.left() - rect.left() - 4, lh), Qt::AlignRight | Qt::AlignVCenter,
               Label(log_y_ ? std::pow(10.0, t) : t));
  }
  p.setPen(Qt::black);
  p.drawText(QRect(area.left(), area.bottom() + lh + 4, area.width(), lh), Qt::AlignCenter, x_title_);
  p.save();
  p.translate(rect.left() + 2, area.center().y());
  p.rotate(-90);
  p.drawText(QRect(-area.height() / 2, 0, area.height(), lh), Qt::AlignCenter, y_title_);
  p.restore();
  // References, then series, clipped to the area.
  p.setClipRect(area.adjusted(-3, -3, 3, 3));
  for (const auto& r : refs_) {
    if (!std::isfinite(r.first) || (log_y_ && r.first <= 0)) continue;
    p.setPen(QPen(QColor(140, 140, 140), 1, Qt::DashLine));
    const double y = py(r.first);
    p.drawLine(QPointF(area.left(), y), QPointF(area.right(), y));
    p.drawText(QRectF(area.left() + 4, y - lh - 1, area.width() - 8, lh), Qt::AlignRight | Qt::AlignBottom, r.second);
  }
  for (const PlotSeries& s : series_) {
    QPen pen(s.color, s.points ? 1 : 1.6, s.dashed ? Qt::DashLine : Qt::SolidLine);
    p.setPen(pen);
    if (s.points) {
      p.setBrush(s.color);
      for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || (log_x_ && s.x[i] <= 0) || (log_y_ && s.y[i] <= 0))
          continue;
        p.drawEllipse(QPointF(px(s.x[i]), py(s.y[i])), s.radius, s.radius);
      }
      p.setBrush(Qt::NoBrush);
      continue;
    }
    QPainterPath path;
    bool open = false;
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      const bool ok = std::isfinite(s.x[i]) && std::isfinite(s.y[i]) && (!log_x_ || s.x[i] > 0) && (!log_y_ || s.y[i] > 0);
      if (!ok) {
        open = false;
        continue;
      }
      const QPointF q(px(s.x[i]), py(s.y[i]));
      if (open) path.lineTo(q);
      else path.moveTo(q);
      open = true;
    }
    p.drawPath(path);
  }
  p.setClipping(false);
  // Legend, top left inside the area.
  int ly = area.top() + 4;
  for (const PlotSeries& s : series_) {
    if (s.name.isEmpty()) continue;
    const int w = fm.horizontalAdvance(s.name);
    p.fillRect(QRect(area.left() + 6, ly, w + 26, lh), QColor(255, 255, 255, 220));
    p.setPen(QPen(s.color, 2, s.dashed ? Qt::DashLine : Qt::SolidLine));
    if (s.points) {
      p.setBrush(s.color);
      p.drawEllipse(QPointF(area.left() + 15, ly + lh / 2.0), 2.5, 2.5);
      p.setBrush(Qt::NoBrush);
    } else {
      p.drawLine(area.left() + 8, ly + lh / 2, area.left() + 22, ly + lh / 2);
    }
    p.setPen(Qt::black);
    p.drawText(QRect(area.left() + 26, ly, w + 4, lh), Qt::AlignLeft | Qt::AlignVCenter, s.name);
    ly += lh;
  }
  p.restore();
}

}  // namespace hdrf::wizard
