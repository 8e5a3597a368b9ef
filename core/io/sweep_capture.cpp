#include "io/sweep_capture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "common/message.h"
#include "io/json_file.h"
#include "io/image_io.h"
#include "io/sequence.h"
#include "io/output_file.h"

namespace hdrf::io {

namespace fs = std::filesystem;
using radiometry::SweepCamera;
using FixAt = CaptureProblem::FixAt;

namespace {

// A share as a whole percentage, the number only (the wordings say "%").
std::string Percent(double share) { return Num(100 * share, 0); }

bool Cancelled(const std::atomic<bool>* cancel) { return cancel && cancel->load(); }

// Sets the exposure and drops the frames that may still carry the old one.
double Expose(SweepCamera& camera, double ms, int settle) {
  const double actual = camera.SetExposure(ms);
  for (int i = 0; i < settle; ++i) camera.Grab();
  return actual;
}

struct FrameStats {
  double high = 0, low = 0;  // shares of pixels saturated and black (IsSaturated, IsBlack)
  double dim = 0;            // share with all channels <= 20
  double mean_green = 0;
};
FrameStats Stats(const ColorImage& im) {
  FrameStats s;
  long high = 0, low = 0, dim = 0;
  double sum = 0;
  for (std::size_t p = 0; p < im.size(); ++p) {
    const Rgb8 v = im[p];
    high += IsSaturated(v);
    low += IsBlack(v);
    dim += std::max({v.r, v.g, v.b}) <= 20;
    sum += v.g;
  }
  const double n = double(std::max<std::size_t>(im.size(), 1));
  s.high = double(high) / n;
  s.low = double(low) / n;
  s.dim = double(dim) / n;
  s.mean_green = sum / n;
  return s;
}

// The relative change of mean level between two frames of one exposure, over pixels
// unclipped in both (all channels); 0 when too few.
double MeanChange(const ColorImage& a, const ColorImage& b) {
  double sa = 0, sb = 0;
  long n = 0;
  for (std::size_t p = 0; p < a.size(); ++p) {
    const Rgb8 u = a[p], v = b[p];
    const int lo = std::min({u.r, u.g, u.b, v.r, v.g, v.b}), hi = std::max({u.r, u.g, u.b, v.r, v.g, v.b});
    if (lo < 10 || hi > 245) continue;
    sa += u.r + u.g + u.b;
    sb += v.r + v.g + v.b;
    ++n;
  }
  if (n < 500 || sa <= 0) return 0;
  return std::abs(sb / sa - 1.0);
}

// Share of pixels with every channel in 20..235 (well exposed).
double MidTones(const ColorImage& im) {
  long n = 0;
  for (std::size_t p = 0; p < im.size(); ++p) {
    const Rgb8 v = im[p];
    n += std::min({v.r, v.g, v.b}) >= 20 && std::max({v.r, v.g, v.b}) <= 235;
  }
  return double(n) / double(std::max<std::size_t>(im.size(), 1));
}

nlohmann::json ToJson(const CaptureRecord& r) {
  const SweepPlanOptions& o = r.plan.options;
  return {{"camera", r.camera},
          {"serial", r.serial},
          {"exposures_ms", r.plan.exposures_ms},
          {"options",
           {{"step_stops", o.step_stops}, {"repeats", o.repeats}, {"settle_frames", o.settle_frames},
            {"max_retries", o.max_retries}, {"flicker_share", o.flicker_share}}},
          {"steps_done", r.steps_done},
          {"recaptures", r.recaptures}};
}

// Atomically: a crash leaves the old record or the new one.
void WriteRecord(const fs::path& folder, const CaptureRecord& r) {
  WriteFileAtomically(folder / "capture.json", ToJson(r).dump(2) + "\n");
}

}  // namespace

void SweepPlanOptions::Check() const {
  if (!(step_stops >= 0.1 && step_stops <= 2)) throw SettingError("step", "must be 0.1 to 2 stops");
  if (repeats < 1 || repeats > 50) throw SettingError("repeats", "must be 1 to 50 (3 or more for the noise fit)");
  if (min_ms < 0 || max_ms < 0 || (min_ms > 0 && max_ms > 0 && max_ms <= min_ms))
    throw SettingError("min-ms/max-ms", "need 0 < min < max (0: metered)");
  if (max_exposures < 3 || max_exposures > 200) throw SettingError("max-exposures", "must be 3 to 200");
  if (settle_frames < 0 || settle_frames > 30) throw SettingError("settle", "must be 0 to 30 frames");
  if (max_retries < 0 || max_retries > 20) throw SettingError("retries", "must be 0 to 20");
  if (!(flicker_share > 0 && flicker_share < 0.5)) throw SettingError("flicker", "must be in (0, 0.5)");
}

void VerifyManualExposure(SweepCamera& camera) {
  const radiometry::ColourLock lock = camera.colour_lock();
  if (lock.auto_exposure)
    throw CaptureProblem(FixAt::kSetup, Say(words::kAutoExposureOn, {camera.description()}));
  if (lock.auto_white_balance)
    throw CaptureProblem(FixAt::kSetup, Say(words::kAutoWhiteBalanceOn, {camera.description()}));
  // The exposure must act on the images: two stops apart, the mid-tones must brighten.
  const radiometry::ExposureLimits lim = camera.limits();
  double a = std::clamp(std::sqrt(lim.min_ms * lim.max_ms), lim.min_ms, lim.max_ms / 4);
  for (int tries = 0; tries < 8; ++tries) {
    const double ta = Expose(camera, a, 2);
    const FrameStats sa = Stats(camera.Grab());
    const double tb = Expose(camera, 4 * a, 2);
    const FrameStats sb = Stats(camera.Grab());
    if (sa.high > 0.5) {  // too bright to judge: shorter
      if (a / 4 < lim.min_ms) break;
      a /= 4;
      continue;
    }
    if (sb.low > 0.5) {  // too dark to judge: longer
      if (16 * a > lim.max_ms) break;
      a *= 4;
      continue;
    }
    if (sb.mean_green < sa.mean_green * 1.2 + 2) {
      throw CaptureProblem(FixAt::kSetup, Say(words::kExposureIgnored, {camera.description(), Num(sa.mean_green, 1),
                                                                        Sig(ta), Num(sb.mean_green, 1), Sig(tb)}));
    }
    return;
  }
  // The scene is all saturated or all black at every pair tried: PlanSweep says which.
}

SweepPlan PlanSweep(SweepCamera& camera, const SweepPlanOptions& options, const CaptureProgress& progress,
                    const std::atomic<bool>* cancel) {
  options.Check();
  VerifyManualExposure(camera);
  const radiometry::ExposureLimits lim = camera.limits();
  SweepPlan plan;
  plan.options = options;
  CaptureStatus status;
  status.stage = "metering";
  auto measure = [&](double ms) {
    status.exposure_ms = Expose(camera, ms, options.settle_frames);
    if (progress) progress(status);
    return Stats(camera.Grab());
  };
  // Shortest: the brightest parts (all but 0.5 %) unclipped.
  double lo = options.min_ms > 0 ? camera.Quantise(options.min_ms) : 0;
  if (lo == 0) {
    double t = camera.Quantise(std::clamp(10.0, lim.min_ms, lim.max_ms));
    FrameStats s = measure(t);
    // Shorter while that unclips more of the image: a minority that stays clipped at half
    // the exposure (within 0.2 % of the image) is a light source, and shorter frames would
    // only add dark, noisy ones.
    while (s.high > 0.005 && t > lim.min_ms && !Cancelled(cancel)) {
      const double shorter = camera.Quantise(std::max(t / 2, lim.min_ms));
      const FrameStats next = measure(shorter);
      if (s.high < 0.5 && s.high - next.high < 0.002) break;
      t = shorter;
      s = next;
    }
    // The darkest levels need pixels near black: shorter while under 0.2 % of the image is.
    while (s.dim < 0.002 && t > lim.min_ms && !Cancelled(cancel)) {
      t = camera.Quantise(std::max(t / 2, lim.min_ms));
      s = measure(t);
    }
    while (s.high <= 0.005 && s.mean_green < 30 && 2 * t <= lim.max_ms && !Cancelled(cancel)) {
      // Everything dark: longer, while the brightest stay unclipped.
      const FrameStats longer = measure(camera.Quantise(2 * t));
      if (longer.high > 0.005) break;
      t = camera.Quantise(2 * t);
      s = longer;
    }
    lo = t;
  }
  {
    const FrameStats s = measure(lo);
    plan.saturated_at_shortest = s.high;
    if (s.high > 0.5)
      throw CaptureProblem(FixAt::kSetup,
                           Say(words::kSaturatedAtShortest, {camera.description(), Sig(lo), Percent(s.high)}));
    if (s.high > 0.005) plan.warnings.push_back(Say(words::kPlanSaturated, {Percent(s.high), Sig(lo)}));
  }
  // Longest: 90 % of the image saturated.
  double hi = options.max_ms > 0 ? camera.Quantise(options.max_ms) : 0;
  if (hi == 0) {
    double t = lo;
    FrameStats s = measure(t);
    while (s.high < 0.9 && 2 * t <= lim.max_ms && !Cancelled(cancel)) {
      t = camera.Quantise(2 * t);
      s = measure(t);
    }
    hi = t;
  }
  {
    const FrameStats s = measure(hi);
    plan.dark_at_longest = s.low;
    if (s.low > 0.5)
      throw CaptureProblem(FixAt::kSetup,
                           Say(words::kBlackAtLongest, {camera.description(), Sig(hi), Percent(s.low)}));
  }
  if (Cancelled(cancel)) throw Error(Say(words::kPlanningCancelled));
  if (hi <= lo) hi = camera.Quantise(lo * std::pow(2.0, 4 * options.step_stops));
  // Exposures: `step` stops apart (wider when there would be too many), as the camera sets them.
  double step = options.step_stops;
  const double range_stops = std::log2(hi / lo);
  if (range_stops / step + 1 > options.max_exposures) {
    step = range_stops / (options.max_exposures - 1);
    plan.warnings.push_back(
        Say(words::kPlanStepsWidened, {Num(range_stops, 1), Num(step, 2), std::to_string(options.max_exposures)}));
  }
  const int n = int(std::ceil(range_stops / step - 1e-6)) + 1;
  for (int k = 0; k < n; ++k) {
    const double t = camera.Quantise(std::min(hi, lo * std::pow(2.0, k * step)));
    if (plan.exposures_ms.empty() || t > plan.exposures_ms.back() * 1.0001) plan.exposures_ms.push_back(t);
  }
  if (plan.exposures_ms.size() < 3)
    throw CaptureProblem(FixAt::kSetup, Say(words::kTooFewExposures, {camera.description(), Sig(lo), Sig(hi)}));
  // Preview: one frame per exposure; which levels do they cover?
  radiometry::Sweep preview;
  preview.source = camera.description() + " (preview sweep)";
  status.stage = "preview";
  status.steps = int(plan.exposures_ms.size());
  for (std::size_t k = 0; k < plan.exposures_ms.size(); ++k) {
    if (Cancelled(cancel)) throw Error(Say(words::kPlanningCancelled));
    status.step = int(k);
    status.exposure_ms = Expose(camera, plan.exposures_ms[k], options.settle_frames);
    if (progress) progress(status);
    preview.images.push_back(camera.Grab());
    preview.exposure_ms.push_back(status.exposure_ms);
  }
  plan.coverage = radiometry::MeasureLevelCoverage(preview);
  const char* ch = "RGB";
  for (int c = 0; c < 3; ++c) {
    const double share = plan.coverage.share[std::size_t(c)];
    const bool gap = plan.coverage.gap_from[std::size_t(c)] <= plan.coverage.gap_to[std::size_t(c)];
    const std::string from = std::to_string(plan.coverage.gap_from[std::size_t(c)]);
    const std::string to = std::to_string(plan.coverage.gap_to[std::size_t(c)]);
    const std::string channel(1, ch[c]);
    if (share < 0.5)
      throw CaptureProblem(
          FixAt::kSetup,
          gap ? Say(words::kCoverageTooLowGap, {camera.description(), Percent(share), channel, from, to})
              : Say(words::kCoverageTooLow, {camera.description(), Percent(share), channel}));
    if (share < 0.9)
      plan.warnings.push_back(gap ? Say(words::kPlanCoverageGap, {Percent(share), channel, from, to})
                                  : Say(words::kPlanCoverage, {Percent(share), channel}));
  }
  return plan;
}

CaptureRecord ReadCaptureRecord(const fs::path& folder) {
  const fs::path file = folder / "capture.json";
  const nlohmann::json j = ReadJsonFile(file);
  CaptureRecord r;
  try {
    r.camera = j.at("camera").get<std::string>();
    r.serial = j.at("serial").get<std::string>();
    r.plan.exposures_ms = j.at("exposures_ms").get<std::vector<double>>();
    const auto& o = j.at("options");
    r.plan.options.step_stops = o.at("step_stops").get<double>();
    r.plan.options.repeats = o.at("repeats").get<int>();
    r.plan.options.settle_frames = o.at("settle_frames").get<int>();
    r.plan.options.max_retries = o.at("max_retries").get<int>();
    r.plan.options.flicker_share = o.at("flicker_share").get<double>();
    r.steps_done = j.at("steps_done").get<int>();
    r.recaptures = j.value("recaptures", 0);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, std::string("is not a capture record: ") + e.what());
  }
  try {
    r.plan.options.Check();
  } catch (const SettingError& e) {
    throw InputError(file, e.what());
  }
  if (r.plan.exposures_ms.size() < 3 || !std::is_sorted(r.plan.exposures_ms.begin(), r.plan.exposures_ms.end()) ||
      r.plan.exposures_ms.front() <= 0)
    throw InputError(file, "'exposures_ms' must hold 3 or more positive exposures in ascending order");
  if (r.steps_done < 0 || r.steps_done > int(r.plan.exposures_ms.size()))
    throw InputError(file, "'steps_done' is outside the plan");
  return r;
}

