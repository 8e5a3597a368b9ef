// `hdrfusion-experiments nr-figure`: the paper's normalized-radiance figure. Two
// consecutive synthetic frames at very different exposures, side by side: the colour as
// delivered, the local mean and local standard deviation of the radiance, the normalized
// radiance and the pixel confidence. NR looks alike in both frames where the colour does not.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "experiments.h"
#include "common/error.h"
#include "imaging/imaging.h"
#include "normalized_radiance/normalized_radiance.h"
#include "radiometry/radiance.h"
#include "io/image_io.h"
#include "io/output_file.h"
#include "pipeline/frame_source.h"
#include "radiometry/pcf.h"

namespace hdrf::experiments {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {
// A scalar image to grey over [lo, hi] (log2 of the value when `log`), 0 = no data = black.
void PutGrey(ColorImage& sheet, int ox, int oy, const Image<float>& im, float lo, float hi, bool log) {
  for (int y = 0; y < im.height(); ++y)
    for (int x = 0; x < im.width(); ++x) {
      float v = im(x, y);
      std::uint8_t g = 0;
      if (v != 0.f) {
        if (log) v = v > 0 ? std::log2(v) : lo;
        g = std::uint8_t(std::lround(255.f * std::clamp((v - lo) / (hi - lo), 0.f, 1.f)));
      }
      sheet(ox + x, oy + y) = {g, g, g};
    }
}
float Percentile(const Image<float>& im, float q, bool log) {
  std::vector<float> v;
  for (std::size_t i = 0; i < im.size(); ++i)
    if (im[i] > 0) v.push_back(log ? std::log2(im[i]) : im[i]);
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + long(q * float(v.size() - 1)), v.end());
  return v[std::size_t(q * float(v.size() - 1))];
}
}  // namespace

