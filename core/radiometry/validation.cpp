#include "radiometry/validation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>

#include "common/error.h"
#include "common/message.h"
#include "radiometry/calibration_detail.h"

namespace hdrf::radiometry {

namespace {

std::vector<double> DistinctExposures(const Sweep& s) { return detail::GroupByExposure(s).exposure; }

std::string Ms(double v) {
  std::ostringstream os;
  os.precision(4);
  os << v << " ms";
  return os.str();
}


}  // namespace

LevelCoverage MeasureLevelCoverage(const Sweep& s, ClipLevels clip) {
  LevelCoverage out;
  std::vector<const ColorImage*> first;  // one frame per exposure
  for (const auto& group : detail::GroupByExposure(s).images) first.push_back(&s.images[std::size_t(group[0])]);
  constexpr int kLo = 8, kHi = 247, kMin = 4;
  const std::size_t n = s.images.empty() ? 0 : s.images[0].size();
  for (int c = 0; c < 3; ++c) {
    std::array<int, 256> count{};
    for (std::size_t p = 0; p < n; p += 3) {
      int unclipped = 0;
      for (const ColorImage* im : first) unclipped += !detail::Clipped(detail::Level((*im)[p], c), clip);
      if (unclipped < 2) continue;
      for (const ColorImage* im : first) ++count[detail::Level((*im)[p], c)];
    }
    int covered = 0, run = 0, best = 0;
    out.gap_from[c] = 1, out.gap_to[c] = 0;
    for (int z = kLo; z <= kHi; ++z) {
      if (count[std::size_t(z)] >= kMin) {
        ++covered;
        run = 0;
      } else if (++run > best) {
        best = run;
        out.gap_from[c] = z - run + 1;
        out.gap_to[c] = z;
      }
    }
    out.share[c] = double(covered) / double(kHi - kLo + 1);
  }
  return out;
}

void CheckSweepForCalibration(const Sweep& s) {
  CheckSweep(s);
  const std::vector<double> e = DistinctExposures(s);
  if (e.size() < 3) {
    std::ostringstream os;
    os << s.source << ": " << e.size() << " distinct exposures (" << Ms(e.front()) << " and " << Ms(e.back())
       << ") cannot calibrate a camera: the response is only pinned down where exposures overlap, and with two "
          "nothing is left to check the fit against. Capture at least 3 (5 or more, a stop or half a stop apart, "
          "from mostly dark to mostly saturated)";
    throw Error(os.str());
  }
  const LevelCoverage cov = MeasureLevelCoverage(s);
  for (int c = 0; c < 3; ++c)
    if (cov.share[c] < 0.5) {
      std::ostringstream os;
      os << s.source << ": the scene shows too few distinct brightnesses to calibrate: only " << int(100 * cov.share[c])
         << " % of the levels of the " << "RGB"[c] << " channel are seen in pixels that another exposure also shows "
         << "(levels " << cov.gap_from[c] << " to " << cov.gap_to[c] << " not at all). Point the camera at a "
         << "scene with dark, middle and bright parts (not a white wall or a single card)";
      throw Error(os.str());
    }
}

const char* VerdictName(Verdict v) {
  switch (v) {
    case Verdict::kGood: return "good";
    case Verdict::kMarginal: return "marginal";
    default: return "redo";
  }
}

LevelTable LevelResiduals(const Sweep& s, const InverseResponse& inverse, const RadianceImage& merged,
                          ClipLevels clip) {
  LevelTable out;
  const detail::Groups g = detail::GroupByExposure(s);
  for (int c = 0; c < 3; ++c) {
    std::array<std::vector<float>, kLevels> per_level;
    for (std::size_t k = 0; k < g.exposure.size(); ++k) {
      const ColorImage& im = s.images[std::size_t(g.images[k][0])];
      for (std::size_t p = 0; p < im.size(); p += 2) {
        const int z = detail::Level(im[p], c);
        const Float3 L = merged[p];
        const float l = c == 0 ? L.x : (c == 1 ? L.y : L.z);
        if (detail::Clipped(z, clip) || !(l > 0) || !(inverse.table[c][z] > 0)) continue;
        per_level[std::size_t(z)].push_back(float(std::log2(inverse.table[c][z] / (g.exposure[k] * l))));
      }
    }
    for (int z = 0; z < kLevels; ++z) {
      auto& v = per_level[std::size_t(z)];
      if (v.size() < 20) {
        out[c][z] = NAN;
        continue;
      }
      std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
      out[c][z] = v[v.size() / 2];
    }
  }
  return out;
}

CalibrationCheck CheckCalibration(const Sweep& sweep, const InverseResponse& inverse, const NoiseModel& noise,
                                  const std::optional<std::array<double, 3>>& noise_misfit,
                                  const std::function<InverseResponse(const Sweep&)>& refit,
                                  const CheckLimits& lim) {
  CalibrationCheck out;
  auto grade = [&](Verdict v, const std::string& why) {
    out.verdict = std::max(out.verdict, v);
    out.reasons.push_back(why);
  };
  // Every exposure against the merge of all.
  const RadianceImage merged = MergeHdr(sweep, inverse, noise);
  out.consistency = MergeConsistency(sweep, inverse, merged, {}, &noise);
  out.level_residual_stops = LevelResiduals(sweep, inverse, merged);
  {
    int over_good = 0, over_redo = 0, judged = 0;
    const ExposureConsistency* worst = nullptr;
    for (const ExposureConsistency& c : out.consistency) {
      if (c.samples < 100) continue;
      ++judged;
      over_good += c.median_abs_stops > lim.good_stops;
      over_redo += c.median_abs_stops > lim.redo_stops;
      if (!worst || c.median_abs_stops > worst->median_abs_stops) worst = &c;
    }
    if (worst && worst->median_abs_stops > lim.good_stops) {
      const std::string worst_stops = Num(worst->median_abs_stops, 2), at = Sig(worst->exposure_ms);
      if (over_redo)
        grade(Verdict::kRedo, Say(words::kExposuresDisagreeRedo, {std::to_string(over_redo), std::to_string(judged),
                                                                  Num(lim.redo_stops, 2), worst_stops, at}));
      else
        grade(Verdict::kMarginal,
              Say(words::kExposuresDisagree, {std::to_string(over_good), std::to_string(judged), Num(lim.good_stops, 2),
                                              worst_stops, at, Num(lim.good_stops, 2)}));
    }
  }
  // The middle exposure held back: fitted without it, predicted from the others.
  const std::vector<double> e = DistinctExposures(sweep);
  const double held = e[e.size() / 2];
  Sweep others, held_back;
  others.source = held_back.source = sweep.source;
  for (std::size_t i = 0; i < sweep.images.size(); ++i) {
    Sweep& to = sweep.exposure_ms[i] == held ? held_back : others;
    to.images.push_back(sweep.images[i].Clone());
    to.exposure_ms.push_back(sweep.exposure_ms[i]);
  }
  try {
    const InverseResponse without = refit(others);
    const RadianceImage merged_others = MergeHdr(others, without, noise);
    const auto c = MergeConsistency(held_back, without, merged_others, {}, &noise);
    if (!c.empty()) out.held_out = c.front();
    out.held_out.exposure_ms = held;
    if (out.held_out.samples < 100)
      grade(Verdict::kMarginal, Say(words::kHeldBackFewPixels, {Sig(held)}));
    else if (out.held_out.median_abs_stops > lim.redo_stops)
      grade(Verdict::kRedo, Say(words::kHeldBackRedo,
                                {Sig(held), Num(out.held_out.median_abs_stops, 2), Num(lim.redo_stops, 2)}));
    else if (out.held_out.median_abs_stops > lim.good_stops)
      grade(Verdict::kMarginal, Say(words::kHeldBackMarginal,
                                    {Sig(held), Num(out.held_out.median_abs_stops, 2), Num(lim.good_stops, 2)}));
  } catch (const Error& err) {
    out.held_out.exposure_ms = held;
    grade(Verdict::kRedo, Say(words::kHeldBackFailed, {Sig(held), err.what()}));
  }
  // Levels the scene leaves uncovered: the curve is interpolated there.
  out.coverage = MeasureLevelCoverage(sweep);
  for (int c = 0; c < 3; ++c)
    if (out.coverage.share[c] < 0.9) {
      grade(Verdict::kMarginal, Say(words::kLevelsUncovered, {std::to_string(int(100 * out.coverage.share[c])),
                                                              std::string(1, "RGB"[c]),
                                                              std::to_string(out.coverage.gap_from[c]),
                                                              std::to_string(out.coverage.gap_to[c])}));
    }
  // Steps between exposures.
  double step = 0;
  for (std::size_t k = 1; k < e.size(); ++k) step = std::max(step, std::log2(e[k] / e[k - 1]));
  if (step > lim.max_step_stops)
    grade(Verdict::kMarginal, Say(words::kStepsTooWide, {Num(step, 2)}));
  // The noise fit.
  if (noise_misfit) {
    const double worst = std::max({(*noise_misfit)[0], (*noise_misfit)[1], (*noise_misfit)[2]});
    if (!(worst <= lim.noise_misfit)) {
      out.noise_usable = false;
      grade(Verdict::kMarginal, Say(words::kNoiseMisfit, {Sig(worst, 3), Sig(lim.noise_misfit, 3)}));
    }
  }
  return out;
}

}  // namespace hdrf::radiometry
