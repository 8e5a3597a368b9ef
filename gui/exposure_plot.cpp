#include "gui/exposure_plot.h"

#include <QLocale>
#include <QPainter>
#include <algorithm>
#include <cmath>
#include <vector>

namespace hdrf::gui {

namespace {
constexpr std::size_t kWindow = 200;
}

ExposurePlot::ExposurePlot(QWidget* parent) : QWidget(parent) {
  setMinimumSize(170, 90);
  setToolTip(tr("Exposure ratio to the first frame, in stops: estimated by the engine (cyan) "
                "and reported by the sensor (orange)"));
}

void ExposurePlot::SetSeries(std::span<const double> est, std::span<const double> rep) {
  const std::size_t n = est.size(), first = n > kWindow ? n - kWindow : 0;
  est_.assign(est.begin() + long(first), est.end());
  rep_.assign(rep.begin() + long(std::min(first, rep.size())), rep.end());
  update();
}

void ExposurePlot::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(rect(), QColor(24, 24, 28));
  // Title and legend on one line: what is plotted, its unit and which colour is which.
  const QFontMetrics fm(font());
  int x = 4;
  const int base = 2 + fm.ascent();
  const auto text = [&](const QString& t, QColor c) {
    p.setPen(c);
    p.drawText(x, base, t);
    x += fm.horizontalAdvance(t) + 10;
  };
  const auto key = [&](const QString& t, QColor c) {
    p.setPen(QPen(c, 3));
    p.drawLine(x, base - fm.ascent() / 2 + 1, x + 14, base - fm.ascent() / 2 + 1);
    x += 18;
    text(t, QColor(200, 200, 200));
  };
  text(tr("Exposure, stops"), QColor(160, 160, 160));
  key(tr("estimated"), QColor(80, 220, 255));
  key(tr("reported"), QColor(255, 160, 60));
  p.setPen(QColor(140, 140, 140));
  p.drawText(rect().adjusted(4, 2, -4, -2), Qt::AlignBottom | Qt::AlignLeft,
             tr("last %1 frames").arg(kWindow));
  if (est_.empty()) return;
  double lo = 1e9, hi = -1e9;
  auto stops = [](double r) { return r > 0 && std::isfinite(r) ? std::log2(r) : std::nan(""); };
  for (double v : est_) {
    const double s = stops(v);
    if (std::isfinite(s)) lo = std::min(lo, s), hi = std::max(hi, s);
  }
  for (double v : rep_) {
    const double s = stops(v);
    if (std::isfinite(s)) lo = std::min(lo, s), hi = std::max(hi, s);
  }
  if (!(hi > lo)) lo -= 0.5, hi += 0.5;
  const QRectF r = QRectF(rect()).adjusted(6, fm.height() + 6, -6, -fm.height() - 2);
  auto pt = [&](std::size_t i, double s) {
    const double x = r.left() + r.width() * double(i) / double(std::max<std::size_t>(1, kWindow - 1));
    return QPointF(x, r.bottom() - r.height() * (s - lo) / (hi - lo));
  };
  // Each series as separate segments: a polyline's stroke with joins costs the raster
  // engine about 25 ms for 200 zig-zagging points with antialiasing, separate segments
  // (square caps cover the corners) under 1 ms.
  auto draw = [&](const std::vector<double>& v, QColor c, double width) {
    std::vector<QLineF> segments;
    segments.reserve(v.size());
    double last = std::nan("");
    for (std::size_t i = 0; i < v.size(); ++i) {
      const double s = stops(v[i]);
      if (std::isfinite(s) && std::isfinite(last)) segments.emplace_back(pt(i - 1, last), pt(i, s));
      last = s;
    }
    p.setPen(QPen(c, width));
    p.drawLines(segments.data(), int(segments.size()));
  };
  draw(rep_, QColor(255, 160, 60), 4.0);  // wide beneath: visible where the two agree
  draw(est_, QColor(80, 220, 255), 1.5);
  p.setPen(QColor(160, 160, 160));
  p.drawText(r, Qt::AlignRight | Qt::AlignTop, QLocale().toString(hi, 'f', 1));
  p.drawText(r, Qt::AlignRight | Qt::AlignBottom, QLocale().toString(lo, 'f', 1));
}

}  // namespace hdrf::gui