int RunNrFigure(const std::string& out_dir) {
  sim::SimOptions so;
  so.frames = 60;
  so.ae.mode = sim::AeMode::kFlicker;
  pipeline::SyntheticFrameSource src(so);
  const SensorInfo s = src.sensor();
  const radiometry::PcfTables pcf = radiometry::ComputePcf(*s.response, *s.noise);
  const std::vector<pipeline::FrameInput> frames = pipeline::ReadAll(src);
  // The consecutive pair with the largest exposure change.
  std::size_t k = 1;
  for (std::size_t i = 1; i < frames.size(); ++i)
    if (std::abs(std::log2(*frames[i - 1].exposure_ms / *frames[i].exposure_ms)) >
        std::abs(std::log2(*frames[k - 1].exposure_ms / *frames[k].exposure_ms)))
      k = i;
  const int w = s.camera.width, h = s.camera.height;
  ColorImage sheet(5 * w, 2 * h);
  struct Maps {
    Image<float> lum, mean, stddev, nr, conf;
    double raw_mean = 0;
  };
  Maps m[2];
  for (int r = 0; r < 2; ++r) {
    const pipeline::FrameInput& f = frames[k - 1 + std::size_t(r)];
    RadianceImage rad;
    Image<float> maxconf;
    radiometry::ConvertFrame(f.color, *s.response, pcf, 1, rad, m[r].conf, maxconf);
    m[r].lum = nr::Luminance(rad);
    m[r].nr = nr::NormalizedRadiance(m[r].lum, {}, &m[r].mean, &m[r].stddev);
    for (std::size_t i = 0; i < f.color.size(); ++i) m[r].raw_mean += imaging::RawIntensityPixel(f.color[i]);
    m[r].raw_mean /= double(f.color.size());
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) sheet(x, r * h + y) = f.color(x, y);
  }
  // One grey scale per column, shared by both rows, so the rows compare directly.
  const float mlo = std::min(Percentile(m[0].mean, 0.01f, true), Percentile(m[1].mean, 0.01f, true));
  const float mhi = std::max(Percentile(m[0].mean, 0.99f, true), Percentile(m[1].mean, 0.99f, true));
  const float slo = std::min(Percentile(m[0].stddev, 0.01f, true), Percentile(m[1].stddev, 0.01f, true));
  const float shi = std::max(Percentile(m[0].stddev, 0.99f, true), Percentile(m[1].stddev, 0.99f, true));
  float chi = 1e-6f;
  for (int r = 0; r < 2; ++r)
    for (std::size_t i = 0; i < m[r].conf.size(); ++i) chi = std::max(chi, m[r].conf[i]);
  for (int r = 0; r < 2; ++r) {
    PutGrey(sheet, w, r * h, m[r].mean, mlo, mhi, true);
    PutGrey(sheet, 2 * w, r * h, m[r].stddev, slo, shi, true);
    PutGrey(sheet, 3 * w, r * h, m[r].nr, -3.f, 3.f, false);
    PutGrey(sheet, 4 * w, r * h, m[r].conf, 0.f, chi, false);
  }
  const fs::path out = out_dir;
  fs::create_directories(out);
  io::WriteColorPng(out / "nr_figure.png", sheet);
  // How alike the two rows are: NR against the delivered intensity and the radiance.
  // Over the pixels the engine trusts in both frames (mean PCF above 0.1; saturated and black
  // pixels have none).
  double nr_diff = 0, nr_abs = 0, lum_ratio = 0;
  long n = 0;
  for (std::size_t i = 0; i < m[0].nr.size(); ++i) {
    if (m[0].nr[i] == 0 || m[1].nr[i] == 0 || !(m[0].lum[i] > 0) || !(m[1].lum[i] > 0)) continue;
    if (m[0].conf[i] < 0.1f || m[1].conf[i] < 0.1f) continue;
    nr_diff += std::abs(m[0].nr[i] - m[1].nr[i]);
    nr_abs += 0.5 * (std::abs(m[0].nr[i]) + std::abs(m[1].nr[i]));
    lum_ratio += std::abs(std::log2(m[1].lum[i] / m[0].lum[i]));
    ++n;
  }
  if (n == 0) throw hdrf::Error("nr-figure: the two frames share no trusted pixel");
  const double ratio = *frames[k - 1].exposure_ms / *frames[k].exposure_ms;
  json j = {{"frames", {k - 1, k}},
            {"exposure_ms", {*frames[k - 1].exposure_ms, *frames[k].exposure_ms}},
            {"exposure_ratio", ratio},
            {"mean_delivered_intensity", {m[0].raw_mean, m[1].raw_mean}},
            {"pixels", n},
            {"nr_mean_abs_difference", nr_diff / double(n)},
            {"nr_mean_abs", nr_abs / double(n)},
            {"radiance_mean_abs_log2_ratio", lum_ratio / double(n)}};
  io::WriteFileAtomically(out / "nr_figure.json", j.dump(1) + "\n");
  char md[1024];
  std::snprintf(md, sizeof md,
                "# Normalized radiance across an exposure change (`hdrfusion-experiments nr-figure`)\n\n"
                "![colour, local mean, local std, NR, confidence](nr_figure.png)\n\n"
                "Frames %zu and %zu of the synthetic room with flickering auto exposure (%.2f ms and %.2f ms: "
                "%.2f stops apart; mean delivered intensity %.2f and %.2f). Columns: colour as delivered, local "
                "mean and local standard deviation of the radiance (log scale, one scale for both rows), "
                "normalized radiance (-3..3), PCF confidence p1. Over the %ld pixels the engine trusts in both "
                "frames (mean PCF above 0.1): the radiance (not exposure-compensated) differs by %.2f stops on "
                "average, the normalized radiance by %.3f (its mean magnitude is %.3f); the camera also moved "
                "between the frames, and pixels saturated in either frame are left out.\n",
                k - 1, k, *frames[k - 1].exposure_ms, *frames[k].exposure_ms, std::abs(std::log2(ratio)), m[0].raw_mean,
                m[1].raw_mean, n, lum_ratio / double(n), nr_diff / double(n), nr_abs / double(n));
  io::WriteFileAtomically(out / "nr_figure.md", md);
  std::printf("%s\nwrote %s/{nr_figure.png, nr_figure.md, nr_figure.json}\n", md, out_dir.c_str());
  return 0;
}

}  // namespace hdrf::experiments
