#include "calibration_wizard/calibration_plots.h"

#include <QCoreApplication>
#include <cmath>

namespace hdrf::wizard {

// The plots' words (translation context "hdrf::wizard::Plots").
struct Plots {
  Q_DECLARE_TR_FUNCTIONS(hdrf::wizard::Plots)
};

namespace {

const char* kChannel[3] = {QT_TRANSLATE_NOOP("hdrf::wizard::Plots", "red"),
                           QT_TRANSLATE_NOOP("hdrf::wizard::Plots", "green"),
                           QT_TRANSLATE_NOOP("hdrf::wizard::Plots", "blue")};

std::vector<double> Levels() {
  std::vector<double> x(radiometry::kLevels);
  for (int i = 0; i < radiometry::kLevels; ++i) x[std::size_t(i)] = i;
  return x;
}

std::vector<PlotSeries> PerChannel(const std::array<std::array<float, radiometry::kLevels>, 3>& table) {
  std::vector<PlotSeries> s;
  for (int c = 0; c < 3; ++c) {
    PlotSeries p{Plots::tr(kChannel[c]), Levels(), {}, ChannelColor(c)};
    for (int i = 0; i < radiometry::kLevels; ++i) p.y.push_back(table[std::size_t(c)][std::size_t(i)]);
    s.push_back(std::move(p));
  }
  return s;
}

}  // namespace

void ShowResponse(PlotWidget& plot, const radiometry::CalibrationOutcome& out) {
  plot.Clear();
  plot.SetTitles(Plots::tr("Inverse response f⁻¹ (") + QString::fromStdString(out.fit.method) + ")", Plots::tr("level"),
                 Plots::tr("radiance × exposure (f⁻¹(128) = 1)"));
  plot.SetSeries(PerChannel(out.fit.inverse.table));
}

void ShowDerivative(PlotWidget& plot, const radiometry::CalibrationOutcome& out) {
  plot.Clear();
  plot.SetTitles(Plots::tr("Response derivative f′"), Plots::tr("level"), Plots::tr("levels per unit of radiance"));
  plot.SetLogY(true);
  plot.SetSeries(PerChannel(radiometry::ResponseDerivative(out.fit.inverse)));
}

void ShowNoise(PlotWidget& plot, const radiometry::CalibrationOutcome& out) {
  plot.Clear();
  plot.SetTitles(Plots::tr("Noise level function Var R = R·σs² + σc²"), Plots::tr("radiance R"), Plots::tr("variance of R"));
  plot.SetLogX(true);
  plot.SetLogY(true);
  if (!out.noise_fit) return;
  std::vector<PlotSeries> s;
  for (int c = 0; c < 3; ++c) {
    PlotSeries measured{"", {}, {}, ChannelColor(c).lighter(130), true};
    double lo = 1e30, hi = 0;
    for (const radiometry::NoiseLevel& l : out.noise_fit->levels[std::size_t(c)]) {
      measured.x.push_back(l.radiance);
      measured.y.push_back(l.variance);
      if (l.radiance > 0) lo = std::min(lo, l.radiance), hi = std::max(hi, l.radiance);
    }
    PlotSeries fitted{Plots::tr(kChannel[c]) + Plots::tr(" (fit)"), {}, {}, ChannelColor(c)};
    if (hi > lo)
      for (int k = 0; k <= 60; ++k) {
        const double r = lo * std::pow(hi / lo, k / 60.0);
        fitted.x.push_back(r);
        fitted.y.push_back(r * out.noise.sigma_s[std::size_t(c)] * out.noise.sigma_s[std::size_t(c)] +
                           out.noise.sigma_c[std::size_t(c)] * out.noise.sigma_c[std::size_t(c)]);
      }
    s.push_back(std::move(measured));
    s.push_back(std::move(fitted));
  }
  plot.SetSeries(std::move(s));
}

void ShowPcf(PlotWidget& plot, const radiometry::CalibrationOutcome& out) {
  plot.Clear();
  plot.SetTitles(Plots::tr("Pixel confidence p0..p3 (green)"), Plots::tr("level"), Plots::tr("confidence"));
  static const QColor kColors[4] = {QColor(120, 120, 120), QColor(230, 140, 20), QColor(150, 60, 190), QColor(20, 150, 160)};
  std::vector<PlotSeries> s;
  for (int k = 0; k < 4; ++k) {
    PlotSeries p{QString("p%1").arg(k), Levels(), {}, kColors[k], false, k == 0};
    for (int i = 0; i < radiometry::kLevels; ++i) p.y.push_back(out.pcf.p[std::size_t(k)][1][std::size_t(i)]);
    s.push_back(std::move(p));
  }
  plot.SetSeries(std::move(s));
}

void ShowResiduals(PlotWidget& plot, const radiometry::CalibrationOutcome& out) {
  plot.Clear();
  plot.SetTitles(Plots::tr("Residual per level (median, against the merge)"), Plots::tr("level"), Plots::tr("stops"));
  plot.SetSeries(PerChannel(out.check.level_residual_stops));
  plot.AddReference(0, "");
}

void ShowConsistency(PlotWidget& plot, const radiometry::CalibrationOutcome& out, const radiometry::CheckLimits& limits) {
  plot.Clear();
  plot.SetTitles(Plots::tr("Each exposure against the merge of all"), Plots::tr("exposure (ms)"), Plots::tr("median |deviation| (stops)"));
  plot.SetLogX(true);
  PlotSeries all{Plots::tr("every exposure"), {}, {}, QColor(40, 90, 220), true, false, 3.5};
  PlotSeries line{"", {}, {}, QColor(40, 90, 220)};
  for (const radiometry::ExposureConsistency& e : out.check.consistency) {
    all.x.push_back(e.exposure_ms);
    all.y.push_back(e.samples >= 100 ? e.median_abs_stops : NAN);
  }
  line.x = all.x;
  line.y = all.y;
  PlotSeries held{Plots::tr("held back, predicted from the others"), {out.check.held_out.exposure_ms},
                  {out.check.held_out.median_abs_stops}, QColor(214, 40, 40), true, false, 5};
  plot.SetSeries({line, all, held});
  plot.AddReference(limits.good_stops, Plots::tr("good"));
  plot.AddReference(limits.redo_stops, Plots::tr("redo"));
}

}  // namespace hdrf::wizard