SweepCapture::SweepCapture(SweepCamera& camera, SweepPlan plan, fs::path folder)
    : SweepCapture(camera, CaptureRecord{camera.description(), camera.serial(), std::move(plan), 0, 0},
                   std::move(folder), false) {}

SweepCapture::SweepCapture(SweepCamera& camera, CaptureRecord record, fs::path folder, bool resume)
    : camera_(camera), record_(std::move(record)), folder_(std::move(folder)), resume_(resume) {
  record_.plan.options.Check();
  if (record_.plan.exposures_ms.size() < 3) throw Error("a sweep plan needs 3 or more exposures");
}

SweepCapture SweepCapture::Resume(SweepCamera& camera, const fs::path& folder) {
  CaptureRecord r = ReadCaptureRecord(folder);
  if (r.serial != camera.serial())
    throw InputError(folder / "capture.json",
                     "was captured from " + r.camera + " (serial " + r.serial + "), not from " + camera.description() +
                         " (serial " + camera.serial() + "); resume with the same camera, or start a new sweep");
  return SweepCapture(camera, std::move(r), folder, true);
}

CaptureResult SweepCapture::Run(const CaptureProgress& progress, const std::atomic<bool>* cancel) {
  const SweepPlanOptions& o = record_.plan.options;
  const auto& exposures = record_.plan.exposures_ms;
  VerifyManualExposure(camera_);
  SequenceWriter::Options wo;
  wo.write_groundtruth = false;
  wo.write_depth = false;
  std::optional<SequenceWriter> writer;
  if (resume_) {
    writer.emplace(SequenceWriter::Reopen(folder_, wo, std::size_t(record_.steps_done) * std::size_t(o.repeats)));
  } else {
    writer.emplace(folder_, camera_.sensor(), wo);  // refuses a folder that is not empty
    WriteRecord(folder_, record_);
    resume_ = true;  // a second Run goes on from here
  }
  CaptureResult result;
  result.steps = int(exposures.size());
  result.recaptures = record_.recaptures;
  CaptureStatus status;
  status.stage = "capture";
  status.steps = result.steps;
  status.recaptures = record_.recaptures;
  // The step before, for the motion check across exposures: on resume, the last frame written.
  std::optional<ColorImage> previous;
  if (writer->size() > 0) {  // (Reopen has cut the lists to the complete steps)
    SequenceReadOptions ro;
    ro.allow_missing_depth = true;
    previous = ReadColorImage(SequenceReader(folder_, ro).frames()[writer->size() - 1].color_path);
  }
  std::optional<ColorImage> reference;
  double reference_midtones = -1;
  if (previous) {
    reference = previous->Clone();
    reference_midtones = MidTones(*reference);
  }
  double t_next = writer->size() > 0 ? double(writer->size()) / 30.0 : 0.0;
  for (int k = record_.steps_done; k < result.steps; ++k) {
    status.step = k;
    std::string failure;
    std::vector<ColorImage> frames;
    double actual = 0;
    for (int attempt = 0; attempt <= o.max_retries; ++attempt) {
      if (Cancelled(cancel)) break;
      if (attempt > 0) {
        ++record_.recaptures;
        status.recaptures = record_.recaptures;
        status.note = Say(words::kRecapturing, {Sig(exposures[std::size_t(k)]), failure});
      }
      actual = Expose(camera_, exposures[std::size_t(k)], o.settle_frames);
      status.exposure_ms = actual;
      if (progress) progress(status);
      frames.clear();
      for (int r = 0; r < o.repeats && !Cancelled(cancel); ++r) frames.push_back(camera_.Grab());
      if (Cancelled(cancel)) break;
      failure.clear();
      for (std::size_t r = 1; r < frames.size() && failure.empty(); ++r) {
        const radiometry::OrderChange m = radiometry::CompareBrightnessOrder(frames[0], frames[r]);
        if (m.moved()) failure = Say(words::kMovedBetweenRepeats, {Percent(m.share)});
        const double d = MeanChange(frames[0], frames[r]);
        if (failure.empty() && d > o.flicker_share)
          failure = Say(words::kFlicker, {Percent(d)});
      }
      // Against the step before, and against the best-exposed step so far (a move during
      // dark steps, where few regions can be compared, is caught once the light returns).
      for (const ColorImage* before : {previous ? &*previous : nullptr, reference ? &*reference : nullptr}) {
        if (!failure.empty() || !before) continue;
        const radiometry::OrderChange m = radiometry::CompareBrightnessOrder(*before, frames[0]);
        if (m.moved())
          failure = Say(words::kMovedSinceBefore, {Percent(m.share)});
      }
      if (failure.empty()) break;
    }
    if (Cancelled(cancel)) {
      result.cancelled = true;
      break;
    }
    if (!failure.empty()) {
      WriteRecord(folder_, record_);
      const std::optional<ParsedMessage> what = ParseMessage(failure);
      const Wording* kind = what ? what->wording : nullptr;
      const Wording& advice = kind == &words::kFlicker            ? words::kAdviceFlicker
                              : kind == &words::kMovedSinceBefore ? words::kAdviceMovedAcross
                                                                  : words::kAdviceKeepStill;
      throw CaptureProblem(FixAt::kCapture,
                           Say(words::kCaptureFailed,
                               {Sig(exposures[std::size_t(k)]), std::to_string(k + 1), std::to_string(result.steps),
                                failure, std::to_string(o.max_retries + 1), Say(advice), std::to_string(k),
                                folder_.string()}));
    }
    for (const ColorImage& f : frames) {
      writer->Add(t_next, f, nullptr, actual, std::nullopt, nullptr);
      t_next += 1.0 / 30.0;
    }
    previous = frames.back().Clone();
    if (const double m = MidTones(frames.back()); m > reference_midtones) {
      reference = frames.back().Clone();
      reference_midtones = m;
    }
    record_.steps_done = k + 1;
    if (std::abs(actual - exposures[std::size_t(k)]) > 1e-9 * actual) record_.plan.exposures_ms[std::size_t(k)] = actual;
    WriteRecord(folder_, record_);
    status.frames_written = int(writer->size());
    status.note.clear();
    status.frame = std::make_shared<const ColorImage>(frames.back().Clone());
    if (progress) progress(status);
    status.frame.reset();
  }
  result.steps_done = record_.steps_done;
  result.frames = int(writer->size());
  result.recaptures = record_.recaptures;
  return result;
}

}  // namespace hdrf::io
