// `hdrfusion-experiments real`: tracking on real recordings. The frames of each 7-Scenes
// folder (frame-NNNNNN.color.png or .jpg, .depth.png in millimetres, .pose.txt camera to
// world, camera-intrinsics.txt) are written as a sequence in the TUM layout; our trackers
// (nr+icp, icp, nr, frame to model, engine defaults, the sRGB curve since the sensor has no
// calibration; nr+icp also with fixed instead of measured scales, nr+icp and icp also with the
// real-sensor settings) and the peers
// (hdrfusion-peers) run on that folder in the same run, each compared with the dataset's own
// poses. Writes real.md and real.json (with several recordings, one folder each and a real.md
// of all).
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>

#include "cli/progress.h"
#include "common/error.h"
#include "eval/eval.h"
#include "experiments.h"
#include "io/image_io.h"
#include "io/json_file.h"
#include "io/source_spec.h"
#include "io/output_file.h"
#include "io/tum.h"
#include "tracking_experiment.h"

namespace hdrf::experiments {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

Pose ReadPoseMatrix(const fs::path& file) {
  std::ifstream in(file);
  double m[16];
  for (double& v : m)
    if (!(in >> v)) throw InputError(file.string(), "needs 16 numbers (a 4x4 camera-to-world matrix)");
  Pose p = Pose::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) p.matrix()(r, c) = m[4 * r + c];
  return se3::Orthonormalized(p);
}

// fx fy cx cy from a 3x3 matrix file.
std::array<double, 4> ReadIntrinsics(const fs::path& file) {
  std::ifstream in(file);
  double k[9];
  for (double& v : k)
    if (!(in >> v)) throw InputError(file.string(), "needs 9 numbers (the 3x3 camera matrix)");
  if (!(k[0] > 0 && k[4] > 0)) throw InputError(file.string(), "focal lengths must be positive");
  return {k[0], k[4], k[2], k[5]};
}

// The recording's folder name (a trailing slash ignored).
std::string RecordingName(const std::string& folder) {
  fs::path p(folder);
  if (p.filename().empty()) p = p.parent_path();
  return p.filename().string();
}

}  // namespace

void CheckRealTrackingArgs(const RealTrackingArgs& a) {
  if (a.out.empty()) throw SettingError("--out", "names the results folder and is required");
  if (a.data.empty()) throw SettingError("--data", "names a 7-Scenes folder and is required");
  std::set<std::string> names;
  for (const std::string& d : a.data) {
    if (!fs::is_directory(fs::path(d) / "frames"))
      throw InputError(d, "has no frames/ folder (frame-NNNNNN.color.png or .jpg, .depth.png, .pose.txt)");
    if (!fs::exists(fs::path(d) / "camera-intrinsics.txt")) throw InputError(d, "has no camera-intrinsics.txt");
    if (!names.insert(RecordingName(d)).second)
      throw SettingError("--data", "two recordings are named '" + RecordingName(d) + "' (each gets OUT/<name>/)");
  }
  if (!a.peers_program.empty() && !fs::exists(a.peers_program))
    throw SettingError("--peers", "'" + a.peers_program + "' does not exist (hdrfusion-peers is built where "
                                  "tools/install_deps.sh --peers installed OpenCV contrib and Open3D)");
}

