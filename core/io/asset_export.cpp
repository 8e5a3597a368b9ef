#include "common/host_memory.h"
#include "io/asset_export.h"

#include "io/project.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <random>

#include "common/error.h"
#include "common/message.h"
#include "io/exr.h"
#include "io/gltf.h"
#include "io/image_io.h"
#include "io/obj.h"
#include "io/ocio_display.h"
#include "io/ply.h"
#include "io/simplify.h"
#include "io/output_file.h"
#include "io/tum.h"
#include "tonemap/operator.h"

namespace hdrf::io {

namespace fs = std::filesystem;
using nlohmann::json;

void AssetOptions::Check() const {
  clean_options.Check();
  atlas.Check();
  bake.Check();
  const tonemap::Spec spec = tonemap::ParseSpec(tone);
  tonemap::ResolveParams(tonemap::FindOperator(spec.op), spec.values);
  if (crop && !(crop->min.x < crop->max.x && crop->min.y < crop->max.y && crop->min.z < crop->max.z))
    throw SettingError("crop", "each minimum must be below its maximum");
  if ((obj || glb) && !texture) throw SettingError("formats", "OBJ and glTF carry the texture: they need texturing on");
  if (!ply && !obj && !glb) throw SettingError("formats", "choose at least one of ply, obj, gltf");
  if ((render_width > 0) != (render_height > 0) || render_width < 0 || render_height < 0 || render_width > 16384 ||
      render_height > 16384)
    throw SettingError("render", "the size must be WxH with both 1 to 16384");
  if (render_frame < 0) throw SettingError("render frame", "must be 0 or more");
}

ScanData LoadScan(const fs::path& in) {
  ScanData s;
  s.source = in;
  if (in.extension() == kProjectExtension) {
    // A project: the mesh extracted from its model, the model rendered from the last pose.
    Project p = LoadProject(in);
    s.mesh = mesh::ExtractMesh(p.model);
    if (s.mesh.triangles.empty()) throw InputError(in, "the model holds no surface: nothing to export");
    s.tone_reference = p.model.Raycast(p.sensor.camera, p.resume.pose).radiance;
    KeyframeSet ks;
    ks.keyframes = std::move(p.keyframes);
    ks.sensor = p.sensor;
    ks.pcf_power = p.options.pcf;
    s.keyframes = std::move(ks);
    for (const pipeline::FrameReport& r : p.reports) s.trajectory.push_back(r.T_world_camera);
    return s;
  }
  const bool dir = fs::is_directory(in);
  const fs::path ply = dir ? in / "mesh.ply" : in;
  if (!fs::exists(ply))
    throw InputError(ply, dir ? "no mesh.ply in this folder (is it a scan output folder?)" : "file is missing");
  s.mesh = ReadPly(ply);
  if (s.mesh.triangles.empty()) throw InputError(ply, "holds no triangles: nothing to export");
  if (dir) {
    if (fs::exists(in / "render_last.exr")) s.tone_reference = ReadExr(in / "render_last.exr");
    if (HasKeyframes(in)) s.keyframes = ReadKeyframes(in);
    if (fs::exists(in / "trajectory.txt"))
      for (const TimedPose& p : ReadTrajectory(in / "trajectory.txt")) s.trajectory.push_back(p.T_world_camera);
  }
  return s;
}

ScanData ScanDataFromSession(pipeline::ScanSession& session, const std::string& source,
                             const std::function<bool(double)>& progress) {
  ScanData scan;
  scan.source = source;
  scan.mesh = session.pipeline().ExtractMesh(progress);
  if (scan.mesh.triangles.empty()) throw Error("the model has no surface yet");
  scan.tone_reference = session.pipeline().Render(session.pipeline().pose()).radiance;
  KeyframeSet ks;
  for (const pipeline::Keyframe& k : session.keyframes())
    ks.keyframes.push_back({k.index, k.timestamp, k.T_world_camera, k.exposure_ratio, k.color.Clone()});
  ks.sensor = session.sensor();
  ks.pcf_power = session.pipeline().options().pcf;
  scan.keyframes = std::move(ks);
  scan.trajectory = session.poses();
  return scan;
}

std::string AssetResult::Summary() const {
  char line[512];
  std::string s;
  std::snprintf(line, sizeof line, "%zu vertices, %zu triangles", vertices, triangles);
  s += line;
  if (atlas_width > 0) {
    const long surface = texels_from_frames + texels_from_volume;
    std::snprintf(line, sizeof line, "; texture %dx%d at %.2f mm per texel, %.1f %% of the surface from the frames",
                  atlas_width, atlas_height, texel_mm, surface > 0 ? 100.0 * double(texels_from_frames) / double(surface) : 0.0);
    s += line;
  }
  std::snprintf(line, sizeof line, " (%.1f s)", seconds);
  return s + line;
}

namespace {

// A private folder inside `out` for the files being written; removed unless committed.
class Staging {
 public:
  explicit Staging(const fs::path& out) : out_(out) {
    fs::create_directories(out);
    std::random_device rd;
    for (int attempt = 0; attempt < 16; ++attempt) {
      char name[64];
      std::snprintf(name, sizeof name, ".export-%d-%08x", int(getpid()), unsigned(rd()));
      std::error_code ec;
      if (fs::create_directory(out / name, ec)) {
        dir_ = out / name;
        return;
      }
    }
    throw InputError(out, "cannot create a staging folder inside it");
  }
  ~Staging() {
    std::error_code ec;
    if (!dir_.empty()) fs::remove_all(dir_, ec);
  }
  fs::path operator/(const std::string& name) const { return dir_ / name; }
  void Commit(const std::vector<std::string>& files) {
    // Everything that can be checked before the first file moves: a half-replaced set would
    // mix two exports.
    for (const std::string& f : files) CheckReplaceable(out_ / f);
    for (const std::string& f : files) {
      if (fs::path(f).has_parent_path()) fs::create_directories(out_ / fs::path(f).parent_path());
      std::error_code ec;
      fs::rename(dir_ / f, out_ / f, ec);
      if (ec) throw InputError(out_ / f, "cannot be moved into place: " + ec.message());
    }
  }

