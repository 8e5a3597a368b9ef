// hdrfusion scan SOURCE --out DIR: the whole method on a sequence or the synthetic sensor.
// Writes trajectory.txt, mesh.ply, renders (OpenEXR + PNG), report.json and the project
// (scan.hdrproj, or --save PATH) that --resume continues, as one set: all are replaced or
// none. If the source fails midway, Ctrl-C (or SIGTERM, SIGHUP) cancels the scan or the
// writing of its outputs, or an output cannot be written, nothing in the output folder
// changes and the model so far is kept in the recovery file.
// While it runs, the scan is autosaved to a recovery file (io/project.h) every --autosave
// seconds; a scan that finishes removes it, one that crashed leaves it to be resumed.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include "io/output_file.h"
#include "cli/commands.h"
#include "cli/interrupt.h"
#include "cli/progress.h"
#include "cli/setting_flags.h"
#include "common/error.h"
#include "io/options_json.h"
#include "io/project.h"
#include "jobs/scan_job.h"
#include "sensors/live_source.h"
#include "tonemap/operator.h"

namespace hdrf::cli {

namespace fs = std::filesystem;

namespace {

// What became of each frame, said as the scan goes: a change of state (a long loss is one
// line, not one per frame), depth beyond the ray cast, a full volume.
class FrameNarrator {
 public:
  explicit FrameNarrator(double raycast_far_m) : far_m_(raycast_far_m) {}
  void Tell(const pipeline::FrameReport& r) {
    if (r.state != last_state_ || (r.state != pipeline::FrameState::kTracked && r.why != last_why_)) {
      if (r.state == pipeline::FrameState::kTracked || (r.state == pipeline::FrameState::kRelocalised && r.fused))
        std::fprintf(stderr, "\nscan: frame %d: tracking again%s; fused\n", r.index,
                     r.state == pipeline::FrameState::kRelocalised ? " (relocalised from an earlier view)" : "");
      else
        std::fprintf(stderr, "\nscan: frame %d: %s (%s); not fused\n", r.index, pipeline::FrameStateName(r.state),
                     r.why.c_str());
    }
    last_state_ = r.state;
    last_why_ = r.why;
    // Said when a quarter of the view first lies beyond the ray cast, again only after it
    // came back within it.
    if (r.depth_beyond_far > 0.25 && !far_said_)
      std::fprintf(stderr, "\nscan: warning: frame %d: %.0f %% of the depth lies beyond %.1f m, past the model's "
                           "ray cast (volume.raycast_far_m): those surfaces are fused but tracking matches only "
                           "nearer ones\n",
                   r.index, 100 * r.depth_beyond_far, far_m_);
    far_said_ = r.depth_beyond_far > 0.25 || (far_said_ && r.depth_beyond_far > 0.1);
    if (!r.volume_full.empty())
      std::fprintf(stderr, "\nscan: warning: frame %d: the volume is full: %s. Surfaces not yet in the model are "
                           "no longer added; the model so far is kept and the scan goes on (raise "
                           "volume.max_memory_mb, or scan with larger voxels: volume.voxel_m)\n",
                   r.index, r.volume_full.c_str());
  }

