#include "calibration_wizard/report.h"

#include <QCoreApplication>
#include <QDateTime>
#include <QFile>
#include <QImage>
#include <QTextStream>
#include <map>

#include "calibration_wizard/calibration_plots.h"
#include "common/error.h"
#include "io/sensor_json.h"

namespace hdrf::wizard {

namespace fs = std::filesystem;

// The report's words (translation context "hdrf::wizard::Report").
struct Report {
  Q_DECLARE_TR_FUNCTIONS(hdrf::wizard::Report)
};

namespace {
QString Esc(const QString& s) { return s.toHtmlEscaped(); }
}  // namespace

fs::path WriteReport(const fs::path& folder, const WizardState& st, const QString& source, const SensorInfo& profile) {
  if (!st.outcome || !st.sweep) throw Error("report: nothing calibrated yet");
  const radiometry::CalibrationOutcome& out = *st.outcome;
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw InputError(folder, "cannot create the report folder: " + ec.message());
  struct Figure {
    const char* file;
    void (*fill)(PlotWidget&, const radiometry::CalibrationOutcome&);
  };
  const Figure figures[] = {{"response.png", ShowResponse},   {"derivative.png", ShowDerivative},
                            {"noise.png", ShowNoise},         {"pcf.png", ShowPcf},
                            {"residuals.png", ShowResiduals}, {"consistency.png", [](PlotWidget& p, const radiometry::CalibrationOutcome& o) { ShowConsistency(p, o); }}};
  for (const Figure& f : figures) {
    PlotWidget plot;
    f.fill(plot, out);
    const QImage im = plot.ToImage(760, 440);
    const fs::path file = folder / f.file;
    if (!im.save(QString::fromStdString(file.string()), "PNG")) throw InputError(file, "cannot be written");
  }
  io::WriteSensorJson(folder / "sensor.json", profile);
  const fs::path html = folder / "report.html";
  QFile file(QString::fromStdString(html.string()));
  if (!file.open(QIODevice::WriteOnly | QIODevice::Truncate | QIODevice::Text))
    throw InputError(html, "cannot be written: " + file.errorString().toStdString());
  QTextStream h(&file);
  std::map<double, int> per_exposure;
  for (double e : st.sweep->exposure_ms) ++per_exposure[e];
  const char* ch = "RGB";
  const QString verdict = radiometry::VerdictName(out.check.verdict);
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << Report::tr("Camera calibration") << "</title>\n"
    << "<style>body{font-family:sans-serif;max-width:1600px;margin:2em}img{width:48%;margin:0.5%}"
       "table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:2px 8px;text-align:right}"
       ".good{color:#186a2b}.marginal{color:#a06000}.redo{color:#b00}</style></head><body>\n";
  h << "<h1>" << Report::tr("Camera calibration") << "</h1>\n<p>" << Esc(source) << "<br>"
    << Report::tr("Serial") << ": " << Esc(QString::fromStdString(profile.device ? profile.device->serial : std::string())) << "<br>"
    << Report::tr("Date") << ": " << QDateTime::currentDateTime().toString(Qt::ISODate) << "<br>"
    << Report::tr("Sweep") << ": " << Esc(QString::fromStdString(st.sweep->source)) << " (" << st.sweep->images.size() << " "
    << Report::tr("frames") << ", " << per_exposure.size() << " " << Report::tr("exposures from") << " " << per_exposure.begin()->first
    << " " << Report::tr("to") << " " << per_exposure.rbegin()->first << " ms)<br>" << Report::tr("Method") << ": "
    << QString::fromStdString(out.fit.method) << "</p>\n";
  h << "<h2 class=\"" << verdict << "\">" << Report::tr("Verdict") << ": " << verdict << "</h2>\n<ul>";
  for (const std::string& r : out.check.reasons) h << "<li>" << Esc(QString::fromStdString(r)) << "</li>";
  if (out.check.reasons.empty()) h << "<li>" << Report::tr("every check within its limit") << "</li>";
  h << "</ul>\n<p>" << Report::tr("Held back") << ": " << out.check.held_out.exposure_ms << " ms, "
    << Report::tr("predicted from the others within") << " " << QString::number(out.check.held_out.median_abs_stops, 'f', 3)
    << " " << Report::tr("stops") << ". " << Report::tr("Levels covered") << ": R " << int(100 * out.check.coverage.share[0] + 0.5)
    << " %, G " << int(100 * out.check.coverage.share[1] + 0.5) << " %, B " << int(100 * out.check.coverage.share[2] + 0.5)
    << " %.</p>\n";
  h << "<table><tr><th>" << Report::tr("channel") << "</th><th>" << Report::tr("rms log residual") << "</th><th>f⁻¹(255)</th><th>"
    << "σs</th><th>σc</th><th>" << Report::tr("noise misfit") << "</th></tr>\n";
  for (int c = 0; c < 3; ++c) {
    h << "<tr><td>" << ch[c] << "</td><td>" << QString::number(out.fit.rms_log_residual[std::size_t(c)], 'f', 4)
      << "</td><td>" << QString::number(out.fit.inverse.table[std::size_t(c)][255], 'f', 3) << "</td>";
    if (out.noise_fit)
      h << "<td>" << QString::number(out.noise.sigma_s[std::size_t(c)], 'f', 5) << "</td><td>"
        << QString::number(out.noise.sigma_c[std::size_t(c)], 'f', 6) << "</td><td>"
        << QString::number(out.noise_fit->rms_relative_residual[std::size_t(c)], 'f', 2) << "</td>";
    else
      h << "<td colspan=3>" << Report::tr("not fitted") << "</td>";
    h << "</tr>\n";
  }
  h << "</table>\n<p>" << (out.noise_saved() ? Report::tr("The noise level function is saved with the response.")
                                             : Report::tr("The noise level function is not saved (see above); the engine uses "
                                                  "a generic one derived from the response."))
    << "</p>\n";
  h << "<h2>" << Report::tr("Exposures") << "</h2>\n<table><tr><th>" << Report::tr("exposure (ms)") << "</th><th>"
    << Report::tr("median |deviation| (stops)") << "</th><th>" << Report::tr("samples") << "</th></tr>\n";
  for (const auto& e : out.check.consistency)
    h << "<tr><td>" << e.exposure_ms << "</td><td>" << QString::number(e.median_abs_stops, 'f', 3) << "</td><td>"
      << e.samples << "</td></tr>\n";
  h << "</table>\n<h2>" << Report::tr("Plots") << "</h2>\n";
  for (const Figure& f : figures) h << "<img src=\"" << f.file << "\" alt=\"" << f.file << "\">\n";
  h << "<p>" << Report::tr("Profile") << ": <a href=\"sensor.json\">sensor.json</a></p>\n</body></html>\n";
  h.flush();
  if (file.error() != QFile::NoError) throw InputError(html, "write failed: " + file.errorString().toStdString());
  return html;
}

}  // namespace hdrf::wizard
