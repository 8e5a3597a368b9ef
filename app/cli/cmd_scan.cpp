// hdrfusion scan SOURCE --out DIR: the whole method on a sequence or the synthetic sensor.
// Writes trajectory.txt, mesh.ply, renders (OpenEXR + PNG) and report.json. If the source
// fails midway, what was built so far is still written, then the error is reported.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
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
#include "io/text_table.h"
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
  cmd->add_option("--frames", a->max_frames, "Process at most this many frames");
  cmd->add_option("--tone", a->tone, "Tone mapping of the PNG renders and the PLY's display colours: OP[,key=value...] "
                                     "(see hdrfusion tonemap --list)")
      ->capture_default_str();
  auto flags = std::make_shared<SettingFlags>(cmd);
  return {cmd, [a, flags] {
    pipeline::PipelineOptions o;
    if (!a->options.empty()) io::ReadPipelineOptions(a->options, o);
    if (a->frame_to_frame) o.tracker.frame_to_model = false;
    flags->Apply(o);
    o.Check();
    // The tone mapping is checked before scanning: a typo must not cost a scan.
    const tonemap::Spec tone_spec = tonemap::ParseSpec(a->tone);
    const tonemap::OperatorDecl& tone_decl = tonemap::FindOperator(tone_spec.op);
    const tonemap::Params tone_params = tonemap::ResolveParams(tone_decl, tone_spec.values);
    auto source = sensors::OpenAnySource(a->source, a->response);
    const fs::path out = a->out;
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) throw InputError(out, "cannot create the output folder: " + ec.message());
    for (const std::string& w : source->sensor().warnings) std::fprintf(stderr, "scan: warning: %s\n", w.c_str());
    pipeline::ScanSession session(o, source->sensor().camera, source->sensor());
    pipeline::Pipeline& pipe = session.pipeline();
    if (!pipe.device_note().empty()) std::fprintf(stderr, "scan: %s\n", pipe.device_note().c_str());
    const int total = a->max_frames > 0 ? (source->size() < 0 ? a->max_frames : std::min(a->max_frames, source->size()))
                                        : source->size();
    if (total < 0)
      throw SettingError("SOURCE", "a live source runs until stopped: give frames=N in its spec or --max-frames N");
    std::fprintf(stderr, "scan: %s, %d frames, tracker %s, volume %d^3 over %.2f m (voxel %.1f mm), on the %s\n",
                 source->description().c_str(), total, tracking::TrackerName(o.tracker.kind),
                 o.volume.resolution, o.volume.size_m, 1000 * o.volume.voxel_m(),
                 pipe.device() == Device::kCuda ? ("GPU: " + CudaDeviceDescription()).c_str() : "CPU");
    json frames = json::array();
    std::string failure;
    Progress progress("scan", total);
    try {
      pipeline::FrameInput f;
      for (int i = 0; i < total && source->Next(f); ++i) {
        const pipeline::FrameReport& r = session.Process(f);
        json fr = {{"index", r.index},
                   {"timestamp", r.timestamp},
                   {"ms", {{"convert", r.ms.convert}, {"normalize", r.ms.normalize}, {"track", r.ms.track},
                           {"compensate", r.ms.compensate}, {"integrate", r.ms.integrate}, {"raycast", r.ms.raycast}}},
                   {"tracking", {{"lost", r.tracking.lost}, {"why", r.tracking.why},
                                 {"inlier_share", r.tracking.inlier_share}, {"condition", r.tracking.condition},
                                 {"rms_icp_m", r.tracking.rms_icp_m}, {"rms_photo", r.tracking.rms_photo},
                                 {"iterations", r.tracking.iterations}}},
                   {"fused", r.fused},
                   {"exposure", {{"estimated_ratio", r.exposure_ratio}, {"samples", r.exposure_samples}}}};
        if (r.exposure_ratio_reported) fr["exposure"]["reported_ratio"] = *r.exposure_ratio_reported;
        frames.push_back(fr);
        if (r.tracking.lost)
          std::fprintf(stderr, "\nscan: frame %d: tracking lost (%s); not fused\n", r.index, r.tracking.why.c_str());
        progress.Step();
      }
    } catch (const std::exception& e) {
      failure = e.what();
    }
    progress.Done();
    const int n = session.frames();
    if (n == 0) throw Error(failure.empty() ? "the source delivered no frames" : failure);
    // Outputs: everything built so far.
    std::vector<io::TimedPose> trajectory;
    for (const pipeline::FrameReport& r : session.reports()) trajectory.push_back({r.timestamp, r.T_world_camera});
    io::WriteTrajectory(out / "trajectory.txt", trajectory);
    // The keyframes (colour, pose, exposure ratio) and the sensor: what export bakes textures from.
    io::WriteKeyframes(out, session.keyframes(), session.sensor(), o.pcf);
    std::fprintf(stderr, "scan: extracting the mesh...\n");
    const mesh::Mesh m = pipe.ExtractMesh();
    // Renders and the mesh's display colours through one operator instance: the mesh takes
    // the curve of the last render (as the studio's 3-D view takes the model view's).
    const io::OcioDisplay ocio;
    auto tone = tone_decl.make(tone_params, Device::kCpu);
    WriteRender(out, "render_first", pipe.Render(Pose::Identity()), Pose::Identity(), *tone, ocio);
    WriteRender(out, "render_last", pipe.Render(pipe.pose()), pipe.pose(), *tone, ocio);
    const std::vector<Rgb8> display = ocio.Encode(tone->MapList(m.radiance));
    io::WritePly(out / "mesh.ply", m, m.radiance.size() == m.position.size() ? &display : nullptr);
    const pipeline::StageTimes mean = session.mean_ms();
    const pipeline::VolumeStats vs = pipe.volume_stats();
    const int lost = session.lost();
    const std::optional<double> exp_err = session.exposure_median_relative_error();
    json report = {{"source", source->description()},
                   {"device", DeviceName(pipe.device())},
                   {"frames", n},
                   {"lost_frames", lost},
                   {"options", json::parse(io::PipelineOptionsToJson(o))},
                   {"mean_ms", {{"convert", mean.convert}, {"normalize", mean.normalize}, {"track", mean.track},
                                {"compensate", mean.compensate}, {"integrate", mean.integrate},
                                {"raycast", mean.raycast}, {"total", mean.total()}}},
                   {"fps", session.frames_per_second()},
                   {"volume", {{"allocated_bricks", vs.allocated_bricks}, {"bytes", vs.bytes}, {"full", vs.full}}},
                   {"mesh", {{"vertices", m.position.size()}, {"triangles", m.triangles.size()}}},
                   {"frames_detail", frames}};
    if (exp_err) report["exposure_median_relative_error"] = *exp_err;
    if (!failure.empty()) report["error"] = failure;
    io::WriteFileAtomically(out / "report.json", report.dump(1) + "\n");
    std::printf("scanned %d frames (%d lost) at %.1f frames/s: %zu mesh vertices, %zu triangles\n", n, lost,
                session.frames_per_second(), m.position.size(), m.triangles.size());
    if (exp_err) std::printf("exposure ratio vs reported: median relative error %.2f %%\n", 100 * *exp_err);
    std::printf("wrote %s/{trajectory.txt, mesh.ply, render_last.exr/png, render_first.exr/png, keyframes/ (%zu), "
                "keyframes.json, sensor.json, report.json}\n",
                a->out.c_str(), session.keyframes().size());
    if (!failure.empty())
      throw Error(failure + " (the model of the " + std::to_string(n) + " frames processed was saved in " + a->out + ")");
    return 0;
  }};
}

}  // namespace hdrf::cli
