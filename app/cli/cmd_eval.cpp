// hdrfusion eval SEQUENCE DIR: trajectory error (ATE after Horn alignment, RPE) against the
// sequence's groundtruth.txt; for synthetic sequences also the mesh's distance to the true
// surface and its radiance against the true scene radiance.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "common/error.h"
#include "eval/eval.h"
#include "io/ply.h"
#include "io/project.h"
#include "mesh/mesh.h"
#include "io/sequence.h"
#include "io/output_file.h"
#include "io/tum.h"
#include "sim/scene.h"

namespace hdrf::cli {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {
}  // namespace

Command AddEvalCommand(CLI::App& app) {
  struct Args {
    std::string seq, dir;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("eval", "Accuracy of a scan against the sequence's ground truth");
  cmd->add_option("SEQUENCE", a->seq, "The sequence that was scanned (with groundtruth.txt)")->required();
  cmd->add_option("DIR", a->dir, "The scan's output folder (trajectory.txt, mesh.ply) or its project (.hdrproj; "
                                  "eval.json is then written beside it as NAME.eval.json)")->required();
  return {cmd, [a] {
    io::SequenceReadOptions ro;
    ro.allow_missing_depth = true;
    const io::SequenceReader seq(a->seq, ro);
    if (!seq.has_groundtruth())
      throw InputError(fs::path(a->seq) / "groundtruth.txt", "file is missing: nothing to evaluate against");
    const bool is_project = fs::path(a->dir).extension() == io::kProjectExtension;
    std::optional<io::Project> project;
    std::vector<io::TimedPose> est;
    if (is_project) {
      project = io::LoadProject(a->dir);
      for (const pipeline::FrameReport& r : project->reports) est.push_back({r.timestamp, r.T_world_camera});
    } else {
      est = io::ReadTrajectory(fs::path(a->dir) / "trajectory.txt");
    }
    std::vector<double> gt_t;
    std::vector<Pose> gt_pose;
    for (const auto& f : seq.frames())
      if (f.T_world_camera) {
        gt_t.push_back(f.timestamp);
        gt_pose.push_back(*f.T_world_camera);
      }
    std::vector<Pose> e, g;
    for (const auto& p : est)
      if (auto k = io::NearestTimestamp(gt_t, p.timestamp)) {
        e.push_back(p.T_world_camera);
        g.push_back(gt_pose[*k]);
      }
    // Too few poses to compare: say which files and why, not only a count.
    if (e.size() < 3) {
      const fs::path est_file = is_project ? fs::path(a->dir) : fs::path(a->dir) / "trajectory.txt";
      throw InputError(est_file, std::to_string(est.size()) + " poses, of which " + std::to_string(e.size()) +
                                     " have a ground-truth pose at their timestamp in " +
                                     (fs::path(a->seq) / "groundtruth.txt").string() + " (" +
                                     std::to_string(gt_t.size()) +
                                     " poses there); 3 or more are needed: is this the scan of that sequence?");
    }
    const eval::TrajectoryError te = eval::CompareTrajectories(e, g);
    json out = {{"pairs", te.pairs},
                {"ate_rmse_m", te.ate_rmse_m},
                {"ate_median_m", te.ate_median_m},
                {"ate_max_m", te.ate_max_m},
                {"rpe_trans_rmse_m", te.rpe_trans_rmse_m},
                {"rpe_rot_rmse_deg", te.rpe_rot_rmse_deg}};
    std::printf("trajectory: %zu frames, ATE RMSE %.4f m (median %.4f, max %.4f), RPE %.4f m / %.3f deg per frame\n",
                te.pairs, te.ate_rmse_m, te.ate_median_m, te.ate_max_m, te.rpe_trans_rmse_m, te.rpe_rot_rmse_deg);
    const auto& syn = seq.sensor().synthetic;
    const fs::path ply = is_project ? fs::path() : fs::path(a->dir) / "mesh.ply";
    if (syn && (is_project || fs::exists(ply)) && !g.empty()) {
      const sim::Scene scene = sim::Scene::Build(syn->scene, syn->seed);
      const mesh::Mesh m = is_project ? mesh::ExtractMesh(project->model) : io::ReadPly(ply);
      // The scan's world is the first scanned camera; ground truth maps it into the scene.
      const eval::ModelError me = eval::CompareModel(m, scene, g.front());
      out["mesh_vertices"] = me.vertices;
      out["mesh_median_distance_m"] = me.mesh_median_distance_m;
      std::printf("mesh: %zu vertices, distance to the true surface: median %.4f m\n", me.vertices,
                  me.mesh_median_distance_m);
      if (me.radiance_samples > 0) {
        out["radiance_median_error_stops"] = me.radiance_median_stops;
        out["radiance_within_0.1_stop"] = me.within_01_stop;
        out["radiance_within_0.25_stop"] = me.within_025_stop;
        out["radiance_scale"] = {me.scale[0], me.scale[1], me.scale[2]};
        std::printf("radiance: median error %.3f stops after one scale per channel; %.1f %% within 0.1 stop, %.1f %% within 0.25\n",
                    me.radiance_median_stops, 100 * me.within_01_stop, 100 * me.within_025_stop);
      }
    }
    const fs::path report = is_project ? fs::path(a->dir).replace_extension(".eval.json") : fs::path(a->dir) / "eval.json";
    io::WriteFileAtomically(report, out.dump(1) + "\n");
    return 0;
  }};
}

}  // namespace hdrf::cli
