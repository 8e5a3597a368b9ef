// `hdrfusion-experiments tracking`: the paper's tracking experiment. The synthetic room
// (ICL-NUIM-like trajectory) is written as a sequence for each auto-exposure mode (flicker,
// smooth); every tracker of ExperimentTrackers runs on the frames read back from it,
// and the peers (hdrfusion-peers: OpenCV rgbd, Open3D) run on the same folder in the same
// run. Writes per-frame error plots, tracking.md and tracking.json.
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "experiments.h"
#include "cli/plot.h"
#include "cli/progress.h"
#include "eval/eval.h"
#include "common/error.h"
#include "tracking_experiment.h"
#include "io/image_io.h"
#include "io/json_file.h"
#include "io/ply.h"
#include "io/sequence.h"
#include "io/source_spec.h"
#include "io/output_file.h"
#include "io/tum.h"
#include "sim/synthetic_source.h"

namespace hdrf::experiments {

using cli::Progress;

using cli::Plot;

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const Rgb8 kPalette[] = {{220, 30, 30},  {240, 140, 0},  {160, 90, 40},  {150, 60, 200}, {30, 150, 50}, {40, 90, 220},
                         {0, 0, 0},      {120, 120, 120}, {0, 170, 170},  {230, 90, 170}, {150, 150, 0}, {90, 60, 120}};

std::string Hex(Rgb8 c) {
  char b[16];
  std::snprintf(b, sizeof b, "#%02x%02x%02x", c.r, c.g, c.b);
  return b;
}

// A folder under the system's temporary directory, removed with everything in it when this
// goes out of scope; none when `prefix` is empty.
class TemporaryFolder {
 public:
  explicit TemporaryFolder(const std::string& prefix) {
    if (prefix.empty()) return;
    path_ = fs::temp_directory_path() / (prefix + "-" + std::to_string(::getpid()));
    fs::create_directories(path_);
  }
  ~TemporaryFolder() {
    std::error_code ec;
    if (!path_.empty()) fs::remove_all(path_, ec);
  }
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};


struct Row {
  std::string id, label, kind;  // kind: "ours", "baseline", "peer"
  std::vector<Pose> poses;
  int lost = 0;
  double seconds = 0;
  std::string covers;
  eval::TrajectoryError err;
  PerFrameError per_frame;
};

}  // namespace

std::string ShellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

PeerResult ReadPeerResult(const json& e, const fs::path& dir, std::size_t frames) {
  PeerResult r;
  r.id = e.at("id").get<std::string>();
  r.label = e.at("label").get<std::string>();
  if (e.contains("unavailable")) {
    r.unavailable = e.at("unavailable").get<std::string>();
    return r;
  }
  for (const auto& tp : io::ReadTrajectory(dir / (r.id + ".txt"))) r.poses.push_back(tp.T_world_camera);
  if (r.poses.size() != frames)
    throw InputError((dir / (r.id + ".txt")).string(), "has " + std::to_string(r.poses.size()) + " poses for " +
                                                           std::to_string(frames) + " frames");
  r.failed = e.at("failed").get<int>();
  r.seconds = e.at("seconds").get<double>();
  return r;
}

void CheckTrackingArgs(const TrackingExperimentArgs& a) {
  if (a.out.empty()) throw SettingError("--out", "names the results folder and is required");
  if (!a.peers_program.empty() && !fs::exists(a.peers_program))
    throw SettingError("--peers", "'" + a.peers_program + "' does not exist (hdrfusion-peers is built where "
                                  "tools/install_deps.sh --peers installed OpenCV contrib and Open3D)");
}

