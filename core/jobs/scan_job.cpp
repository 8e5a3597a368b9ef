#include "jobs/scan_job.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/message.h"
#include "io/exr.h"
#include "io/image_io.h"
#include "io/keyframes_io.h"
#include "io/ocio_display.h"
#include "io/options_json.h"
#include "io/output_file.h"
#include "io/ply.h"
#include "io/tum.h"
#include "tonemap/display.h"

namespace hdrf::jobs {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The normals as a grey shading seen from the camera (light from behind it).
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

// A render as OpenEXR radiance, its PNG through the operator and the OpenColorIO display
// transform, and its normals shaded.
void WriteRender(const fs::path& dir, const std::string& name, const volume::Volume::Rendering& r, const Pose& T,
                 tonemap::Operator& tone, const io::OcioDisplay& ocio) {
  io::WriteExr(dir / (name + ".exr"), r.radiance, io::ExrPrecision::kHalf);
  Image<Float3> shown;
  tone.Map(r.radiance, shown, tonemap::FrameTime::Still());
  ocio.Apply(shown);
  io::WriteColorPng(dir / (name + ".png"), io::OcioDisplay::Quantise(shown));
  io::WriteColorPng(dir / (name + "_normals.png"), ShadeNormals(r.normal, T));
}

json Report(pipeline::ScanSession& session, const std::string& source, const fs::path& project, double loop_s,
            const OutputSummary& mesh) {
  pipeline::Pipeline& pipe = session.pipeline();
  const int n = session.frames();
  json frames = json::array();
  for (const pipeline::FrameReport& r : session.reports()) frames.push_back(io::FrameReportToJson(r));
  const pipeline::StageTimes mean = session.mean_ms();
  const pipeline::VolumeStats vs = pipe.volume_stats();
  json report = {{"source", source},
                 {"device", DeviceName(pipe.device())},
                 {"frames", n},
                 {"lost_frames", session.lost()},
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
                             {"full_reason", vs.full_reason}, {"voxel_m", pipe.options().volume.voxel_m},
                             {"gpu_bricks", vs.streaming.gpu_bricks}, {"host_bricks", vs.streaming.host_bricks},
                             {"gpu_bytes", vs.streaming.gpu_bytes}, {"swapped_out", vs.streaming.swapped_out},
                             {"swapped_in", vs.streaming.swapped_in}}},
                 {"mesh", {{"vertices", mesh.vertices}, {"triangles", mesh.triangles}}},
                 {"project", project.string()},
                 {"frames_detail", frames}};
  if (const std::optional<double> e = session.exposure_median_relative_error()) report["exposure_median_relative_error"] = *e;
  return report;
}

}  // namespace

ScanJob::ScanJob(const pipeline::PipelineOptions& options, const SensorInfo& sensor, const std::string& name,
                 double autosave_s)
    : session_(std::make_unique<pipeline::ScanSession>(options, sensor.camera, sensor)),
      recovery_(io::NewRecoveryFile(name)),
      autosave_s_(autosave_s),
      autosave_time_(std::chrono::steady_clock::now()) {
  Prune({});
}

ScanJob::ScanJob(const io::Project& project, const std::function<void(pipeline::PipelineOptions&)>& adjust,
                 const std::string& name, double autosave_s)
    : session_(io::ResumeSession(project, adjust)),
      recovery_(io::NewRecoveryFile(name)),
      autosave_s_(autosave_s),
      autosave_time_(std::chrono::steady_clock::now()),
      saved_frames_(session_->frames()),
      saved_by_user_(session_->frames()),
      source_(project.source),
      spec_(project.source_spec),
      continued_frames_(project.resume.frames) {
  Prune(project.file);
}

void ScanJob::Prune(const fs::path& in_use) {
  const io::RecoveryLimits limits;
  const io::RecoveryPrune p = io::PruneRecoveryFiles(limits, in_use);
  if (p.removed == 0) return;
  notice_ = Say(words::kRecoveryPruned,
                {std::to_string(p.removed), Num(double(p.bytes) / (1 << 20), 1), io::RecoveryFolder().string(),
                 std::to_string(limits.max_age_days), std::to_string(limits.max_files),
                 std::to_string(limits.max_bytes >> 30)});
}

void ScanJob::SetSource(const std::string& description, const std::string& spec) {
  source_ = description;
  spec_ = spec;
}

ContinueFrom ScanJob::Continue(const io::Project& project, pipeline::FrameSource& source, const std::string& spec) {
  if (!io::SameCamera(source.sensor().camera, project.sensor.camera)) return ContinueFrom::kOtherCamera;
  const auto& a = source.sensor().response;
  const auto& b = project.sensor.response;
  if (a.has_value() != b.has_value() || (a && !io::SameResponse(*a, *b))) return ContinueFrom::kOtherResponse;
  same_source_ = io::SameSource(project, spec, source.description());
  spec_ = same_source_ && !project.source_spec.empty() ? project.source_spec : spec;
  // The same bounded source goes on where the scan stopped.
  if (!same_source_ || source.size() < 0) return ContinueFrom::kFirstFrame;
  return source.Skip(project.resume.frames) ? ContinueFrom::kAfterScanned : ContinueFrom::kNothingLeft;
}

