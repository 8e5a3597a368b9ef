#include "pipeline/settings.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <type_traits>

#include "common/error.h"

namespace hdrf::pipeline {

void PipelineOptions::Check() const {
  volume.Check();
  tracker.Check();
  reloc.Check();
  exposure.Check();
  nr.Check();
  depth.Check();
  if (pcf < 0 || pcf > 3) throw SettingError("pcf", "must be 0, 1, 2 or 3 (p0..p3)");
}

namespace {

// The shortest text that reads back as the same value of its own type (0.1f is "0.1").
template <typename T>
std::string FormatNumber(T v) {
  char b[64];
  const auto r = std::to_chars(b, b + sizeof b, v);
  return std::string(b, r.ptr);
}

// The whole of `text` as a finite number; throws naming the key otherwise.
double ParseNumber(const std::string& key, const std::string& text) {
  const char* s = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s, &end);
  if (text.empty() || end == s || *end != '\0' || errno == ERANGE || !std::isfinite(v))
    throw SettingError(key, "'" + text + "' is not a number");
  return v;
}

void CheckRange(const Setting& s, double v) {
  if (v < s.min || v > s.max)
    throw SettingError(s.key, FormatNumber(v) + " is out of range (" + s.Range() + ")");
}

double ParseChecked(const Setting& s, const std::string& text, bool whole) {
  const double v = ParseNumber(s.key, text);
  if (whole && v != std::floor(v))
    throw SettingError(s.key, "'" + text + "' is not a whole number");
  CheckRange(s, v);
  return v;
}

// A numeric or boolean field reached through `field(options)`.
template <typename Field>
Setting Bind(std::string key, SettingKind kind, double lo, double hi, std::string unit,
             std::string help, Field field) {
  Setting s;
  s.key = std::move(key);
  s.kind = kind;
  s.min = lo;
  s.max = hi;
  s.unit = std::move(unit);
  s.help = std::move(help);
  s.get = [field](const PipelineOptions& o) {
    const auto v = field(const_cast<PipelineOptions&>(o));
    if constexpr (std::is_same_v<std::decay_t<decltype(v)>, bool>)
      return std::string(v ? "true" : "false");
    else
      return FormatNumber(v);
  };
  s.set = [field, kind, self = s](PipelineOptions& o, const std::string& text) {
    auto& f = field(o);
    using T = std::decay_t<decltype(f)>;
    if constexpr (std::is_same_v<T, bool>) {
      if (text == "true" || text == "1" || text == "on")
        f = true;
      else if (text == "false" || text == "0" || text == "off")
        f = false;
      else
        throw SettingError(self.key, "'" + text + "' is not true or false");
    } else {
      f = T(ParseChecked(self, text, kind == SettingKind::kInt));
    }
  };
  return s;
}

#define HDRF_FIELD(expr) \
  [](PipelineOptions & o) -> auto& { return o.expr; }

Setting Real(std::string key, double lo, double hi, std::string unit, std::string help,
             auto field) {
  return Bind(std::move(key), SettingKind::kReal, lo, hi, std::move(unit), std::move(help), field);
}
Setting Int(std::string key, double lo, double hi, std::string unit, std::string help, auto field) {
  return Bind(std::move(key), SettingKind::kInt, lo, hi, std::move(unit), std::move(help), field);
}
Setting Bool(std::string key, std::string help, auto field) {
  return Bind(std::move(key), SettingKind::kBool, 0, 1, "", std::move(help), field);
}

Setting Choice(std::string key, std::vector<std::string> choices, std::string help,
               std::function<std::string(const PipelineOptions&)> get,
               std::function<void(PipelineOptions&, const std::string&)> parse) {
  Setting s;
  s.key = std::move(key);
  s.kind = SettingKind::kChoice;
  s.choices = std::move(choices);
  s.help = std::move(help);
  s.get = std::move(get);
  s.set = [parse, self = s](PipelineOptions& o, const std::string& text) {
    bool known = false;
    for (const auto& c : self.choices) known |= c == text;
    if (!known) throw SettingError(self.key, "'" + text + "' is not " + self.Range());
    parse(o, text);
  };
  return s;
}

Setting Expert(Setting s) {
  s.expert = true;
  return s;
}
Setting Alias(Setting s, std::string alias) {
  s.alias = std::move(alias);
  return s;
}

// The plain-words label of every setting and when an operator would change it; shown in the
// studio's form and its tooltips.
struct Words {
  const char* key;
  const char* label;
  const char* advice;
};
constexpr Words kWords[] = {
    {"device", "Run on", "Keep cuda where a GPU answers; cpu to compare with the reference or when the GPU is busy"},
    {"pcf", "Pixel confidence", "Keep p1; p0 trusts every pixel alike, p2 and p3 trust mid-tones more"},
    {"volume.voxel_m", "Voxel size", "Smaller for small objects and sharper colour (memory grows about 4x per halving); larger for big rooms"},
    {"volume.voxel", "Voxel storage", "compact for scanning; full only to inspect the normalized radiance stored in the model"},
    {"volume.truncation_voxels", "Surface band", "Wider for noisy depth, narrower to keep thin objects apart"},
    {"volume.max_weight", "Geometry memory", "Lower so that moving objects fade from the model sooner"},
    {"volume.max_radiance_weight", "Colour memory", "Lower so that colour follows changing light sooner"},
    {"volume.tau0", "Colour confidence threshold", "Raise to keep dark or clipped pixels out of the colour"},
    {"volume.tau1_deg", "Colour viewing angle limit", "Lower to take colour only from views that face the surface"},
    {"volume.max_memory_mb", "Model memory limit", "Raise for large rooms when the volume reports it is full"},
    {"volume.gpu_memory_mb", "GPU memory limit", "Set on a GPU with little memory; 0 lets the model use the GPU alone"},
    {"volume.raycast_near_m", "Nearest model distance", "Lower when scanning objects closer than it"},
    {"volume.raycast_far_m", "Farthest model distance", "Raise when tracking should use surfaces farther away (large halls)"},
    {"tracker.kind", "Tracking method", "Keep nr+icp; icp alone for scenes without texture, intensity only to compare"},
    {"tracker.frame_to_model", "Track against the model", "Turn off only to compare with frame-to-frame tracking"},
    {"tracker.levels", "Image pyramid levels", "More for fast motion, fewer for small images"},
    {"tracker.iterations", "Iterations per level", "More when tracking is lost on fast motion; fewer for speed"},
    {"tracker.icp_sigma_m", "Depth residual scale", "Raise for noisy depth sensors"},
    {"tracker.photo_sigma", "Colour residual scale", "Raise for noisy colour"},
    {"tracker.adaptive_scales", "Measure residual scales", "Keep on; off to use the fixed scales above"},
    {"tracker.photo_agreement", "Weigh colour by its fit", "Turn on when colour and depth are not registered (an uncalibrated camera)"},
    {"tracker.depth_noise_scaling", "Depth noise grows with distance", "Turn on for real structured-light or stereo cameras (a Kinect)"},
    {"tracker.icp_sigma_floor_m", "Least depth residual scale", "Raise when very clean depth makes tracking overconfident"},
    {"tracker.photo_sigma_floor", "Least colour residual scale", "Raise when very clean colour makes tracking overconfident"},
    {"tracker.huber_k", "Outlier threshold", "Lower when moving objects disturb tracking"},
    {"tracker.icp_max_dist_m", "Largest point match distance", "Raise for fast motion, lower for clutter"},
    {"tracker.icp_max_angle_deg", "Largest normal difference", "Raise for noisy normals"},
    {"tracker.min_inlier_share", "Least matched share", "Lower for scenes with little overlap between frames; raise to refuse doubtful frames"},
    {"tracker.max_condition", "Worst conditioning", "Lower to refuse frames of flat walls that cannot fix every direction"},
    {"tracker.weak_info_floor", "Weak-direction hold", "Raise if poses slide along flat walls; lower if smooth but quick moves are tracked late"},
    {"tracker.max_jump_m", "Largest jump", "Raise for a fast hand-held camera"},
    {"tracker.max_jump_deg", "Largest turn", "Raise for a fast turning camera"},
    {"tracker.max_speed_mps", "Largest speed", "Raise for a camera swung or carried faster than this"},
    {"tracker.verify_growth", "Residual growth limit", "Raise when good frames are refused after a change of scene"},
    {"tracker.verify_floor_m", "Always-good depth residual", "Raise for noisy depth when good frames are refused"},
    {"tracker.verify_floor_photo", "Always-good colour residual", "Raise for noisy colour when good frames are refused"},
    {"tracker.min_robust_inliers", "Least robust weight", "Lower when good frames are refused in clutter"},
    {"tracker.max_exposure_drift", "Exposure disagreement limit", "Raise for a camera whose reported exposure is unreliable"},
    {"tracker.confirm_frames", "Frames to confirm", "More to be surer after a loss, fewer to resume sooner"},
    {"tracker.min_anchor_depth", "Depth needed to start", "Lower for scenes mostly out of the depth range"},
    {"reloc.enabled", "Relocalise when lost", "Keep on; off only to study losses"},
    {"reloc.candidates", "Views tried when lost", "More to find the place sooner, at more time per lost frame"},
    {"reloc.min_translation_m", "Keyframe spacing", "Lower to keep more views for relocalisation (more memory)"},
    {"reloc.min_rotation_deg", "Keyframe angle", "Lower to keep more views for relocalisation (more memory)"},
    {"exposure.stride", "Exposure sample spacing", "Lower for small images, higher for speed"},
    {"exposure.min_samples", "Least exposure samples", "Lower for small images"},
    {"nr.patch", "Patch size", "Larger for noisy colour, smaller for fine texture"},
    {"nr.downsample", "Patch statistics scale", "Keep 2; 1 for small images"},
    {"nr.min_std", "Least local contrast", "Raise when noise in flat areas disturbs tracking"},
    {"depth.bilateral", "Smooth depth", "Keep on; off for clean synthetic depth"},
    {"depth.sigma_space_px", "Smoothing width", "Larger for noisy depth"},
    {"depth.sigma_depth_m", "Smoothing depth range", "Larger for noisy depth, smaller to keep edges"},
    {"depth.radius", "Smoothing window", "Larger with a larger smoothing width"},
    {"depth.max_normal_jump_m", "Depth edge threshold", "Raise for noisy depth at a distance"},
};

std::vector<Setting> MakeSettings() {
  constexpr double kBig = 1e12;
  std::vector<Setting> v;
  // The engine as a whole.
  v.push_back(Choice(
      "device", {"cpu", "cuda"}, "Where the engine runs (cuda: the GPU where one is usable)",
      [](const PipelineOptions& o) { return std::string(DeviceName(o.device)); },
      [](PipelineOptions& o, const std::string& t) {
        o.device = t == "cuda" ? Device::kCuda : Device::kCpu;
      }));
  v.push_back(Int("pcf", 0, 3, "",
                  "Pixel confidence p0..p3 used for tracking and fusion (p1: square root)",
                  HDRF_FIELD(pcf)));
  // Volume.
  v.push_back(Alias(Real("volume.voxel_m", 1e-3, 1, "m",
                         "Voxel side; the volume has no fixed extent, its memory follows the surface seen",
                         HDRF_FIELD(volume.voxel_m)),
                    "--voxel-size"));
  v.push_back(Alias(Choice(
                        "volume.voxel", {"compact", "no-nr", "full"},
                        "Voxel storage: compact (12 B), no-nr (24 B) or full (28 B)",
                        [](const PipelineOptions& o) {
                          return std::string(volume::VoxelEncodingName(o.volume.encoding));
                        },
                        [](PipelineOptions& o, const std::string& t) {
                          o.volume.encoding = volume::ParseVoxelEncoding(t);
                        }),
                    "--voxel"));
  v.push_back(Expert(Real("volume.truncation_voxels", 1, 64, "voxels", "TSDF truncation distance",
                          HDRF_FIELD(volume.truncation_voxels))));
  v.push_back(
      Expert(Real("volume.max_weight", 1e-3, 1e6, "",
                  "Cap of the TSDF weight (running-mean window)", HDRF_FIELD(volume.max_weight))));
  v.push_back(Expert(Real("volume.max_radiance_weight", 1e-3, 1e6, "", "Cap of the radiance weight",
                          HDRF_FIELD(volume.max_radiance_weight))));
  v.push_back(Alias(Real("volume.tau0", 0, 0.999, "",
                         "Radiance is fused only where the largest channel PCF exceeds this",
                         HDRF_FIELD(volume.tau0)),
                    "--tau0"));
  v.push_back(
      Alias(Real("volume.tau1_deg", 1e-3, 90, "deg",
                 "Radiance is fused only where the angle between normal and view ray is below this",
                 HDRF_FIELD(volume.tau1_deg)),
            "--tau1"));
  v.push_back(Real("volume.max_memory_mb", 1, 1 << 24, "MiB", "Voxel memory the whole model may use",
                   HDRF_FIELD(volume.max_memory_mb)));
  v.push_back(Real("volume.gpu_memory_mb", 0, 1 << 24, "MiB",
                   "GPU only: voxel memory on the GPU; beyond it, bricks out of view move to host memory and back "
                   "when seen again (0: no GPU budget; 4 MiB at least)",
                   HDRF_FIELD(volume.gpu_memory_mb)));
  v.push_back(Expert(Real("volume.raycast_near_m", 1e-3, 100, "m",
                          "Ray casting starts this far from the camera",
                          HDRF_FIELD(volume.raycast_near_m))));
  v.push_back(Expert(Real("volume.raycast_far_m", 1e-2, 1000, "m",
                          "Ray casting gives up this far from the camera",
                          HDRF_FIELD(volume.raycast_far_m))));
  // Tracking.
  v.push_back(Alias(
      Choice(
          "tracker.kind", {"nr+icp", "nr", "icp", "intensity"},
          "nr+icp, nr (normalized radiance), icp, or intensity (the brightness-constancy baseline)",
          [](const PipelineOptions& o) {
            return std::string(tracking::TrackerName(o.tracker.kind));
          },
          [](PipelineOptions& o, const std::string& t) {
            o.tracker.kind = tracking::ParseTrackerKind(t);
          }),
      "--tracker"));
  v.push_back(Bool("tracker.frame_to_model",
                   "Track against the model (false: against the previous frame)",
                   HDRF_FIELD(tracker.frame_to_model)));
  v.push_back(Expert(Int("tracker.levels", 1, 4, "", "Pyramid levels, each half the size",
                         HDRF_FIELD(tracker.levels))));
  {
    Setting it;
    it.key = "tracker.iterations";
    it.kind = SettingKind::kIntList;
    it.min = 0;
    it.max = 100;
    it.max_items = 4;
    it.help = "Gauss-Newton iterations per level, coarsest first";
    it.expert = true;
    it.get = [](const PipelineOptions& o) {
      std::string t;
      for (int i = 0; i < 4; ++i) {
        if (i) t += ',';
        t += std::to_string(o.tracker.iterations[std::size_t(i)]);
      }
      return t;
    };
    it.set = [self = it](PipelineOptions& o, const std::string& text) {
      std::vector<std::string> parts;
      std::size_t start = 0;
      for (std::size_t k = 0; k <= text.size(); ++k)
        if (k == text.size() || text[k] == ',')
          parts.push_back(text.substr(start, k - start)), start = k + 1;
      if (text.empty() || parts.size() > 4)
        throw SettingError(self.key, "needs 1 to 4 whole numbers");
      for (std::size_t i = 0; i < parts.size(); ++i)
        o.tracker.iterations[i] = int(ParseChecked(self, parts[i], true));
    };
    v.push_back(it);
  }
  v.push_back(Expert(Real("tracker.icp_sigma_m", 1e-6, 10, "m",
                          "Expected scale of the point-to-plane residual",
                          HDRF_FIELD(tracker.icp_sigma_m))));
  v.push_back(Expert(Real("tracker.photo_sigma", 1e-6, 100, "",
                          "Expected scale of the normalized-radiance residual",
                          HDRF_FIELD(tracker.photo_sigma))));
  v.push_back(Bool("tracker.adaptive_scales",
                   "Weigh the tracker's terms by their measured residuals (after a few frames) instead of the scales above",
                   HDRF_FIELD(tracker.adaptive_scales)));
  v.push_back(Bool("tracker.photo_agreement",
                   "nr+icp: cut the photometric term's share where it pulls the pose off the depth's own optimum",
                   HDRF_FIELD(tracker.photo_agreement)));
  v.push_back(Bool("tracker.depth_noise_scaling",
                   "Scale each point-to-plane residual with its depth squared, as a structured-light or stereo sensor's noise grows",
                   HDRF_FIELD(tracker.depth_noise_scaling)));
  v.push_back(Expert(Real("tracker.icp_sigma_floor_m", 1e-6, 10, "m",
                          "Smallest point-to-plane scale the measured scales may take",
                          HDRF_FIELD(tracker.icp_sigma_floor_m))));
  v.push_back(Expert(Real("tracker.photo_sigma_floor", 1e-6, 100, "",
                          "Smallest normalized-radiance scale the measured scales may take",
                          HDRF_FIELD(tracker.photo_sigma_floor))));
  v.push_back(
      Expert(Real("tracker.huber_k", 1e-3, 100, "", "Huber threshold, in units of the scales above",
                  HDRF_FIELD(tracker.huber_k))));
  v.push_back(
      Expert(Real("tracker.icp_max_dist_m", 1e-4, 10, "m",
                  "ICP pairs farther apart are not matched", HDRF_FIELD(tracker.icp_max_dist_m))));
  v.push_back(Expert(Real("tracker.icp_max_angle_deg", 1e-3, 90, "deg",
                          "ICP pairs whose normals differ more are not matched",
                          HDRF_FIELD(tracker.icp_max_angle_deg))));
  v.push_back(Real("tracker.min_inlier_share", 0, 1, "",
                   "A frame matching fewer of its pixels than this is lost",
                   HDRF_FIELD(tracker.min_inlier_share)));
  v.push_back(Expert(Real("tracker.max_condition", 1.0001, kBig, "",
                          "A frame whose system is worse conditioned is lost",
                          HDRF_FIELD(tracker.max_condition))));
  v.push_back(Expert(Real("tracker.weak_info_floor", 0, 0.999, "",
                          "Along directions the pixels fix less than this share of the best-fixed one, the "
                          "motion prediction holds the pose (0: off)",
                          HDRF_FIELD(tracker.weak_info_floor))));
  v.push_back(Real("tracker.max_jump_m", 1e-4, 100, "m",
                   "A frame moving farther from its prediction is lost",
                   HDRF_FIELD(tracker.max_jump_m)));
  v.push_back(Real("tracker.max_jump_deg", 1e-3, 180, "deg",
                   "A frame turning farther from its prediction is lost",
                   HDRF_FIELD(tracker.max_jump_deg)));
  v.push_back(Real("tracker.max_speed_mps", 0.01, 100, "m/s",
                   "A pose implying a faster camera since the last accepted one is not fused",
                   HDRF_FIELD(tracker.max_speed_mps)));
  v.push_back(Expert(Real("tracker.verify_growth", 1, 1000, "",
                          "A pose whose residual exceeds this many times the scan's recent median is not fused",
                          HDRF_FIELD(tracker.verify_growth))));
  v.push_back(Expert(Real("tracker.verify_floor_m", 0, 1, "m",
                          "Point-to-surface residuals below this always verify",
                          HDRF_FIELD(tracker.verify_floor_m))));
  v.push_back(Expert(Real("tracker.verify_floor_photo", 0, 10, "",
                          "Normalized-radiance residuals below this always verify (no ICP)",
                          HDRF_FIELD(tracker.verify_floor_photo))));
  v.push_back(Expert(Real("tracker.min_robust_inliers", 0, 1, "",
                          "A pose whose terms' mean robust weight is lower is not fused",
                          HDRF_FIELD(tracker.min_robust_inliers))));
  v.push_back(Expert(Real("tracker.max_exposure_drift", 1e-3, 100, "",
                          "A pose whose exposure estimate departs more from the sensor's (relative) is not fused",
                          HDRF_FIELD(tracker.max_exposure_drift))));
  v.push_back(Int("tracker.confirm_frames", 1, 1000, "frames",
                  "After a loss, frames that must verify in a row before fusion resumes",
                  HDRF_FIELD(tracker.confirm_frames)));
  v.push_back(Real("tracker.min_anchor_depth", 0, 1, "",
                   "The first frame with this share of pixels with depth anchors the model",
                   HDRF_FIELD(tracker.min_anchor_depth)));
  v.push_back(Bool("reloc.enabled", "When lost, look for the pose among the scan's earlier views",
                   HDRF_FIELD(reloc.enabled)));
  v.push_back(Expert(Int("reloc.candidates", 1, 32, "", "Earlier views tried per lost frame",
                         HDRF_FIELD(reloc.candidates))));
  v.push_back(Expert(Real("reloc.min_translation_m", 1e-3, 100, "m",
                          "A view is kept for relocalisation after this much motion", HDRF_FIELD(reloc.min_translation_m))));
  v.push_back(Expert(Real("reloc.min_rotation_deg", 1e-3, 180, "deg",
                          "A view is kept for relocalisation after this much turning", HDRF_FIELD(reloc.min_rotation_deg))));
  // Exposure compensation.
  v.push_back(Expert(Int("exposure.stride", 1, 16, "px",
                         "Every stride-th pixel in x and y is an exposure sample",
                         HDRF_FIELD(exposure.stride))));
  v.push_back(Expert(Int("exposure.min_samples", 1, 1e9, "",
                         "Fewer matched samples: the exposure ratio stays 1",
                         HDRF_FIELD(exposure.min_samples))));
  // Normalized radiance.
  v.push_back(Int("nr.patch", 3, 255, "px",
                  "Side of the local patch, in pixels of the down-sampled image (odd)",
                  HDRF_FIELD(nr.patch)));
  v.push_back(Expert(Int("nr.downsample", 1, 8, "",
                         "Local statistics on an image down-sampled by this factor",
                         HDRF_FIELD(nr.downsample))));
  v.push_back(
      Expert(Real("nr.min_std", 1e-9, 1, "", "Floor on the local std, relative to the local mean",
                  HDRF_FIELD(nr.min_std))));
  // Depth.
  v.push_back(Bool("depth.bilateral", "Edge-preserving bilateral filter of the depth",
                   HDRF_FIELD(depth.bilateral)));
  v.push_back(Expert(Real("depth.sigma_space_px", 1e-3, 100, "px",
                          "Bilateral filter: spatial sigma", HDRF_FIELD(depth.sigma_space_px))));
  v.push_back(Expert(Real("depth.sigma_depth_m", 1e-6, 10, "m", "Bilateral filter: range sigma",
                          HDRF_FIELD(depth.sigma_depth_m))));
  v.push_back(Expert(Int("depth.radius", 1, imaging::kBilateralMaxRadius, "px",
                         "Bilateral filter: window radius", HDRF_FIELD(depth.radius))));
  v.push_back(Expert(Real("depth.max_normal_jump_m", 1e-4, 10, "m",
                          "Normals are undefined across larger depth jumps",
                          HDRF_FIELD(depth.max_normal_jump_m))));
  for (Setting& s : v)
    for (const Words& w : kWords)
      if (s.key == w.key) s.label = w.label, s.advice = w.advice;
  return v;
}

#undef HDRF_FIELD

}  // namespace

