// hdrfusion scan SOURCE --out DIR: the whole method on a sequence or the synthetic sensor.
// Writes trajectory.txt, mesh.ply, renders (OpenEXR + PNG), report.json and the project
// (scan.hdrproj, or --save PATH) that --resume continues, as one set: all are replaced or
// none. If the source fails midway, Ctrl-C cancels the scan, or an output cannot be written,
// nothing in the output folder changes and the model so far is kept in the recovery file.
// While it runs, the scan is autosaved to a recovery file (io/project.h) every --autosave
// seconds; a scan that finishes removes it, one that crashed leaves it to be resumed.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/progress.h"
#include "cli/setting_flags.h"
#include "io/source_spec.h"
#include "sensors/live_source.h"
#include "common/error.h"
#include "io/exr.h"
#include "io/image_io.h"
#include "io/keyframes_io.h"
#include "io/options_json.h"
#include "io/ply.h"
#include "io/project.h"
#include "cli/interrupt.h"
#include "io/output_file.h"
#include "io/tum.h"
#include "mesh/mesh.h"
#include "pipeline/pipeline.h"
#include "pipeline/scan_session.h"
#include "io/ocio_display.h"
#include "tonemap/display.h"
#include "tonemap/operator.h"

namespace hdrf::cli {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

ColorImage ShadeNormals(const Image<Float3>& n, const Pose& T_world_camera) {
  const Eigen::Matrix3d Rt = T_world_camera.rotation().transpose();
  ColorImage out(n.width(), n.height());
  for (std::size_t i = 0; i < n.size(); ++i) {
    const Float3 w = n[i];
    if (Length(w) == 0) {
      out[i] = {0, 0, 0};
      continue;
    }
    const Eigen::Vector3d c = Rt * Eigen::Vector3d(w.x, w.y, w.z);  // camera frame
    const double shade = std::clamp(-c.z(), 0.0, 1.0) * 0.85 + 0.15;
    const auto v = std::uint8_t(255 * shade);
    out[i] = {v, v, v};
  }
  return out;
}

// The render's PNG through the chosen operator and the OpenColorIO display transform.
void WriteRender(const fs::path& dir, const std::string& name, const volume::Volume::Rendering& r, const Pose& T,
                 tonemap::Operator& tone, const io::OcioDisplay& ocio) {
  io::WriteExr(dir / (name + ".exr"), r.radiance, io::ExrPrecision::kHalf);
  Image<Float3> shown;
  tone.Map(r.radiance, shown, tonemap::FrameTime::Still());
  ocio.Apply(shown);
  io::WriteColorPng(dir / (name + ".png"), io::OcioDisplay::Quantise(shown));
  io::WriteColorPng(dir / (name + "_normals.png"), ShadeNormals(r.normal, T));
}

}  // namespace

