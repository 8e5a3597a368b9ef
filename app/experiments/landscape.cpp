// `hdrfusion-experiments landscape`: the paper's error-function figure. For pairs of
// consecutive synthetic frames whose exposure differs by a stop or more (flicker), each
// error function of the tracker is evaluated around the true pose, against a translation
// offset along x and a rotation offset about y: raw intensity (brightness constancy),
// normalized radiance (PCF-weighted), and point-to-plane ICP. Writes PNG plots, a Markdown
// table and landscape.json.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "experiments.h"
#include "cli/plot.h"
#include "common/error.h"
#include "imaging/imaging.h"
#include "normalized_radiance/normalized_radiance.h"
#include "radiometry/radiance.h"
#include "io/image_io.h"
#include "io/json_file.h"
#include "io/output_file.h"
#include "pipeline/frame_source.h"
#include "radiometry/pcf.h"
#include "tracking/tracking.h"

namespace hdrf::experiments {

using cli::Plot;

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

struct PreparedFrame {
  tracking::Live nr, raw;  // one level each: NR + PCF weight, raw intensity + weight 1
  Pose T;                  // true pose, relative to frame 0
  double exposure_ms = 0;
};

PreparedFrame Prepare(const pipeline::FrameInput& f, const SensorInfo& s, const radiometry::PcfTables& pcf,
                      const Pose& T0inv) {
  RadianceImage rad;
  Image<float> conf, maxconf;
  radiometry::ConvertFrame(f.color, *s.response, pcf, 1, rad, conf, maxconf);
  const DepthImage d = imaging::BilateralDepth(f.depth_m);
  const Image<float> nr = nr::NormalizedRadiance(nr::Luminance(rad), {});
  Image<float> raw(f.color.width(), f.color.height()), one(f.color.width(), f.color.height(), 1.f);
  for (std::size_t i = 0; i < raw.size(); ++i) raw[i] = imaging::RawIntensityPixel(f.color[i]);
  PreparedFrame p;
  p.nr = tracking::MakeLive(d, nr, conf, s.camera, 1);
  p.raw = tracking::MakeLive(d, raw, one, s.camera, 1);
  p.T = T0inv * *f.T_world_camera_true;
  p.exposure_ms = f.exposure_ms.value_or(0);
  return p;
}

// The reference (world frame) of a prepared live level.
tracking::Reference AsReference(const tracking::Live& live, const Pose& T, const PinholeCamera& cam) {
  const auto& L = live.levels[0];
  const RigidTransform R = ToRigidTransform(T);
  Image<Float3> vw(cam.width, cam.height), nw(cam.width, cam.height);
  for (std::size_t i = 0; i < vw.size(); ++i)
    if (L.vertex_c[i].z > 0 && Length(L.normal_c[i]) > 0) {
      vw[i] = R.Apply(L.vertex_c[i]);
      nw[i] = R.Rotate(L.normal_c[i]);
    }
  return tracking::MakeReference(vw, nw, L.intensity, cam, 1, T);
}

// Robust mean squared residual of one error function at a pose.
double ErrorAt(const tracking::Reference& ref, const tracking::Live& live, const Pose& T, tracking::TrackerKind k) {
  tracking::TrackerOptions o;
  o.kind = k;
  const tracking::GnSystem g = tracking::AccumulateCpu(ref.levels[0].view(), ref.T_world_camera,
                                                       live.levels[0].view(), T, o);
  const bool icp = k == tracking::TrackerKind::kIcp;
  const double w = icp ? g.v[29] : g.v[30];
  return w > 0 ? (icp ? g.v[27] : g.v[28]) / w : std::nan("");
}

}  // namespace

