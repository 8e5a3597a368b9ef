// hdrfusion calibrate SWEEP --out sensor.json: camera response, noise level function and PCF
// from an exposure sweep, with a quality report and plots.
// hdrfusion merge SWEEP --sensor sensor.json --out hdr.exr: the HDR merge of a sweep.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <unistd.h>

#include "io/output_file.h"
#include "cli/commands.h"
#include "cli/plot.h"
#include "common/error.h"
#include "io/exr.h"
#include "io/image_io.h"
#include "io/sensor_json.h"
#include "io/sweep.h"
#include "radiometry/calibration.h"
#include "radiometry/calibration_job.h"
#include "radiometry/pcf.h"
#include "radiometry/validation.h"
#include "sensors/profiles.h"

namespace hdrf::cli {

namespace fs = std::filesystem;
using namespace radiometry;

namespace {

void WritePlots(const fs::path& dir, const InverseResponse& inv, const PcfTables& pcf) {
  fs::create_directories(dir);
  std::vector<double> x(256);
  for (int i = 0; i < 256; ++i) x[std::size_t(i)] = i;
  double top = 0;
  for (int c = 0; c < 3; ++c) top = std::max(top, double(inv.table[c][255]));
  Plot response(640, 400, 0, 255, 0, top);
  const LevelTable d = ResponseDerivative(inv);
  double dmax = 0;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 256; ++i) dmax = std::max(dmax, double(d[c][i]));
  Plot deriv(640, 400, 0, 255, 0, dmax);
  for (int c = 0; c < 3; ++c) {
    std::vector<double> y(256), yd(256);
    for (int i = 0; i < 256; ++i) {
      y[std::size_t(i)] = inv.table[c][i];
      yd[std::size_t(i)] = d[c][i];
    }
    response.Line(x, y, kChannelColor[c]);
    deriv.Line(x, yd, kChannelColor[c]);
  }
  io::WriteColorPng(dir / "response.png", response.image());
  io::WriteColorPng(dir / "derivative.png", deriv.image());
  // PCF family: p1, p2, p3 stacked (p0 = 1 everywhere), one curve per channel.
  ColorImage stack(640, 3 * 300);
  for (int k = 1; k <= 3; ++k) {
    Plot p(640, 300, 0, 255, 0, 1);
    for (int c = 0; c < 3; ++c) {
      std::vector<double> y(256);
      for (int i = 0; i < 256; ++i) y[std::size_t(i)] = pcf[k][c][i];
      p.Line(x, y, kChannelColor[c]);
    }
    for (int yy = 0; yy < 300; ++yy)
      for (int xx = 0; xx < 640; ++xx) stack(xx, (k - 1) * 300 + yy) = p.image()(xx, yy);
  }
  io::WriteColorPng(dir / "pcf.png", stack);
}

}  // namespace