Command AddScanCommand(CLI::App& app) {
  struct Args {
    std::string source, out, options, response;
    int max_frames = 0;
    std::string tone = "mantiuk08";
    bool frame_to_frame = false;
    std::string save, resume;
    double autosave_s = 60;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("scan", "Track, fuse and mesh a sequence or the synthetic sensor");
  cmd->add_option("SOURCE", a->source, "Sequence folder, synthetic:[scene=room,seed=1,frames=300,ae=smooth,size=320x240], "
                  "openni:[device=URI|SERIAL,mode=vga|qvga,ae=on|off,awb=on|off,exposure=MS,gain=N,frames=N] "
                  "(a live camera, docs/sensors.md) or a recording FILE.oni")
      ->required();
  cmd->add_option("--out", a->out, "Output folder (created; existing outputs are replaced)")->required();
  cmd->add_option("--options", a->options, "JSON file of engine settings (docs/formats.md); the flags override it");
  cmd->add_flag("--frame-to-frame", a->frame_to_frame, "Track against the previous frame (tracker.frame_to_model false)");
  cmd->add_option("--response", a->response, "Fallback for sequences without calibration: srgb")
      ->check(CLI::IsMember({"srgb"}));
  cmd->add_option("--frames", a->max_frames, "Process at most this many frames (default: all)")
      ->check(CLI::Range(1, std::numeric_limits<int>::max()));
  cmd->add_option("--save", a->save, "Project file to save the scan to, to continue or export it later "
                                     "(default OUT/scan.hdrproj)");
  cmd->add_option("--resume", a->resume, "Continue the scan saved in this project file, in its coordinates and "
                                         "with its settings, from SOURCE (the same sequence goes on where it stopped)");
  cmd->add_option("--autosave", a->autosave_s, "Seconds between autosaves to the recovery file (0: none)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 86400.0));
  cmd->add_option("--tone", a->tone, "Tone mapping of the PNG renders and the PLY's display colours: OP[,key=value...] "
                                     "(see hdrfusion tonemap --list)")
      ->capture_default_str();
  auto flags = std::make_shared<SettingFlags>(cmd);
  return {cmd, [a, flags] {
    // A resumed scan starts from its project's settings; files and flags apply on top.
    std::optional<io::Project> project;
    if (!a->resume.empty()) project = io::LoadProject(a->resume);
    auto settings = [&](pipeline::PipelineOptions& o) {
      if (!a->options.empty()) io::ReadPipelineOptions(a->options, o);
      if (a->frame_to_frame) o.tracker.frame_to_model = false;
      flags->Apply(o);
      o.Check();
    };
    pipeline::PipelineOptions o = project ? project->options : pipeline::PipelineOptions{};
    settings(o);
    // The tone mapping is checked before scanning: a typo must not cost a scan.
    const tonemap::Spec tone_spec = tonemap::ParseSpec(a->tone);
    const tonemap::OperatorDecl& tone_decl = tonemap::FindOperator(tone_spec.op);
    const tonemap::Params tone_params = tonemap::ResolveParams(tone_decl, tone_spec.values);
    auto source = sensors::OpenAnySource(a->source, a->response);
    const fs::path out = a->out;
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) throw InputError(out, "cannot create the output folder: " + ec.message());
    for (const std::string& w : source->sensor().warnings) std::fprintf(stderr, "scan: warning: %s\n", Printable(w).c_str());
    const fs::path save = a->save.empty() ? out / "scan.hdrproj" : fs::path(a->save);
    // An output that may not be replaced (a link, a device, a folder) is refused before the scan.
    io::CheckReplaceable(save);
    for (const char* f : {"trajectory.txt", "mesh.ply", "report.json", "keyframes.json", "sensor.json", "render_first.exr",
                          "render_first.png", "render_first_normals.png", "render_last.exr", "render_last.png",
                          "render_last_normals.png"})
      io::CheckReplaceable(out / f);
    // Unfinished scans a crash left behind are offered, newest first.
    for (const fs::path& r : io::FindRecoveryFiles())
      if (project == std::nullopt || fs::absolute(r) != fs::absolute(a->resume)) {
        std::fprintf(stderr, "scan: an unfinished scan was autosaved to %s: continue it with "
                             "hdrfusion scan --resume %s SOURCE --out DIR (or delete the file)\n",
                     r.c_str(), r.c_str());
        break;
      }
    std::unique_ptr<pipeline::ScanSession> owned;
    const bool same_source = project && io::SameSource(*project, a->source, source->description());
    if (project) {
      const PinholeCamera& pc = project->sensor.camera;
      const PinholeCamera& sc = source->sensor().camera;
      if (!io::SameCamera(pc, sc))
        throw InputError(a->resume, "the project was scanned with a " + std::to_string(pc.width) + "x" +
                                        std::to_string(pc.height) + " camera (fx " + std::to_string(pc.fx) +
                                        "), SOURCE has a " + std::to_string(sc.width) + "x" +
                                        std::to_string(sc.height) + " one (fx " + std::to_string(sc.fx) +
                                        "): a scan goes on with the camera it began with");
      owned = io::ResumeSession(*project, [&](pipeline::PipelineOptions& po) { po = o; });
      // The same bounded source goes on where the scan stopped.
      if (same_source && source->size() >= 0) {
        if (!source->Skip(project->resume.frames))
          throw InputError(a->resume, "holds " + std::to_string(project->resume.frames) + " frames, more than " +
                                          source->description() + " has: nothing left to scan");
        std::fprintf(stderr, "scan: resuming %s after its %d frames\n", a->resume.c_str(), project->resume.frames);
      } else {
        std::fprintf(stderr, "scan: resuming %s (%d frames) from the first frame of %s: it must start where the "
                             "scan stopped (the tracker starts from the last pose)\n",
                     a->resume.c_str(), project->resume.frames, source->description().c_str());
      }
    } else {
      owned = std::make_unique<pipeline::ScanSession>(o, source->sensor().camera, source->sensor());
    }
    pipeline::ScanSession& session = *owned;
    pipeline::Pipeline& pipe = session.pipeline();
    if (!pipe.device_note().empty()) std::fprintf(stderr, "scan: %s\n", pipe.device_note().c_str());
    if (!pipe.settings_note().empty()) std::fprintf(stderr, "scan: note: %s\n", pipe.settings_note().c_str());
    if (o.volume.gpu_memory_mb > 0 && pipe.device() != Device::kCuda)
      std::fprintf(stderr, "scan: note: volume.gpu_memory_mb applies on the GPU; on the CPU the whole model stays in "
                           "host memory (volume.max_memory_mb)\n");
    const int left = source->size() < 0 ? -1 : source->size() - (same_source ? project->resume.frames : 0);
    const int total = a->max_frames > 0 ? (left < 0 ? a->max_frames : std::min(a->max_frames, left)) : left;
    if (total < 0)
      throw SettingError("SOURCE", "a live source runs until stopped: give frames=N in its spec or --frames N");
    std::fprintf(stderr, "scan: %s, %d frames, tracker %s, unbounded volume, %.1f mm voxels, on the %s\n",
                 source->description().c_str(), total, tracking::TrackerName(o.tracker.kind),
                 1000 * o.volume.voxel_m,
                 pipe.device() == Device::kCuda ? ("GPU: " + CudaDeviceDescription()).c_str() : "CPU");
    const std::string source_text = project ? project->source : source->description();
    const std::string source_spec = same_source && !project->source_spec.empty() ? project->source_spec : a->source;
    // Autosaves go to a recovery file named after the project and the start time.
    const fs::path recovery = io::NewRecoveryFile(save.stem().string());
    auto last_save = std::chrono::steady_clock::now();
    std::string failure, autosave_failure;
    bool stopped = false, far_said = false;
    Progress progress("scan", total);
    // The loop's own time (reading the source included): the rate the studio is compared with.
    const auto loop_start = std::chrono::steady_clock::now();
    {
      StopOnInterrupt stop;  // Ctrl-C ends the scan early, keeping what it built
      try {
        pipeline::FrameInput f;
        pipeline::FrameState last_state = pipeline::FrameState::kTracked;
        std::string last_why;
        for (int i = 0; i < total && source->Next(f); ++i) {
          const pipeline::FrameReport& r = session.Process(f);
          // What became of the frame, said when it changes (a long loss is one line, not one per frame).
          if (r.state != last_state || (r.state != pipeline::FrameState::kTracked && r.why != last_why)) {
            if (r.state == pipeline::FrameState::kTracked || (r.state == pipeline::FrameState::kRelocalised && r.fused))
              std::fprintf(stderr, "\nscan: frame %d: tracking again%s; fused\n", r.index,
                           r.state == pipeline::FrameState::kRelocalised ? " (relocalised from an earlier view)" : "");
            else
              std::fprintf(stderr, "\nscan: frame %d: %s (%s); not fused\n", r.index, pipeline::FrameStateName(r.state),
                           r.why.c_str());
          }
          last_state = r.state;
          last_why = r.why;
          // Said when a quarter of the view first lies beyond the ray cast, again only after it
          // came back within it.
          if (r.depth_beyond_far > 0.25 && !far_said)
            std::fprintf(stderr, "\nscan: warning: frame %d: %.0f %% of the depth lies beyond %.1f m, past the model's "
                                 "ray cast (volume.raycast_far_m): those surfaces are fused but tracking matches only "
                                 "nearer ones\n",
                         r.index, 100 * r.depth_beyond_far, o.volume.raycast_far_m);
          far_said = r.depth_beyond_far > 0.25 || (far_said && r.depth_beyond_far > 0.1);
          if (!r.volume_full.empty())
            std::fprintf(stderr, "\nscan: warning: frame %d: the volume is full: %s. Surfaces not yet in the model are "
                                 "no longer added; the model so far is kept and the scan goes on (raise "
                                 "volume.max_memory_mb, or scan with larger voxels: volume.voxel_m)\n",
                         r.index, r.volume_full.c_str());
          progress.Step();
          if (a->autosave_s > 0 && std::chrono::duration<double>(std::chrono::steady_clock::now() - last_save).count() >=
                                       a->autosave_s) {
            try {
              fs::create_directories(recovery.parent_path());
              io::SaveProject(recovery, session, {source_text, source_spec, false});
            } catch (const std::exception& e) {
              if (autosave_failure.empty())
                std::fprintf(stderr, "\nscan: warning: autosave failed: %s (the scan goes on)\n", e.what());
              autosave_failure = e.what();
            }
            last_save = std::chrono::steady_clock::now();
          }
          if (stop.raised()) {
            stopped = true;
            break;
          }
        }
      } catch (const std::exception& e) {
        failure = e.what();
      }
    }
    progress.Done();
    const double loop_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();
    const int n = session.frames();
    if (n == 0) throw Error(failure.empty() ? "the source delivered no frames" : failure);
    if (session.count(pipeline::FrameState::kWaiting) == n && !pipe.volume_stats().allocated_bricks)
      throw Error("none of the " + std::to_string(n) + " frames could anchor the model: none had depth on at least " +
                  std::to_string(int(std::ceil(100 * o.tracker.min_anchor_depth))) +
                  " % of its pixels (tracker.min_anchor_depth); nothing was written" +
                  (failure.empty() ? "" : " (and the source failed: " + failure + ")"));
    // The model, kept in the recovery file when the outputs cannot be: what to do with it.
    const auto keep = [&]() -> std::string {
      try {
        fs::create_directories(recovery.parent_path());
        io::SaveProject(recovery, session, {source_text, source_spec, false});
      } catch (const std::exception& e) {
        return "the model could not be kept either: " + std::string(e.what());
      }
      return "the " + std::to_string(n) + " frames scanned are kept in " + recovery.string() +
             ": export them with `hdrfusion export " + recovery.string() + " --out DIR`, or go on with `hdrfusion " +
             "scan --resume " + recovery.string() + " SOURCE --out DIR`";
    };
    // A scan that did not finish leaves the outputs of the last one that did exactly as they were.
    if (stopped) {
      std::fprintf(stderr, "scan: cancelled by Ctrl-C after %d frames: nothing in %s was changed; %s\n", n,
                   a->out.c_str(), keep().c_str());
      return 130;
    }
    if (!failure.empty()) throw Error(failure + " (nothing in " + a->out + " was changed; " + keep() + ")");
    const int lost = session.lost();
    const std::optional<double> exp_err = session.exposure_median_relative_error();
    std::size_t vertices = 0, triangles = 0;
    // All outputs are one set: written beside their targets, and moved into place only when
    // every one of them is complete (a full disk or a failed mesh changes nothing).
    try {
      io::OutputSet outputs;
      // The project first: the model is the most expensive thing to lose.
      const auto save_start = std::chrono::steady_clock::now();
      io::SaveProject(save, session, {source_text, source_spec, true});
      std::fprintf(stderr, "scan: wrote the project (%.2f s)\n",
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - save_start).count());
      std::vector<io::TimedPose> trajectory;
      for (const pipeline::FrameReport& r : session.reports()) trajectory.push_back({r.timestamp, r.T_world_camera});
      io::WriteTrajectory(out / "trajectory.txt", trajectory);
      // The keyframes (colour, pose, exposure ratio) and the sensor: what export bakes textures from.
      io::WriteKeyframes(out, session.keyframes(), session.sensor(), o.pcf);
      std::fprintf(stderr, "scan: extracting the mesh...\n");
      const mesh::Mesh m = pipe.ExtractMesh();
      vertices = m.position.size();
      triangles = m.triangles.size();
      // Renders and the mesh's display colours through one operator instance: the mesh takes
      // the curve of the last render (as the studio's 3-D view takes the model view's).
      const io::OcioDisplay ocio;
      auto tone = tone_decl.make(tone_params, Device::kCpu);
      WriteRender(out, "render_first", pipe.Render(Pose::Identity()), Pose::Identity(), *tone, ocio);
      WriteRender(out, "render_last", pipe.Render(pipe.pose()), pipe.pose(), *tone, ocio);
      const std::vector<Rgb8> display = ocio.Encode(tone->MapList(m.radiance));
      io::WritePly(out / "mesh.ply", m, m.radiance.size() == m.position.size() ? &display : nullptr);
      json frames = json::array();
      for (const pipeline::FrameReport& r : session.reports()) frames.push_back(io::FrameReportToJson(r));
      const pipeline::StageTimes mean = session.mean_ms();
      const pipeline::VolumeStats vs = pipe.volume_stats();
      json report = {{"source", source_text},
                     {"device", DeviceName(pipe.device())},
                     {"frames", n},
                     {"lost_frames", lost},
                     {"fused_frames", session.fused()},
                     {"waiting_frames", session.count(pipeline::FrameState::kWaiting)},
                     {"unconfirmed_frames", session.count(pipeline::FrameState::kConfirming)},
                     {"relocalisations", session.relocalisations()},
                     {"options", json::parse(io::PipelineOptionsToJson(pipe.options()))},  // as used (the frames may lower some)
                     {"mean_ms", {{"convert", mean.convert}, {"normalize", mean.normalize}, {"track", mean.track},
                                  {"compensate", mean.compensate}, {"integrate", mean.integrate},
                                  {"raycast", mean.raycast}, {"total", mean.total()}}},
                     {"fps", session.frames_per_second()},
                     {"wall_fps", loop_s > 0 ? double(n) / loop_s : 0.0},
                     {"volume", {{"allocated_bricks", vs.allocated_bricks}, {"bytes", vs.bytes}, {"full", vs.full},
                                 {"full_reason", vs.full_reason}, {"voxel_m", o.volume.voxel_m},
                                 {"gpu_bricks", vs.streaming.gpu_bricks}, {"host_bricks", vs.streaming.host_bricks},
                                 {"gpu_bytes", vs.streaming.gpu_bytes}, {"swapped_out", vs.streaming.swapped_out},
                                 {"swapped_in", vs.streaming.swapped_in}}},
                     {"mesh", {{"vertices", vertices}, {"triangles", triangles}}},
                     {"project", save.string()},
                     {"frames_detail", frames}};
      if (exp_err) report["exposure_median_relative_error"] = *exp_err;
      io::WriteFileAtomically(out / "report.json", report.dump(1) + "\n");
      outputs.Commit();
    } catch (const std::exception& e) {
      throw Error(std::string(e.what()) + " (nothing in " + a->out + " was changed; " + keep() + ")");
    }
    std::error_code rm_ec;
    fs::remove(recovery, rm_ec);
    std::printf("scanned %d frames (%d fused, %d lost, %d relocalisations) at %.1f frames/s (%.1f with reading the "
                "source): %zu mesh vertices, %zu triangles\n",
                n, session.fused(), lost, session.relocalisations(), session.frames_per_second(),
                loop_s > 0 ? double(n) / loop_s : 0.0, vertices, triangles);
    if (exp_err) std::printf("exposure ratio vs reported: median relative error %.2f %%\n", 100 * *exp_err);
    std::printf("wrote %s/{trajectory.txt, mesh.ply, render_last.exr/png, render_first.exr/png, keyframes/ (%zu), "
                "keyframes.json, sensor.json, report.json} and the project %s\n",
                a->out.c_str(), session.keyframes().size(), save.c_str());
    return 0;
  }};
}

}  // namespace hdrf::cli