int RunLandscape(const std::string& out_dir, int pairs, int steps) {
  sim::SimOptions so;
  so.frames = 120;
  so.ae.mode = sim::AeMode::kFlicker;
  pipeline::SyntheticFrameSource src(so);
  const SensorInfo s = src.sensor();
  const radiometry::PcfTables pcf = radiometry::ComputePcf(*s.response, *s.noise);
  const std::vector<pipeline::FrameInput> frames = pipeline::ReadAll(src);
  const Pose T0inv = frames[0].T_world_camera_true->inverse();
  const fs::path out = out_dir;
  fs::create_directories(out);
  struct Fn {
    const char* name;
    tracking::TrackerKind kind;
    bool nr;
    Rgb8 colour;
  };
  const Fn fns[] = {{"intensity (brightness constancy)", tracking::TrackerKind::kIntensity, false, {210, 40, 40}},
                    {"normalized radiance (PCF)", tracking::TrackerKind::kNr, true, {30, 150, 50}},
                    {"ICP (point-to-plane)", tracking::TrackerKind::kIcp, true, {40, 70, 210}}};
  const double max_t = 0.05, max_r = 3.0 * 3.14159265358979 / 180.0;
  std::vector<double> offs;
  for (int i = -steps; i <= steps; ++i) offs.push_back(double(i) / steps);
  // Mean over pairs of each function's curve, each curve divided by its value at the truth.
  std::vector<std::vector<double>> curve_t(3, std::vector<double>(offs.size(), 0.0)), curve_r = curve_t;
  json j = {{"pairs", json::array()}, {"max_translation_m", max_t}, {"max_rotation_deg", 3.0}};
  int used = 0;
  for (std::size_t k = 1; k < frames.size() && used < pairs; ++k) {
    const double ratio = *frames[k - 1].exposure_ms / *frames[k].exposure_ms;
    if (std::abs(std::log2(ratio)) < 1.0) continue;  // only pairs a stop or more apart
    const PreparedFrame a = Prepare(frames[k - 1], s, pcf, T0inv), b = Prepare(frames[k], s, pcf, T0inv);
    json pj = {{"frames", {k - 1, k}}, {"exposure_ratio", ratio}};
    for (int fi = 0; fi < 3; ++fi) {
      const tracking::Reference ref = AsReference(fns[fi].nr ? a.nr : a.raw, a.T, s.camera);
      const tracking::Live& live = fns[fi].nr ? b.nr : b.raw;
      const double e0 = ErrorAt(ref, live, b.T, fns[fi].kind);
      std::vector<double> et, er;
      for (double u : offs) {
        Vec6 dt = Vec6::Zero(), dr = Vec6::Zero();
        dt(0) = u * max_t;
        dr(4) = u * max_r;
        et.push_back(ErrorAt(ref, live, b.T * se3::Exp(dt), fns[fi].kind));
        er.push_back(ErrorAt(ref, live, b.T * se3::Exp(dr), fns[fi].kind));
      }
      auto argmin = [&](const std::vector<double>& e) {
        std::size_t m = 0;
        for (std::size_t i = 1; i < e.size(); ++i)
          if (e[i] < e[m]) m = i;
        return offs[m];
      };
      for (std::size_t i = 0; i < offs.size(); ++i) {
        curve_t[std::size_t(fi)][i] += et[i] / e0;
        curve_r[std::size_t(fi)][i] += er[i] / e0;
      }
      pj[fns[fi].name] = {{"error_at_truth", e0},
                          {"argmin_translation_m", argmin(et) * max_t},
                          {"argmin_rotation_deg", argmin(er) * 3.0},
                          {"translation", et},
                          {"rotation", er}};
    }
    j["pairs"].push_back(pj);
    ++used;
  }
  if (used == 0) throw hdrf::Error("landscape: no frame pair a stop apart in the sequence");
  // Plots: mean normalised error against the offset (x: -5..5 cm / -3..3 degrees).
  double top = 1;
  for (int fi = 0; fi < 3; ++fi)
    for (std::size_t i = 0; i < offs.size(); ++i) {
      curve_t[std::size_t(fi)][i] /= used;
      curve_r[std::size_t(fi)][i] /= used;
      if (std::isfinite(curve_t[std::size_t(fi)][i])) top = std::max(top, curve_t[std::size_t(fi)][i]);
      if (std::isfinite(curve_r[std::size_t(fi)][i])) top = std::max(top, curve_r[std::size_t(fi)][i]);
    }
  Plot pt(640, 400, -1, 1, 0, top), pr(640, 400, -1, 1, 0, top);
  for (int fi = 0; fi < 3; ++fi) {
    pt.Line(offs, curve_t[std::size_t(fi)], fns[fi].colour);
    pr.Line(offs, curve_r[std::size_t(fi)], fns[fi].colour);
  }
  io::WriteColorPng(out / "landscape_translation.png", pt.image());
  io::WriteColorPng(out / "landscape_rotation.png", pr.image());
  std::string md =
      "# Error landscape (`hdrfusion-experiments landscape`)\n\n"
      "Synthetic room, flickering auto exposure, 320x240; " + std::to_string(used) +
      " pairs of consecutive frames whose exposures differ by a stop or more. Each error function is the "
      "robust mean squared residual of the tracker's term, evaluated at the true pose of the second frame "
      "moved along x (-5..5 cm) or rotated about y (-3..3 degrees), divided by its value at the truth "
      "(1 = truth), averaged over the pairs.\n\n"
      "Plots: `landscape_translation.png`, `landscape_rotation.png` (x axis: offset from -max to +max; "
      "red: intensity, green: normalized radiance, blue: ICP).\n\n"
      "| error function | mean of error at max offset / at truth (translation) | (rotation) | pairs whose minimum is "
      "the truth (translation, +-1 step) | (rotation) |\n|---|---|---|---|---|\n";
  const double step_t = max_t / steps, step_r = 3.0 / steps;
  for (int fi = 0; fi < 3; ++fi) {
    int ok_t = 0, ok_r = 0;
    for (const auto& pj : j["pairs"]) {
      ok_t += std::abs(pj[fns[fi].name]["argmin_translation_m"].get<double>()) <= step_t + 1e-9;
      ok_r += std::abs(pj[fns[fi].name]["argmin_rotation_deg"].get<double>()) <= step_r + 1e-9;
    }
    const auto& ct = curve_t[std::size_t(fi)];
    const auto& cr = curve_r[std::size_t(fi)];
    char line[256];
    std::snprintf(line, sizeof line, "| %s | %.2f | %.2f | %d / %d | %d / %d |\n", fns[fi].name,
                  0.5 * (ct.front() + ct.back()), 0.5 * (cr.front() + cr.back()), ok_t, used, ok_r, used);
    md += line;
    j["summary"][fns[fi].name] = {{"contrast_translation", 0.5 * (ct.front() + ct.back())},
                                  {"contrast_rotation", 0.5 * (cr.front() + cr.back())},
                                  {"min_at_truth_translation", ok_t},
                                  {"min_at_truth_rotation", ok_r}};
  }
  j["pairs_used"] = used;
  io::WriteFileAtomically(out / "landscape.md", md);
  io::WriteFileAtomically(out / "landscape.json", j.dump(1) + "\n");
  std::printf("%s", md.c_str());
  std::printf("\nwrote %s/{landscape.md, landscape.json, landscape_translation.png, landscape_rotation.png}\n",
              out_dir.c_str());
  return 0;
}

}  // namespace hdrf::experiments