Command AddCalibrateCommand(CLI::App& app) {
  struct Args {
    std::string sweep, out, method = "debevec", basis, plots;
    bool save_profile = false;
    int emor_components = EmorOptions{}.components;
    int threshold_passes = DebevecOptions{}.threshold_passes;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand(
      "calibrate", "Fit camera response, noise and PCF from an exposure sweep; write sensor.json");
  cmd->add_option("SWEEP", a->sweep, "Exposure sweep folder (docs/formats.md)")->required();
  cmd->add_option("--out", a->out, "sensor.json to write")->required();
  cmd->add_option("--method", a->method, "Response fit")
      ->check(CLI::IsMember({"debevec", "robertson", "emor"}))->capture_default_str();
  cmd->add_option("--emor-basis", a->basis, "invemor.txt of the EMoR distribution (--method emor)");
  cmd->add_option("--emor-components", a->emor_components, "EMoR basis components")
      ->capture_default_str();
  cmd->add_option("--threshold-passes", a->threshold_passes,
                  "Noise-aware refinement of the fitted curve on the level thresholds (0: the classic method)")
      ->check(CLI::Range(0, 10))->capture_default_str();
  cmd->add_option("--plots", a->plots, "Folder for response.png, derivative.png, pcf.png");
  cmd->add_flag("--save-profile", a->save_profile,
                "Also store the result as the profile of the sweep's camera (the serial in its sensor.json), "
                "used whenever that camera is connected");
  return {cmd, [a] {
    // The output is checked before the sweep is read and fitted: a typo in --out must not
    // cost the whole fit.
    // (The sweep's own sensor.json may be the output: the calibration completes it.)
    const fs::path out = a->out;
    if (fs::is_directory(out)) throw InputError(out, "is a folder; give the sensor.json file to write");
    io::CheckOutputFile(out, {}, {".json"});
    if (!a->plots.empty()) io::CheckOutputFolderEarly(a->plots, {a->sweep});
    const Sweep sweep = io::ReadSweep(a->sweep);
    SensorInfo sensor = io::ReadSensorJson(fs::path(a->sweep) / "sensor.json");
    std::map<double, int> per_exposure;
    for (double e : sweep.exposure_ms) ++per_exposure[e];
    std::printf("sweep %s: %zu frames, %zu exposures from %.4g to %.4g ms\n", a->sweep.c_str(),
                sweep.images.size(), per_exposure.size(), per_exposure.begin()->first,
                per_exposure.rbegin()->first);
    CalibrationSettings settings;
    settings.method = a->method;
    settings.emor_components = a->emor_components;
    settings.threshold_passes = a->threshold_passes;
    if (a->method == "emor") {
      if (a->basis.empty())
        throw SettingError("--emor-basis", "--method emor needs the EMoR basis file invemor.txt");
      settings.basis = EmorBasis::Load(a->basis);
    }
    // Refuses before the fit: too few exposures, reversed, moved, clipped, flat.
    const CalibrationOutcome run = RunCalibration(sweep, settings);
    const ResponseFit& fit = run.fit;
    std::printf("\nresponse (%s%s), scaled so that f^-1(128) = 1 per channel\n", fit.method.c_str(),
                a->threshold_passes > 0 ? ", refined on the level thresholds" : ", classic");
    const char* ch = "RGB";
    for (int c = 0; c < 3; ++c)
      std::printf("  %c: rms log residual %.4f (%.2f %%), %d sample pixels, f^-1(255)/f^-1(128) = %.2f\n",
                  ch[c], fit.rms_log_residual[c], 100 * (std::exp(fit.rms_log_residual[c]) - 1),
                  fit.samples_used[c], fit.inverse.table[c][255]);
    if (fit.method == "emor") {
      const double gap = std::max({fit.basis_gap[0], fit.basis_gap[1], fit.basis_gap[2]});
      std::printf("  EMoR against the free-form (Debevec) curve of the same sweep: largest difference "
                  "%.2f %% / %.2f %% / %.2f %% of the range at levels %d / %d / %d (R/G/B, levels 5-250)\n",
                  100 * fit.basis_gap[0], 100 * fit.basis_gap[1], 100 * fit.basis_gap[2],
                  fit.basis_gap_level[0], fit.basis_gap_level[1], fit.basis_gap_level[2]);
      if (gap > 0.01)
        std::printf("  warning: this camera's response lies outside what %d EMoR components represent "
                    "(%.1f %% apart); --method debevec follows it more closely\n", a->emor_components,
                    100 * gap);
    }
    if (run.noise_fit) {
      std::printf("\nnoise level function (Var R = R sigma_s^2 + sigma_c^2)\n");
      for (int c = 0; c < 3; ++c)
        std::printf("  %c: sigma_s %.5f  sigma_c %.6f  (%zu level thresholds, rms relative misfit %.2f)\n",
                    ch[c], run.noise.sigma_s[c], run.noise.sigma_c[c], run.noise_fit->levels[c].size(),
                    run.noise_fit->rms_relative_residual[c]);
    } else {
      std::printf("\nnoise level function not fitted: %s\n", run.noise_error.c_str());
    }
    const CalibrationCheck& check = run.check;
    std::printf("\nchecking the fit (each exposure against the merge; the middle one held back and predicted)\n");
    for (const auto& e : check.consistency)
      std::printf("  %9.4g ms: median |deviation| %.3f stops over %ld samples\n", e.exposure_ms,
                  e.median_abs_stops, e.samples);
    std::printf("  held back %.4g ms: predicted within %.3f stops (median over %ld samples)\n",
                check.held_out.exposure_ms, check.held_out.median_abs_stops, check.held_out.samples);
    std::printf("  levels covered by the scene: R %.0f %%, G %.0f %%, B %.0f %% (of levels 8-247)\n",
                100 * check.coverage.share[0], 100 * check.coverage.share[1], 100 * check.coverage.share[2]);
    std::printf("verdict: %s\n", VerdictName(check.verdict));
    for (const std::string& r : check.reasons) std::printf("  - %s\n", r.c_str());
    if (check.verdict == Verdict::kRedo) {
      std::string why;
      for (const std::string& r : check.reasons) why += "\n  - " + r;
      throw Error(a->sweep + ": the calibration is not good enough to use, nothing was written (verdict: redo):" + why +
                  "\nRedo the sweep: static camera and scene, auto exposure off, 5 or more exposures a stop or "
                  "less apart from mostly dark to mostly saturated");
    }
    sensor = run.Apply(sensor);
    const bool have_noise = run.noise_saved();
    io::UpdateSensorJson(a->out, sensor);  // other tools' keys in an existing file are kept
    std::printf("\nwrote %s (response%s)\n", a->out.c_str(), have_noise ? " and noise" : " only");
    if (a->save_profile) {
      if (!sensor.device || sensor.device->serial.empty())
        throw InputError(fs::path(a->sweep) / "sensor.json",
                         "names no device serial (hdrfusion.device.serial), so the profile cannot be stored for a "
                         "camera; " + a->out + " was written");
      std::printf("stored as the profile of %s: %s\n", sensor.device->serial.c_str(),
                  sensors::SaveProfile(sensor.device->serial, sensor).c_str());
    }
    if (!a->plots.empty()) {
      WritePlots(a->plots, fit.inverse, run.pcf);
      std::printf("wrote %s/response.png (f^-1 against level, R red, G green, B blue), "
                  "derivative.png (f' against level), pcf.png (p1, p2, p3 from top, 0..1)\n",
                  a->plots.c_str());
    }
    return 0;
  }};
}

Command AddMergeCommand(CLI::App& app) {
  struct Args {
    std::string sweep, sensor, out;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("merge", "Merge an exposure sweep into one HDR radiance image");
  cmd->add_option("SWEEP", a->sweep, "Exposure sweep folder")->required();
  cmd->add_option("--sensor", a->sensor, "sensor.json with response (and noise)")->required();
  cmd->add_option("--out", a->out, "Output OpenEXR (float)")->required();
  return {cmd, [a] {
    io::CheckOutputFile(a->out, {a->sweep, a->sensor}, {".exr"});
    const SensorInfo s = io::ReadSensorJson(a->sensor);
    if (!s.response)
      throw InputError(a->sensor, "has no 'response'; run hdrfusion calibrate first");
    NoiseModel noise;
    if (s.noise) {
      noise = *s.noise;
    } else {
      std::fprintf(stderr, "merge: %s has no 'noise'; weighting with sigma_s = 0.02, "
                           "sigma_c = 0.002\n", a->sensor.c_str());
      noise.sigma_s = {0.02f, 0.02f, 0.02f};
      noise.sigma_c = {0.002f, 0.002f, 0.002f};
    }
    const Sweep sweep = io::ReadSweep(a->sweep);
    CheckSweep(sweep);
    const RadianceImage merged = MergeHdr(sweep, *s.response, noise);
    io::WriteExr(a->out, merged, io::ExrPrecision::kFloat);
    for (const auto& e : MergeConsistency(sweep, *s.response, merged))
      std::printf("%9.4g ms: median |deviation| %.3f stops (%ld samples)\n", e.exposure_ms,
                  e.median_abs_stops, e.samples);
    std::printf("wrote %s (%dx%d)\n", a->out.c_str(), merged.width(), merged.height());
    return 0;
  }};
}

}  // namespace hdrf::cli