void ScanJob::SaveRecovery() {
  fs::create_directories(recovery_.parent_path());
  io::SaveProject(recovery_, *session_, Info(false));
  saved_frames_ = session_->frames();
}

std::string ScanJob::Autosave(bool force) {
  const int frames = session_->frames();
  if (frames == 0 || frames == saved_frames_) return {};
  const auto now = std::chrono::steady_clock::now();
  if (!force && (autosave_s_ <= 0 || std::chrono::duration<double>(now - autosave_time_).count() < autosave_s_)) return {};
  autosave_time_ = now;
  try {
    SaveRecovery();
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
}

void ScanJob::Save(const fs::path& file, bool finished) {
  io::SaveProject(file, *session_, Info(finished));
  saved_frames_ = saved_by_user_ = session_->frames();
  DropRecovery();
}

std::string ScanJob::Keep() {
  try {
    SaveRecovery();
  } catch (const std::exception& e) {
    return "the model could not be kept either: " + std::string(e.what());
  }
  const std::string r = recovery_.string();
  return "the " + std::to_string(session_->frames()) + " frames scanned are kept in " + r +
         ": export them with `hdrfusion export " + r + " --out DIR`, or go on with `hdrfusion scan --resume " + r +
         " SOURCE --out DIR`";
}

void ScanJob::Close() {
  if (session_->frames() > saved_by_user_) Autosave(true);
  else DropRecovery();
}

void ScanJob::DropRecovery() {
  std::error_code ec;
  fs::remove(recovery_, ec);
}

void ScanJob::CheckOutputs(const fs::path& out, const fs::path& project, const std::string& source_spec) {
  if (io::IsWithin(out, source_spec))
    throw InputError(out, "is the recording the scan reads: its outputs (sensor.json, trajectory.txt, ...) would "
                          "replace the recording's own files; choose another --out");
  if (io::IsWithin(project, source_spec))
    throw InputError(project, "is in the recording the scan reads; choose another project file");
  io::CheckReplaceable(project);
  io::CheckOutputFolder(out / "keyframes");
  for (const char* f : {"trajectory.txt", "mesh.ply", "report.json", "keyframes.json", "sensor.json", "render_first.exr",
                        "render_first.png", "render_first_normals.png", "render_last.exr", "render_last.png",
                        "render_last_normals.png"})
    io::CheckReplaceable(out / f);
}

OutputSummary ScanJob::WriteOutputs(const fs::path& out, const fs::path& project, const tonemap::OperatorDecl& tone_decl,
                                    const tonemap::Params& tone_params, double loop_s,
                                    const std::function<void(const std::string&)>& say,
                                    const std::function<bool()>& cancelled) {
  pipeline::ScanSession& session = *session_;
  pipeline::Pipeline& pipe = session.pipeline();
  OutputSummary summary;
  const auto check = [&] {
    if (cancelled && cancelled()) throw Cancelled();
  };
  // All outputs are one set: written beside their targets, and moved into place only when
  // every one of them is complete (a full disk or a failed mesh changes nothing).
  try {
    io::OutputSet outputs;
    check();
    // The project first: the model is the most expensive thing to lose.
    const auto save_start = std::chrono::steady_clock::now();
    io::SaveProject(project, session, Info(true));
    if (say) {
      char took[64];
      std::snprintf(took, sizeof took, "wrote the project (%.2f s)",
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - save_start).count());
      say(took);
    }
    std::vector<io::TimedPose> trajectory;
    for (const pipeline::FrameReport& r : session.reports()) trajectory.push_back({r.timestamp, r.T_world_camera});
    io::WriteTrajectory(out / "trajectory.txt", trajectory);
    // The keyframes (colour, pose, exposure ratio) and the sensor: what export bakes textures from.
    io::WriteKeyframes(out, session.keyframes(), session.sensor(), pipe.options().pcf);
    check();
    if (say) say("extracting the mesh...");
    const mesh::Mesh m = pipe.ExtractMesh([&](double) { return !(cancelled && cancelled()); });
    summary.vertices = m.position.size();
    summary.triangles = m.triangles.size();
    // Renders and the mesh's display colours through one operator instance: the mesh takes
    // the curve of the last render (as the studio's 3-D view takes the model view's).
    const io::OcioDisplay ocio;
    auto tone = tone_decl.make(tone_params, Device::kCpu);
    check();
    WriteRender(out, "render_first", pipe.Render(Pose::Identity()), Pose::Identity(), *tone, ocio);
    WriteRender(out, "render_last", pipe.Render(pipe.pose()), pipe.pose(), *tone, ocio);
    const std::vector<Rgb8> display = ocio.Encode(tone->MapList(m.radiance));
    io::WritePly(out / "mesh.ply", m, m.radiance.size() == m.position.size() ? &display : nullptr);
    io::WriteFileAtomically(out / "report.json", Report(session, source_, project, loop_s, summary).dump(1) + "\n");
    check();
    outputs.Commit();
  } catch (const Cancelled&) {
    throw Cancelled("nothing in " + out.string() + " was changed; " + Keep());
  } catch (const std::exception& e) {
    throw Error(std::string(e.what()) + " (nothing in " + out.string() + " was changed; " + Keep() + ")");
  }
  saved_frames_ = saved_by_user_ = session.frames();
  DropRecovery();
  return summary;
}

}  // namespace hdrf::jobs