namespace {

// One recording: its sequence folder, our trackers and the peers on it; writes real.md and
// real.json in `out` and returns the table.
std::string RunRecording(const fs::path& data, const fs::path& out, const fs::path& work_dir,
                         const std::string& peers_program) {
  // 1. The recording as a sequence folder (copies: every reader gets identical files).
  std::map<int, std::string> stems;  // frame number -> "frame-NNNNNN"
  std::map<int, std::string> color_ext;  // frame number -> ".png" or ".jpg" (7-Scenes ships both)
  const std::regex pat(R"(frame-(\d{1,9})\.color(\.png|\.jpg))");
  for (const auto& e : fs::directory_iterator(data / "frames")) {
    std::smatch m;
    const std::string name = e.path().filename().string();
    if (std::regex_match(name, m, pat)) {
      const int n = std::stoi(m[1]);
      if (stems.count(n)) throw InputError((data / "frames").string(), "holds frame " + m[1].str() + " twice (.png and .jpg)");
      stems[n] = "frame-" + m[1].str();
      color_ext[n] = m[2].str();
    }
  }
  if (stems.size() < 5) throw InputError((data / "frames").string(), "holds fewer than 5 colour frames (frame-NNNNNN.color.png or .jpg)");
  const auto k = ReadIntrinsics(data / "camera-intrinsics.txt");
  const fs::path work = work_dir;
  const fs::path seq = work / "sequence";
  fs::remove_all(seq);
  fs::create_directories(seq / "rgb");
  fs::create_directories(seq / "depth");
  std::string rgb, depth;
  std::vector<io::TimedPose> gt;
  for (const auto& [n, stem] : stems) {
    for (const char* ext : {".depth.png", ".pose.txt"})
      if (!fs::exists(data / "frames" / (stem + ext)))
        throw InputError((data / "frames" / (stem + ext)).string(), "is missing (its colour frame is there)");
    const std::string cext = color_ext.at(n);
    fs::copy_file(data / "frames" / (stem + ".color" + cext), seq / "rgb" / (stem + cext));
    fs::copy_file(data / "frames" / (stem + ".depth.png"), seq / "depth" / (stem + ".png"));
    char t[32];
    std::snprintf(t, sizeof t, "%.6f", n / 30.0);  // 7-Scenes: 30 frames/s
    rgb += std::string(t) + " rgb/" + stem + cext + "\n";
    depth += std::string(t) + " depth/" + stem + ".png\n";
    gt.push_back({n / 30.0, ReadPoseMatrix(data / "frames" / (stem + ".pose.txt"))});
  }
  const auto write = io::WriteFileAtomically;
  write(seq / "rgb.txt", rgb);
  write(seq / "depth.txt", depth);
  io::WriteTrajectory(seq / "groundtruth.txt", gt);
  {
    const ColorImage probe =
        io::ReadColorImage(seq / "rgb" / (stems.begin()->second + color_ext.begin()->second));
    json s = {{"camera", {{"width", probe.width()}, {"height", probe.height()}, {"fx", k[0]}, {"fy", k[1]}, {"cx", k[2]},
                          {"cy", k[3]}}},
              {"depth", {{"scale", 1000}}}};
    write(seq / "sensor.json", s.dump(1) + "\n");
  }
  // 2. Our trackers, on the frames read back (no calibration: the sRGB curve).
  auto source = io::OpenSource(seq.string(), "srgb");
  const SensorInfo sensor = source->sensor();
  std::vector<pipeline::FrameInput> frames;
  {
    pipeline::FrameInput f;
    while (source->Next(f)) frames.push_back(std::move(f));
  }
  std::vector<Pose> truth;
  const Pose T0inv = frames.at(0).T_world_camera_true.value().inverse();
  for (const auto& f : frames) truth.push_back(T0inv * f.T_world_camera_true.value());
  struct Row {
    std::string id, label, kind;
    std::vector<Pose> poses;
    int lost = 0;
    double seconds = 0;
    std::string unavailable;
  };
  std::vector<Row> rows;
  pipeline::PipelineOptions engine;
  for (const auto& spec : ExperimentTrackers()) {
    if (spec.baseline || !spec.frame_to_model) continue;  // ours: nr-f2m, icp, nr+icp
    cli::Progress p("real: " + spec.id, int(frames.size()));
    const TrackerRun run = RunTracker(spec, frames, sensor.camera, sensor, engine, [&](int) { p.Step(); });
    p.Done();
    rows.push_back({spec.id, spec.label, "ours", run.poses, run.lost, run.seconds, ""});
    // The same tracker with settings a real sensor may want, for comparison with its defaults:
    // fixed instead of measured scales (nr+icp), and the settings for triangulating depth
    // sensors and unregistered colour (docs/engine.md, "Real sensors").
    struct Variant {
      std::string suffix, label;
      std::function<void(pipeline::PipelineOptions&)> set;
    };
    std::vector<Variant> variants;
    if (spec.kind == tracking::TrackerKind::kNrIcp) {
      variants.push_back({"-fixed-scales", ", fixed scales (tracker.adaptive_scales false)",
                          [](pipeline::PipelineOptions& o) { o.tracker.adaptive_scales = false; }});
      variants.push_back({"-real-sensor", ", tracker.depth_noise_scaling and tracker.photo_agreement true",
                          [](pipeline::PipelineOptions& o) {
                            o.tracker.depth_noise_scaling = true;
                            o.tracker.photo_agreement = true;
                          }});
    }
    if (spec.kind == tracking::TrackerKind::kIcp)
      variants.push_back({"-real-sensor", ", tracker.depth_noise_scaling true",
                          [](pipeline::PipelineOptions& o) { o.tracker.depth_noise_scaling = true; }});
    for (const Variant& v : variants) {
      pipeline::PipelineOptions o = engine;
      v.set(o);
      cli::Progress pv("real: " + spec.id + v.suffix, int(frames.size()));
      const TrackerRun rv = RunTracker(spec, frames, sensor.camera, sensor, o, [&](int) { pv.Step(); });
      pv.Done();
      rows.push_back({spec.id + v.suffix, spec.label + v.label, "ours", rv.poses, rv.lost, rv.seconds, ""});
    }
  }
  // 3. The peers on the same folder, now.
  if (peers_program.empty()) {
    std::fprintf(stderr, "real: peers not run (--peers names the hdrfusion-peers program to run them)\n");
  } else {
    const fs::path pout = work / "peers";
    fs::remove_all(pout);
    const std::string cmd = ShellQuote(peers_program) + " " + ShellQuote(seq.string()) + " --out " +
                            ShellQuote(pout.string()) + " --only open3d,opencv-rgbd,opencv-icp,opencv-rgbd-icp";
    std::fprintf(stderr, "real: peers: %s\n", cmd.c_str());
    const int rc = std::system(cmd.c_str());
    if (rc != 0) {
      rows.push_back({"peers", "", "peer", {}, 0, 0, "hdrfusion-peers failed (status " + std::to_string(rc) + ")"});
    } else {
      const json pj = io::ReadJsonFile(pout / "peers.json");
      for (const auto& e : pj.at("peers")) {
        PeerResult pr = ReadPeerResult(e, pout, frames.size());
        rows.push_back({pr.id, pr.label, "peer", std::move(pr.poses), pr.failed, pr.seconds, pr.unavailable});
      }
    }
  }
  // 4. The table.
  fs::create_directories(out);
  json j = json::array();
  std::string table =
      "| tracker | kind | ATE RMSE (cm) | ATE max (cm) | RPE trans. (mm/frame) | RPE rot. (deg/frame) | lost | wall (s) |\n"
      "|---|---|---|---|---|---|---|---|\n";
  char line[512];
  for (const Row& r : rows) {
    if (r.poses.empty()) {
      table += "| " + r.id + " | " + r.kind + " | unavailable: " + r.unavailable + " | | | | | |\n";
      j.push_back({{"id", r.id}, {"label", r.label}, {"kind", r.kind}, {"unavailable", r.unavailable}});
      continue;
    }
    const eval::TrajectoryError e = eval::CompareTrajectories(r.poses, truth);
    std::snprintf(line, sizeof line, "| %s | %s | %.2f | %.2f | %.2f | %.3f | %d | %.1f |\n", r.id.c_str(),
                  r.kind.c_str(), 100 * e.ate_rmse_m, 100 * e.ate_max_m, 1000 * e.rpe_trans_rmse_m,
                  e.rpe_rot_rmse_deg, r.lost, r.seconds);
    table += line;
    j.push_back({{"id", r.id},
                 {"label", r.label},
                 {"kind", r.kind},
                 {"ate_rmse_m", e.ate_rmse_m},
                 {"ate_max_m", e.ate_max_m},
                 {"rpe_trans_rmse_m", e.rpe_trans_rmse_m},
                 {"rpe_rot_rmse_deg", e.rpe_rot_rmse_deg},
                 {"lost", r.lost},
                 {"seconds", r.seconds}});
  }
  const std::string md =
      "# Tracking on a real recording (`hdrfusion-experiments real`)\n\n"
      "Recording: " + data.string() + ", " + std::to_string(frames.size()) + " frames at " +
      std::to_string(sensor.camera.width) + "x" + std::to_string(sensor.camera.height) +
      ", auto exposure on, colour and depth not registered, no calibration (ours: the sRGB curve). "
      "Reference: the dataset's own poses (KinectFusion estimates, not motion capture). ATE after a rigid "
      "alignment. Ours: frame to model, engine defaults; peers: hdrfusion-peers, their default settings, frame "
      "to frame, on the same sequence folder in the same run.\n\n" +
      table;
  io::WriteFileAtomically(out / "real.md", md);
  io::WriteFileAtomically(out / "real.json", json{{"frames", frames.size()}, {"trackers", j}}.dump(1) + "\n");
  std::printf("%s\n%s\nwrote %s/{real.md, real.json}\n", data.string().c_str(), table.c_str(), out.string().c_str());
  return "## " + RecordingName(data.string()) + " (" + std::to_string(frames.size()) + " frames)\n\n" + table;
}

}  // namespace

int RunRealTracking(const RealTrackingArgs& a) {
  CheckRealTrackingArgs(a);
  const fs::path out = a.out;
  if (a.data.size() == 1) {
    RunRecording(a.data[0], out, a.work.empty() ? out / "work" : fs::path(a.work), a.peers_program);
    return 0;
  }
  std::string md = "# Tracking on real recordings (`hdrfusion-experiments real`)\n\nEach recording's folder holds its "
                   "real.md (the set-up) and real.json.\n\n";
  for (const std::string& d : a.data) {
    const std::string name = RecordingName(d);
    const fs::path work = a.work.empty() ? out / name / "work" : fs::path(a.work) / name;
    md += RunRecording(d, out / name, work, a.peers_program) + "\n";
  }
  io::WriteFileAtomically(out / "real.md", md);
  std::printf("wrote %s/real.md\n", out.string().c_str());
  return 0;
}

}  // namespace hdrf::experiments