std::string Setting::Range() const {
  auto number = [](double v) { return FormatNumber(v); };
  switch (kind) {
    case SettingKind::kBool:
      return "true or false";
    case SettingKind::kChoice: {
      std::string t = "one of ";
      for (std::size_t i = 0; i < choices.size(); ++i) t += (i ? ", " : "") + choices[i];
      return t;
    }
    case SettingKind::kIntList:
      return "1 to " + std::to_string(max_items) + " whole numbers, each " + number(min) + " .. " +
             number(max);
    default:
      return number(min) + " .. " + number(max) + (unit.empty() ? "" : " " + unit);
  }
}

const std::vector<Setting>& Settings() {
  static const std::vector<Setting> settings = MakeSettings();
  return settings;
}

std::string RetiredSetting(const std::string& key) {
  const std::string k = key.rfind("--", 0) == 0 ? key.substr(2) : key;
  if (k == "volume.resolution" || k == "volume.size_m" || k == "volume-res" || k == "volume-size")
    return "was removed: the volume has no fixed extent now; set its voxel size with volume.voxel_m (metres)";
  return "";
}

const Setting& FindSetting(const std::string& key) {
  for (const Setting& s : Settings())
    if (s.key == key) return s;
  if (const std::string why = RetiredSetting(key); !why.empty()) throw SettingError(key, why);
  throw SettingError(key, "unknown setting (hdrfusion settings lists them)");
}

}  // namespace hdrf::pipeline