 private:
  double far_m_;
  pipeline::FrameState last_state_ = pipeline::FrameState::kTracked;
  std::string last_why_;
  bool far_said_ = false;
};

struct ScanArgs {
  std::string source, out, options, response;
  int max_frames = 0;
  std::string tone = "mantiuk08";
  bool frame_to_frame = false;
  std::string save, resume;
  double autosave_s = 60;
};

// The scan job: a new one, or the saved project continued from SOURCE (refused where SOURCE
// has another camera or no frame left).
std::unique_ptr<jobs::ScanJob> MakeJob(const ScanArgs& a, const std::optional<io::Project>& project,
                                       const pipeline::PipelineOptions& o, pipeline::FrameSource& source,
                                       const fs::path& save) {
  std::unique_ptr<jobs::ScanJob> job;
  if (project) {
    job = std::make_unique<jobs::ScanJob>(*project, [&](pipeline::PipelineOptions& po) { po = o; },
                                          save.stem().string(), a.autosave_s);
    const int scanned = project->resume.frames;
    switch (job->Continue(*project, source, a.source)) {
      case jobs::ContinueFrom::kOtherCamera: {
        const PinholeCamera& pc = project->sensor.camera;
        const PinholeCamera& sc = source.sensor().camera;
        throw InputError(a.resume, "the project was scanned with a " + std::to_string(pc.width) + "x" +
                                        std::to_string(pc.height) + " camera (fx " + std::to_string(pc.fx) +
                                        "), SOURCE has a " + std::to_string(sc.width) + "x" +
                                        std::to_string(sc.height) + " one (fx " + std::to_string(sc.fx) +
                                        "): a scan goes on with the camera it began with");
      }
      case jobs::ContinueFrom::kOtherResponse:
        throw InputError(a.resume, "the project was scanned through another camera response than SOURCE gives (" +
                                        std::string(a.response.empty() ? "its sensor.json" : "--response " + a.response) +
                                        "): its radiance would not add up; continue with the response it began with");
      case jobs::ContinueFrom::kNothingLeft:
        throw InputError(a.resume, "holds " + std::to_string(scanned) + " frames, more than " +
                                        source.description() + " has: nothing left to scan");
      case jobs::ContinueFrom::kAfterScanned:
        std::fprintf(stderr, "scan: resuming %s after its %d frames\n", a.resume.c_str(), scanned);
        break;
      case jobs::ContinueFrom::kFirstFrame:
        std::fprintf(stderr, "scan: resuming %s (%d frames) from the first frame of %s: it must start where the "
                               "scan stopped (the tracker starts from the last pose)\n",
                     a.resume.c_str(), scanned, source.description().c_str());
        break;
    }
  } else {
    job = std::make_unique<jobs::ScanJob>(o, source.sensor(), save.stem().string(), a.autosave_s);
    job->SetSource(source.description(), a.source);
  }
  return job;
}

// What the job and the engine say before the first frame (recovery files pruned, the device
// chosen, settings lowered for the frame size, a GPU budget on the CPU).
void SayNotes(jobs::ScanJob& job, const pipeline::PipelineOptions& o) {
  pipeline::Pipeline& pipe = job.session().pipeline();
  if (!job.notice().empty()) std::fprintf(stderr, "scan: %s\n", job.notice().c_str());
  if (!pipe.device_note().empty()) std::fprintf(stderr, "scan: %s\n", pipe.device_note().c_str());
  if (!pipe.settings_note().empty()) std::fprintf(stderr, "scan: note: %s\n", pipe.settings_note().c_str());
  if (o.volume.gpu_memory_mb > 0 && pipe.device() != Device::kCuda)
    std::fprintf(stderr, "scan: note: volume.gpu_memory_mb applies on the GPU; on the CPU the whole model stays in "
                         "host memory (volume.max_memory_mb)\n");
}

// Up to `total` frames through the job, each told, autosaving between frames; true where an
// interrupt stopped it. A frame's exception ends the loop with its message in `failure`.
bool RunFrames(jobs::ScanJob& job, pipeline::FrameSource& source, int total, const pipeline::PipelineOptions& o,
               const StopOnInterrupt& stop, Progress& progress, std::string* failure) {
  try {
    FrameNarrator narrator(o.volume.raycast_far_m);
    pipeline::FrameInput f;
    bool autosave_failed = false;
    for (int i = 0; i < total && source.Next(f); ++i) {
      narrator.Tell(job.Process(f));
      progress.Step();
      if (const std::string e = job.Autosave(); !e.empty() && !autosave_failed) {
        std::fprintf(stderr, "\nscan: warning: autosave failed: %s (the scan goes on)\n", e.c_str());
        autosave_failed = true;
      }
      if (stop.raised()) return true;
    }
  } catch (const std::exception& e) {
    *failure = e.what();
  }
  return false;
}

}  // namespace

Command AddScanCommand(CLI::App& app) {
  auto a = std::make_shared<ScanArgs>();
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
    const fs::path out = a->out;
    io::CheckOutputFolderEarly(out);  // before the source is opened: a folder that cannot be made costs nothing
    auto source = sensors::OpenAnySource(a->source, a->response);
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) throw InputError(out, "cannot create the output folder: " + ec.message());
    for (const std::string& w : source->sensor().warnings) std::fprintf(stderr, "scan: warning: %s\n", Printable(w).c_str());
    const fs::path save = a->save.empty() ? out / "scan.hdrproj" : fs::path(a->save);
    // (p.txt was taken and written as a project that nothing would offer to open)
    if (save.extension() != io::kProjectExtension)
      throw SettingError("--save", "a project file's name ends in " + std::string(io::kProjectExtension) + ", got '" +
                                       a->save + "'");
    // An output that may not be replaced (a link, a device, a folder) is refused before the scan.
    jobs::ScanJob::CheckOutputs(out, save, a->source);
    // The folder is this scan's until it ends: a second scan into it is refused at once.
    const io::FolderLock lock(out);
    // Unfinished scans a crash left behind are offered, newest first.
    for (const fs::path& r : io::FindRecoveryFiles())
      if (project == std::nullopt || fs::absolute(r) != fs::absolute(a->resume)) {
        std::fprintf(stderr, "scan: an unfinished scan was autosaved to %s: continue it with "
                             "hdrfusion scan --resume %s SOURCE --out DIR (or delete the file)\n",
                     r.c_str(), r.c_str());
        break;
      }
    // Autosaves go to a recovery file named after the project and the start time.
    std::unique_ptr<jobs::ScanJob> job = MakeJob(*a, project, o, *source, save);
    SayNotes(*job, o);
    pipeline::ScanSession& session = job->session();
    pipeline::Pipeline& pipe = session.pipeline();
    const int left = source->size() < 0 ? -1 : source->size() - (job->same_source() ? job->continued_frames() : 0);
    const int total = a->max_frames > 0 ? (left < 0 ? a->max_frames : std::min(a->max_frames, left)) : left;
    if (total < 0)
      throw SettingError("SOURCE", "a live source runs until stopped: give frames=N in its spec or --frames N");
    std::fprintf(stderr, "scan: %s, %d frames, tracker %s, unbounded volume, %.1f mm voxels, on the %s\n",
                 source->description().c_str(), total, tracking::TrackerName(o.tracker.kind),
                 1000 * o.volume.voxel_m,
                 pipe.device() == Device::kCuda ? ("GPU: " + CudaDeviceDescription()).c_str() : "CPU");
    // Ctrl-C, SIGTERM or SIGHUP end the scan early (or cancel the writing of its outputs),
    // keeping the model it built in the recovery file.
    StopOnInterrupt stop;
    Progress progress("scan", total);
    // The loop's own time (reading the source included): the rate the studio is compared with.
    const auto loop_start = std::chrono::steady_clock::now();
    std::string failure;
    const bool stopped = RunFrames(*job, *source, total, o, stop, progress, &failure);
    progress.Done();
    const double loop_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();
    const int n = session.frames();
    if (n == 0) throw Error(failure.empty() ? "the source delivered no frames" : failure);
    if (session.count(pipeline::FrameState::kWaiting) == n && !pipe.volume_stats().allocated_bricks)
      throw Error("none of the " + std::to_string(n) + " frames could anchor the model: none had depth on at least " +
                  std::to_string(int(std::ceil(100 * o.tracker.min_anchor_depth))) +
                  " % of its pixels (tracker.min_anchor_depth); nothing was written" +
                  (failure.empty() ? "" : " (and the source failed: " + failure + ")"));
    // A scan that did not finish leaves the outputs of the last one that did exactly as they were.
    if (stopped) {
      std::fprintf(stderr, "scan: cancelled by %s after %d frames: nothing in %s was changed; %s\n", stop.name(), n,
                   a->out.c_str(), job->Keep().c_str());
      return stop.exit_status();
    }
    if (!failure.empty()) throw Error(failure + " (nothing in " + a->out + " was changed; " + job->Keep() + ")");
    jobs::OutputSummary written;
    try {
      written = job->WriteOutputs(
          out, save, tone_decl, tone_params, loop_s, [](const std::string& s) { std::fprintf(stderr, "scan: %s\n", s.c_str()); },
          [&] { return stop.raised(); });
    } catch (const Cancelled& e) {
      std::fprintf(stderr, "scan: cancelled by %s while writing the outputs: %s\n", stop.name(), e.what());
      return stop.exit_status();
    }
    const std::optional<double> exp_err = session.exposure_median_relative_error();
    std::printf("scanned %d frames (%d fused, %d lost, %d relocalisations) at %.1f frames/s (%.1f with reading the "
                "source): %zu mesh vertices, %zu triangles\n",
                n, session.fused(), session.lost(), session.relocalisations(), session.frames_per_second(),
                loop_s > 0 ? double(n) / loop_s : 0.0, written.vertices, written.triangles);
    if (exp_err) std::printf("exposure ratio vs reported: median relative error %.2f %%\n", 100 * *exp_err);
    std::printf("wrote %s/{trajectory.txt, mesh.ply, render_last.exr/png, render_first.exr/png, keyframes/ (%zu), "
                "keyframes.json, sensor.json, report.json} and the project %s\n",
                a->out.c_str(), session.keyframes().size(), save.c_str());
    return 0;
  }};
}

}  // namespace hdrf::cli