 private:
  fs::path out_, dir_;
};

ColorImage Encode(const std::vector<Float3>& display, int w, int h, const OcioDisplay& ocio) {
  const std::vector<Rgb8> rgb = ocio.Encode(display);
  ColorImage img(w, h);
  for (std::size_t i = 0; i < rgb.size(); ++i) img[i] = rgb[i];
  return img;
}

json Matrix(const Eigen::Matrix4d& T) {
  json a = json::array();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) a.push_back(T(i, j));
  return a;
}

// The camera of a render at any size: the scan camera's field of view along the height.
PinholeCamera RenderCamera(const PinholeCamera& scan, int w, int h) {
  const float s = float(h) / float(scan.height);
  return {w, h, scan.fy * s * (scan.fx / scan.fy), scan.fy * s, 0.5f * float(w) - 0.5f, 0.5f * float(h) - 0.5f};
}

// The mesh an export writes: cleaned (or only levelled), in the output's world frame,
// cropped and simplified as asked.
struct PreparedMesh {
  mesh::CleanMesh c;
  mesh::WorldFrame wf;
  double simplify_error = 0;
  std::size_t before_simplify = 0;
};
PreparedMesh PrepareMesh(const ScanData& scan, const AssetOptions& o) {
  PreparedMesh p;
  mesh::CleanOptions co = o.clean_options;
  if (!o.clean) co.min_piece_area = 0, co.max_hole_perimeter = 0, co.weld_tolerance = 0, co.fill_radiance = false;
  if (scan.mesh.triangles.empty())
    throw InputError(scan.source, "the scan's mesh has no triangles: there is nothing to export");
  p.c = mesh::Clean(scan.mesh, co);
  mesh::CleanMesh& c = p.c;
  // Said here, naming the setting: an empty mesh would reach the texture writer as a 0x0 image.
  if (c.mesh.triangles.empty())
    throw SettingError("min-piece-area", "nothing is left after the clean-up: every piece of the mesh is smaller than " +
                                             Sig(co.min_piece_area, 4) + " m² (export keeps pieces at least that large)");
  const mesh::WorldFrame& wf = p.wf;
  mesh::WorldFrameOptions wo;
  wo.up = o.up;
  p.wf = mesh::EstimateWorldFrame(c.mesh, wo);
  mesh::TransformMesh(c.mesh, wf.transform);
  if (o.crop) {
    mesh::CleanOptions only_crop;
    only_crop.weld_tolerance = 0, only_crop.min_piece_area = 0, only_crop.max_hole_perimeter = 0, only_crop.fill_radiance = false;
    only_crop.crop = o.crop;
    mesh::CleanMesh cc = mesh::Clean(c.mesh, only_crop);
    std::vector<std::uint8_t> flags(cc.mesh.position.size());
    for (std::size_t v = 0; v < flags.size(); ++v) flags[v] = c.radiance_filled[std::size_t(cc.source[v])];
    c.report.cropped = cc.report.cropped;
    c.mesh = std::move(cc.mesh);
    c.radiance_filled = std::move(flags);
    if (c.mesh.triangles.empty()) throw SettingError("crop", "the box holds none of the mesh (" + wf.Describe() + ")");
  }
  p.before_simplify = c.mesh.triangles.size();
  if (o.triangles > 0) {
    SimplifyResult s = Simplify(c.mesh, o.triangles);
    std::vector<std::uint8_t> flags(s.mesh.position.size());
    for (std::size_t v = 0; v < flags.size(); ++v) flags[v] = c.radiance_filled[std::size_t(s.source[v])];
    c.mesh = std::move(s.mesh);
    c.radiance_filled = std::move(flags);
    p.simplify_error = s.error_m;
  }
  return p;
}

// The atlas of the mesh and its texture baked from the scan's keyframes (views placed in
// the output's frame); the figures into `res`, and the operator's tone curve from the texture
// where the scan has no render to take it from.
struct AssetTexture {
  std::optional<mesh::Atlas> atlas;
  std::optional<mesh::BakedTexture> baked;
};
AssetTexture MakeTexture(const ScanData& scan, const AssetOptions& o, const mesh::Mesh& m, const mesh::WorldFrame& wf,
                         tonemap::Operator& op, const std::function<bool(const std::string&, double)>& progress,
                         AssetResult& res) {
  AssetTexture t;
  if (!o.texture) return t;
  t.atlas = mesh::BuildAtlas(m, o.atlas, [&](double f) { return !progress || progress("UV atlas", 0.1 + 0.15 * f); });
  std::vector<mesh::BakeView> views;
  if (scan.keyframes && !scan.keyframes->keyframes.empty()) {
    if (progress && !progress("keyframes", 0.25)) throw Cancelled();
    views = pipeline::MakeBakeViews(scan.keyframes->keyframes, scan.keyframes->sensor, scan.keyframes->pcf_power);
    for (mesh::BakeView& v : views) v.T_world_camera = Pose(wf.transform) * v.T_world_camera;
  } else {
    res.warnings.push_back(Say(words::kNoKeyframes));
  }
  t.baked = mesh::BakeTexture(*t.atlas, views, o.bake, [&](double f) { return !progress || progress("texture", 0.3 + 0.5 * f); });
  res.atlas_width = t.atlas->width;
  res.atlas_height = t.atlas->height;
  res.texel_mm = t.atlas->texel_m * 1000;
  res.texels_from_frames = t.baked->from_frames;
  res.texels_from_volume = t.baked->from_volume;
  if (!scan.tone_reference) {
    Image<Float3> shown;
    op.Map(t.baked->radiance, shown, tonemap::FrameTime::Still());
  }
  return t;
}

// The record of an export (export.json, without its list of files).
json ExportReport(const ScanData& scan, const AssetOptions& o, const tonemap::Spec& spec, const std::string& units,
                  const PreparedMesh& p, const AssetTexture& t, const AssetResult& res) {
  const mesh::CleanReport& r = p.c.report;
  const mesh::Mesh& m = p.c.mesh;
  const mesh::WorldFrame& wf = p.wf;
  json report = {
      {"source", scan.source.string()},
      {"up_axis", o.up == mesh::UpAxis::kZ ? "z" : "y"},
      {"transform_output_from_model", Matrix(wf.transform)},
      {"transform_note", "row-major 4x4; model = the first camera's frame (x right, y down, z forward), metres; "
                         "mesh.glb is Y-up as glTF requires (a Z-up export is turned (x,y,z) -> (x,z,-y) in it)"},
      {"world_frame", wf.Describe()},
      {"floor_found", wf.floor_found},
      {"tone_mapping", tonemap::FormatSpec(spec)},
      {"radiance_units", units},
      {"vertices", m.position.size()},
      {"triangles", m.triangles.size()},
      {"simplify", {{"budget", o.triangles}, {"triangles_before", p.before_simplify}, {"error_m", p.simplify_error}}},
      {"clean", {{"welded", r.welded}, {"degenerate_removed", r.degenerate_removed}, {"duplicate_removed", r.duplicate_removed},
                 {"cropped", r.cropped}, {"pieces_kept", r.pieces_kept}, {"pieces_removed", r.pieces_removed},
                 {"holes_filled", r.holes_filled}, {"holes_left", r.holes_left}, {"radiance_filled", r.radiance_filled},
                 {"radiance_missing", r.radiance_missing}}},
      {"warnings", res.warnings}};
  if (t.atlas)
    report["texture"] = {{"width", t.atlas->width}, {"height", t.atlas->height}, {"texel_mm", t.atlas->texel_m * 1000},
                         {"charts", t.atlas->charts.size()}, {"overlap_splits", t.atlas->overlap_splits},
                         {"padding", t.atlas->padding}, {"textured_vertices", t.atlas->mesh.position.size()},
                         {"keyframes", scan.keyframes ? scan.keyframes->keyframes.size() : 0},
                         {"surface_texels", t.baked->surface_texels}, {"texels_from_frames", t.baked->from_frames},
                         {"texels_from_volume", t.baked->from_volume}, {"mean_frames_per_texel", t.baked->mean_views},
                         {"sample_sigma_px", o.bake.sample_sigma_px}};
  if (o.render_width > 0) report["render"] = {{"width", o.render_width}, {"height", o.render_height}, {"frame", o.render_frame}};
  return report;
}

}  // namespace