int RunTrackingExperiment(const TrackingExperimentArgs& a) {
  CheckTrackingArgs(a);  // before anything is written
  const fs::path peers = a.peers_program;
  const fs::path out = a.out;
  fs::create_directories(out);
  // The sequences everyone reads: where asked (kept), else a temporary folder removed after.
  TemporaryFolder scratch(a.work.empty() ? "hdrfusion-tracking" : "");
  const fs::path work = a.work.empty() ? scratch.path() : fs::path(a.work);
  if (peers.empty())
    std::fprintf(stderr, "tracking: peers not run (--peers names the hdrfusion-peers program to run them)\n");
  json all = json::object();
  std::string md =
      "# Tracking under auto exposure (`hdrfusion-experiments tracking`)\n\n"
      "The paper's tracking experiment on the synthetic sensor: scene `room` (an ICL-NUIM-like room and "
      "hand-held trajectory), " + std::to_string(a.frames) + " frames at " + a.size +
      ", the real Xtion response, Kinect-like depth noise. Every tracker below reads the same sequence "
      "folder (colour as delivered, depth, intrinsics; ours also the calibrated response in sensor.json). "
      "ATE: RMSE of the camera positions after a rigid alignment to the truth; RPE: RMSE of the "
      "frame-to-frame relative motion error. 'first failure': the first frame whose own motion is wrong by more "
      "than 2 cm or 2 degrees. 'lost': frames the tracker itself reported failed (ours keep "
      "the last pose and do not fuse; peers keep the constant-velocity prediction). Wall time is measured in "
      "this run on this machine; 'covers' says what it includes.\n\n";
  const auto trackers = ExperimentTrackers();
  for (const std::string& ae : a.ae_modes) {
    // 1. The sequence, written once and read back: everyone gets identical inputs.
    const fs::path seq_dir = work / ("room-" + ae);
    fs::remove_all(seq_dir);
    sim::SimOptions so;
    so.frames = a.frames;
    io::ParseSize(a.size, &so.width, &so.height);
    so.ae.mode = sim::ParseAeMode(ae);
    {
      sim::SyntheticSource src(so);
      io::SequenceWriter writer(seq_dir, src.sensor());
      Progress p("tracking: writing " + seq_dir.string(), src.size());
      while (!src.done()) {
        const sim::SimFrame f = src.Next();
        writer.Add(f.timestamp, f.color, &f.depth, f.exposure_ms, f.T_world_camera, nullptr);
        p.Step();
      }
      p.Done();
    }
    auto source = io::OpenSource(seq_dir.string(), "");
    const SensorInfo sensor = source->sensor();
    std::vector<pipeline::FrameInput> frames;
    {
      Progress p("tracking: reading " + seq_dir.string(), source->size());
      pipeline::FrameInput f;
      while (source->Next(f)) {
        frames.push_back(std::move(f));
        p.Step();
      }
      p.Done();
    }
    std::vector<Pose> truth;
    const Pose T0inv = frames.at(0).T_world_camera_true.value().inverse();
    for (const auto& f : frames) truth.push_back(T0inv * f.T_world_camera_true.value());
    // 2. Our trackers and the baselines.
    std::vector<Row> rows;
    // Engine defaults (compact voxels, CPU, the unbounded volume holds the whole room).
    pipeline::PipelineOptions engine;
    for (std::size_t t = 0; t < trackers.size(); ++t) {
      const auto& spec = trackers[t];
      Progress p("tracking: " + ae + " " + std::to_string(t + 1) + "/" + std::to_string(trackers.size()) + " " +
                     spec.id,
                 int(frames.size()));
      const TrackerRun run = RunTracker(spec, frames, sensor.camera, sensor, engine, [&](int) { p.Step(); });
      p.Done();
      Row r;
      r.id = spec.id;
      r.label = spec.label;
      r.kind = spec.baseline || spec.kind == tracking::TrackerKind::kIntensity ? "baseline" : "ours";
      r.poses = run.poses;
      r.lost = run.lost;
      r.seconds = run.seconds;
      r.covers = spec.baseline ? "tracking" : "whole engine: tracking, fusion, ray casting";
      rows.push_back(std::move(r));
    }
    // 3. The peers, on the same folder, now.
    std::string geometry;
    json geometry_j;
    if (!peers.empty()) {
      const fs::path pout = work / ("peers-" + ae);
      fs::remove_all(pout);
      const std::string cmd = ShellQuote(peers.string()) + " " + ShellQuote(seq_dir.string()) + " --out " +
                              ShellQuote(pout.string());
      std::fprintf(stderr, "tracking: %s peers: %s\n", ae.c_str(), cmd.c_str());
      const int rc = std::system(cmd.c_str());
      if (rc != 0) {
        // The shell reports a killed child as exit status 128 + signal.
        const int sig = WIFSIGNALED(rc) ? WTERMSIG(rc) : (WEXITSTATUS(rc) > 128 ? WEXITSTATUS(rc) - 128 : 0);
        const std::string how = sig ? "killed by signal " + std::to_string(sig) + (sig == SIGKILL ? " (out of memory?)" : "")
                                    : "exit status " + std::to_string(WEXITSTATUS(rc));
        // Our own results stand: the table reports the failure instead of the peers.
        std::fprintf(stderr, "tracking: hdrfusion-peers failed (%s): %s\n", how.c_str(), cmd.c_str());
        Row r;
        r.id = "peers";
        r.kind = "peer";
        r.covers = "unavailable: hdrfusion-peers failed (" + how + ")";
        rows.push_back(std::move(r));
      }
      const json pj = rc == 0 ? io::ReadJsonFile(pout / "peers.json") : json{{"peers", json::array()}};
      for (const auto& e : pj.at("peers")) {
        PeerResult pr = ReadPeerResult(e, pout, frames.size());
        Row r;
        r.id = pr.id;
        r.label = pr.label;
        r.kind = "peer";
        if (!pr.unavailable.empty()) {
          r.covers = "unavailable: " + pr.unavailable;
          rows.push_back(std::move(r));
          continue;
        }
        r.poses = std::move(pr.poses);
        r.lost = pr.failed;
        r.seconds = pr.seconds;
        r.covers = "tracking";
        rows.push_back(std::move(r));
        // Open3D's TSDF integration at its own poses, beside our engine on the same frames.
        if (e.contains("tsdf_frames") && e.at("tsdf_frames").get<int>() > 2 && fs::exists(pout / "open3d-tsdf.ply")) {
          const int k = e.at("tsdf_frames").get<int>();
          const sim::SyntheticSource scene_src(so);
          const Pose T0 = *frames[0].T_world_camera_true;
          const eval::ModelError theirs = eval::CompareModel(io::ReadPly(pout / "open3d-tsdf.ply"), scene_src.scene(), T0);
          pipeline::Pipeline ours(engine, sensor.camera, sensor);
          Progress p("tracking: " + ae + " our engine over the same " + std::to_string(k) + " frames", k);
          const auto t0 = std::chrono::steady_clock::now();
          for (int i = 0; i < k; ++i) {
            ours.Process(frames[std::size_t(i)]);
            p.Step();
          }
          const double our_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          p.Done();
          const eval::ModelError mine = eval::CompareModel(ours.ExtractMesh(), scene_src.scene(), T0);
          char g[512];
          std::snprintf(g, sizeof g,
                        "Geometry over the first %d frames, each system at its own poses (mesh vertices' median "
                        "distance to the true surface): Open3D odometry + ScalableTSDFVolume (voxel 4 m/512, "
                        "truncation 4 cm, its example's settings) %.1f mm, %zu vertices, integration %.1f s; "
                        "HDRFusion (nr+icp, defaults) %.1f mm, %zu vertices, whole engine %.1f s.\n\n",
                        k, 1000 * theirs.mesh_median_distance_m, theirs.vertices,
                        e.at("tsdf_seconds").get<double>(), 1000 * mine.mesh_median_distance_m, mine.vertices, our_s);
          geometry = g;
          geometry_j = {{"frames", k},
                        {"open3d_mesh_median_distance_m", theirs.mesh_median_distance_m},
                        {"open3d_tsdf_seconds", e.at("tsdf_seconds").get<double>()},
                        {"hdrfusion_mesh_median_distance_m", mine.mesh_median_distance_m},
                        {"hdrfusion_seconds", our_s}};
        }
      }
    }
    // 4. Errors, plots, tables.
    double top_t = 0, top_r = 0;
    for (Row& r : rows) {
      if (r.poses.empty()) continue;
      r.err = eval::CompareTrajectories(r.poses, truth);
      r.per_frame = PerFrameErrors(r.poses, truth, r.err.T_gt_est);
      for (double v : r.per_frame.trans_m) top_t = std::max(top_t, v);
      for (double v : r.per_frame.rot_deg) top_r = std::max(top_r, v);
    }
    top_t = std::clamp(top_t * 100.0, 1.0, 30.0);  // cm, clipped at 30 cm
    top_r = std::clamp(top_r, 1.0, 15.0);          // degrees, clipped at 15
    const int n = int(frames.size());
    Plot pt(1000, 420, 0, n - 1, 0, top_t), pr(1000, 420, 0, n - 1, 0, top_r);
    std::vector<double> xs(frames.size());
    for (int i = 0; i < n; ++i) xs[std::size_t(i)] = i;
    json j = json::array();
    char line[512];
    std::string table =
        "| tracker | kind | ATE RMSE (cm) | ATE max (cm) | RPE trans. (mm/frame) | RPE rot. (deg/frame) | first "
        "failure | lost | wall (s) | frames/s | covers | plot colour |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const Row& r = rows[k];
      const Rgb8 c = kPalette[k % std::size(kPalette)];
      if (r.poses.empty()) {
        std::snprintf(line, sizeof line, "| %s | peer | - | - | - | - | - | - | - | - | %s | - |\n", r.id.c_str(),
                      r.covers.c_str());
        table += line;
        j.push_back({{"id", r.id}, {"label", r.label}, {"kind", r.kind}, {"unavailable", r.covers}});
        continue;
      }
      std::vector<double> tcm, rdeg = r.per_frame.rot_deg;
      for (double v : r.per_frame.trans_m) tcm.push_back(v * 100.0);
      // The first frame whose own motion is wrong by more than 2 cm or 2 degrees.
      int first_failure = -1;
      for (int i = 1; i < n && first_failure < 0; ++i) {
        const Pose e = (truth[std::size_t(i - 1)].inverse() * truth[std::size_t(i)]).inverse() *
                       (r.poses[std::size_t(i - 1)].inverse() * r.poses[std::size_t(i)]);
        if (se3::TranslationNorm(e) > 0.02 || se3::RotationAngle(e) > 2.0 * M_PI / 180.0) first_failure = i;
      }
      const std::string ff = first_failure < 0 ? "none" : std::to_string(first_failure);
      pt.Line(xs, tcm, c, 1);
      pr.Line(xs, rdeg, c, 1);
      std::snprintf(line, sizeof line, "| %s | %s | %.2f | %.2f | %.2f | %.3f | %s | %d | %.1f | %.1f | %s | %s |\n",
                    r.id.c_str(), r.kind.c_str(), 100 * r.err.ate_rmse_m, 100 * r.err.ate_max_m,
                    1000 * r.err.rpe_trans_rmse_m, r.err.rpe_rot_rmse_deg, ff.c_str(), r.lost, r.seconds,
                    double(n) / std::max(1e-9, r.seconds), r.covers.c_str(), Hex(c).c_str());
      table += line;
      j.push_back({{"id", r.id},
                   {"label", r.label},
                   {"kind", r.kind},
                   {"ate_rmse_m", r.err.ate_rmse_m},
                   {"ate_median_m", r.err.ate_median_m},
                   {"ate_max_m", r.err.ate_max_m},
                   {"rpe_trans_rmse_m", r.err.rpe_trans_rmse_m},
                   {"rpe_rot_rmse_deg", r.err.rpe_rot_rmse_deg},
                   {"lost", r.lost},
                   {"first_failure", first_failure},
                   {"seconds", r.seconds},
                   {"covers", r.covers},
                   {"trans_error_m", r.per_frame.trans_m},
                   {"rot_error_deg", r.per_frame.rot_deg}});
    }
    const std::string stem = "tracking_" + ae;
    io::WriteColorPng(out / (stem + "_translation.png"), pt.image());
    io::WriteColorPng(out / (stem + "_rotation.png"), pr.image());
    double ratio_lo = 1e30, ratio_hi = 0;
    for (const auto& f : frames) ratio_lo = std::min(ratio_lo, *f.exposure_ms), ratio_hi = std::max(ratio_hi, *f.exposure_ms);
    std::snprintf(line, sizeof line, "## %s auto exposure (exposures %.2f to %.1f ms, %.1f stops)\n\n", ae.c_str(),
                  ratio_lo, ratio_hi, std::log2(ratio_hi / ratio_lo));
    md += line;
    md += table;
    md += "\nPer-frame error after the alignment, against the frame index: `" + stem +
          "_translation.png` (0 to " + std::to_string(int(std::lround(top_t))) + " cm) and `" + stem +
          "_rotation.png` (0 to " + std::to_string(int(std::lround(top_r))) +
          " degrees); each tracker in its plot colour, values above the top clipped.\n\n"
          "![translation](" + stem + "_translation.png)\n\n![rotation](" + stem + "_rotation.png)\n\n";
    md += geometry;
    all[ae] = {{"frames", n}, {"size", a.size}, {"trackers", j}};
    if (!geometry_j.is_null()) all[ae]["geometry"] = geometry_j;
    std::printf("%s auto exposure, %d frames:\n%s\n", ae.c_str(), n, table.c_str());
    std::fflush(stdout);
  }
  md += "## The trackers\n\n";
  for (const auto& t : trackers) md += "- `" + t.id + "`: " + t.label + "\n";
  md += "- peers (run by `hdrfusion-peers` from Debian's libopencv-contrib-dev 4.6 and libopen3d-dev 0.16, their "
        "documented default settings; frame to frame, started from the same constant-velocity prediction as ours): "
        "`opencv-rgbd` RgbdOdometry (photometric on grey), `opencv-icp` ICPOdometry, `opencv-rgbd-icp` "
        "RgbdICPOdometry, `opencv-kinfu` KinectFusion (Debian's OpenCV is built without OPENCV_ENABLE_NONFREE, so "
        "KinFu refuses to start: reported, not run), `open3d` ComputeRGBDOdometry with the hybrid Jacobian "
        "(its TSDF integration runs too; its time is not in the tracking time).\n";
  io::WriteFileAtomically(out / "tracking.md", md);
  io::WriteFileAtomically(out / "tracking.json", all.dump(1) + "\n");
  std::printf("wrote %s/{tracking.md, tracking.json, tracking_*_translation.png, tracking_*_rotation.png}\n",
              a.out.c_str());
  return 0;
}

}  // namespace hdrf::experiments