AssetResult ExportAsset(const ScanData& scan, const AssetOptions& o, const fs::path& out,
                        const std::function<bool(const std::string&, double)>& progress) {
  o.Check();
  const auto t0 = std::chrono::steady_clock::now();
  const auto tick = [&](const std::string& stage, double f) {
    if (progress && !progress(stage, f)) throw Cancelled();
  };
  AssetResult res;
  const tonemap::Spec spec = tonemap::ParseSpec(o.tone);
  const auto& decl = tonemap::FindOperator(spec.op);
  auto op = decl.make(tonemap::ResolveParams(decl, spec.values), Device::kCpu);
  PinholeCamera camera;
  if (scan.keyframes) camera = scan.keyframes->sensor.camera;
  if ((o.render_width > 0) && !camera.Valid())
    throw SettingError("render", "renders need the scan's camera (keyframes.json and sensor.json in the scan folder)");
  // A render's memory, checked before any work: 16384 x 16384 is allowed and needs about
  // 28 GB (the radiance, alpha and depth images, the rasteriser's buffers and the encoders'
  // copies: about 104 bytes a pixel).
  if (o.render_width > 0) {
    const std::uint64_t need = std::uint64_t(o.render_width) * std::uint64_t(o.render_height) * kRenderBytesPerPixel;
    if (const auto free = AvailableHostBytes(); free && need > *free)
      throw SettingError("render", "a " + std::to_string(o.render_width) + "x" + std::to_string(o.render_height) +
                                       " render needs about " + std::to_string((need + (1u << 30) - 1) >> 30) +
                                       " GiB of memory, and the machine has " + std::to_string(*free >> 30) +
                                       " GiB free: render a smaller size");
  }
  // Checked whether or not a render is asked for: the pose is looked up either way.
  if (o.render_frame >= int(std::max<std::size_t>(1, scan.trajectory.size())))
    throw SettingError("render frame", "is " + std::to_string(o.render_frame) + ", but the scan has " +
                                           std::to_string(scan.trajectory.size()) + " poses (frames 0 to " +
                                           std::to_string(std::max<std::size_t>(1, scan.trajectory.size()) - 1) + ")");
  // 1. Clean-up, world frame, crop, simplification.
  tick("clean-up", 0.0);
  PreparedMesh p = PrepareMesh(scan, o);
  mesh::CleanMesh& c = p.c;
  const mesh::WorldFrame& wf = p.wf;
  tick("clean-up", 0.1);
  // The tone curve: the scan's last render where there is one.
  if (scan.tone_reference) {
    Image<Float3> shown;
    op->Map(*scan.tone_reference, shown, tonemap::FrameTime::Still());
  }
  const OcioDisplay ocio;
  // 2. Atlas and texture.
  AssetTexture tex = MakeTexture(scan, o, c.mesh, wf, *op, progress, res);
  std::optional<mesh::Atlas>& atlas = tex.atlas;
  std::optional<mesh::BakedTexture>& baked = tex.baked;
  tick("writing", 0.8);
  Staging stage(out);
  std::vector<std::string> files;
  const std::string units =
      "linear radiance in the scan's model units: the first frame's sensor radiance (the inverse camera response's "
      "output), every other frame scaled to it by its estimated exposure ratio";
  if (o.ply) {
    const std::vector<Rgb8> display = ocio.Encode(op->MapList(c.mesh.radiance));
    WritePly(stage / "mesh.ply", c.mesh, &display, &c.radiance_filled);
    files.push_back("mesh.ply");
  }
  std::vector<std::uint8_t> texture_png;
  if (atlas) {
    ExrWriteOptions eo;
    eo.precision = ExrPrecision::kHalf;
    eo.attributes = {{"hdrfusion:units", units},
                     {"hdrfusion:texel_mm", std::to_string(atlas->texel_m * 1000)},
                     {"hdrfusion:source", scan.source.string()}};
    WriteExr(stage / "texture.exr", baked->radiance, eo);
    // Encoded once: texture.png and the glTF's embedded base colour are the same bytes.
    texture_png = EncodeColorPng(
        Encode(op->MapList(std::vector<Float3>(baked->radiance.data(), baked->radiance.data() + baked->radiance.size())),
               atlas->width, atlas->height, ocio));
    WriteFileAtomically(stage / "texture.png", std::string(texture_png.begin(), texture_png.end()));
    files.insert(files.end(), {"texture.exr", "texture.png"});
    tick("writing", 0.85);
  }
  if (o.obj) {
    WriteObj(stage / "mesh.obj", *atlas, {{"mesh.mtl", "texture.exr"}, {"mesh_display.mtl", "texture.png"}},
             {"HDRFusion Studio export of " + scan.source.string(), wf.Describe(),
              "map_Kd of mesh.mtl: texture.exr (" + units + "); mesh_display.mtl: texture.png (tone-mapped)"});
    files.insert(files.end(), {"mesh.obj", "mesh.mtl", "mesh_display.mtl"});
    tick("writing", 0.9);
  }
  if (o.glb) {
    WriteGlb(stage / "mesh.glb", *atlas, texture_png, o.up, units);
    files.push_back("mesh.glb");
  }
  tick("writing", 0.95);
  // Renders: the textured mesh (or the vertex radiance) from a pose of the scan.
  const Pose T_render = Pose(wf.transform) * (scan.trajectory.empty() ? Pose::Identity() : scan.trajectory[std::size_t(o.render_frame)]);
  const auto render = [&](int w, int h) {
    mesh::Atlas plain;
    const mesh::Atlas* a = atlas ? &*atlas : nullptr;
    if (!a) {
      plain.mesh = c.mesh;
      a = &plain;
    }
    static const RadianceImage none;
    return mesh::RenderTextured(*a, atlas ? baked->radiance : none, T_render, RenderCamera(camera, w, h));
  };
  const auto shade = [&](const mesh::TexturedRender& r) {
    std::vector<Float3> list(r.radiance.data(), r.radiance.data() + r.radiance.size());
    ColorImage img = Encode(op->MapList(list), r.radiance.width(), r.radiance.height(), ocio);
    for (std::size_t i = 0; i < img.size(); ++i)
      if (r.alpha[i] == 0) img[i] = {0, 0, 0};
    return img;
  };
  if (o.render_width > 0) {
    const mesh::TexturedRender r = render(o.render_width, o.render_height);
    ExrWriteOptions eo;
    eo.precision = ExrPrecision::kHalf;
    eo.extra = {{"A", &r.alpha, ExrPrecision::kHalf}, {"Z", &r.depth, ExrPrecision::kFloat}};
    eo.attributes = {{"hdrfusion:units", units}, {"hdrfusion:depth", "Z: metres along the camera's axis, 0 = empty"}};
    WriteExr(stage / "render.exr", r.radiance, eo);
    WriteColorPng(stage / "render.png", shade(r));
    files.insert(files.end(), {"render.exr", "render.png"});
  }
  if (camera.Valid()) res.preview = shade(render(480, std::max(1, 480 * camera.height / camera.width)));
  // The record of it all.
  json report = ExportReport(scan, o, spec, units, p, tex, res);
  files.push_back("export.json");
  report["files"] = files;
  res.report_json = report.dump(1) + "\n";
  WriteFileAtomically(stage / "export.json", res.report_json);
  stage.Commit(files);
  res.files = files;
  res.vertices = c.mesh.position.size();
  res.triangles = c.mesh.triangles.size();
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  tick("done", 1.0);
  return res;
}

}  // namespace hdrf::io
