// hdrfusion export SCAN_DIR|MESH.ply --out DIR [--up z|y] [clean-up options] [--tone OP]
// An HDR mesh for other tools: cleaned (docs/export.md), in a gravity-aligned world frame
// with the floor at height 0, display colours through the chosen tone mapping, and the
// transform and every clean-up step recorded in export.json.
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/commands.h"
#include "common/error.h"
#include "io/exr.h"
#include "io/ocio_display.h"
#include "io/ply.h"
#include "io/simplify.h"
#include "io/text_table.h"
#include "mesh/cleanup.h"
#include "mesh/world_frame.h"
#include "tonemap/operator.h"

namespace hdrf::cli {

namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;

mesh::Box ParseBox(const std::string& text) {
  std::vector<float> v;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ',')) {
    try {
      std::size_t used = 0;
      v.push_back(std::stof(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw SettingError("--crop", "'" + item + "' is not a number (want xmin,ymin,zmin,xmax,ymax,zmax in metres)");
    }
  }
  if (v.size() != 6) throw SettingError("--crop", "want six numbers: xmin,ymin,zmin,xmax,ymax,zmax (metres, output frame)");
  return {{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
}
}  // namespace

Command AddExportCommand(CLI::App& app) {
  struct Args {
    std::string in, out, up = "z", crop, tone = "mantiuk08";
    std::size_t triangles = 0;
    mesh::CleanOptions clean;
    bool no_clean = false;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("export", "Export a scan's HDR mesh for other tools: cleaned, levelled, tone-mapped colours");
  cmd->add_option("IN", a->in, "A scan output folder (hdrfusion scan --out) or an HDR PLY")->required();
  cmd->add_option("--out", a->out, "Output folder (created; mesh.ply and export.json are replaced)")->required();
  cmd->add_option("--up", a->up, "Up axis of the output: z (Blender) or y (glTF)")->check(CLI::IsMember({"z", "y"}))->capture_default_str();
  cmd->add_option("--min-piece-area", a->clean.min_piece_area, "Drop connected pieces smaller than this (m^2; 0 keeps all)")
      ->capture_default_str();
  cmd->add_option("--max-hole", a->clean.max_hole_perimeter, "Close holes up to this perimeter (m; 0 closes none)")
      ->capture_default_str();
  cmd->add_option("--weld", a->clean.weld_tolerance, "Merge vertices closer than this (m)")->capture_default_str();
  cmd->add_option("--crop", a->crop, "Keep only what is inside xmin,ymin,zmin,xmax,ymax,zmax (metres, output frame)");
  cmd->add_option("--triangles", a->triangles, "Simplify to at most this many triangles (0: keep all); normals, radiance "
                                               "and flags are kept, boundaries are not moved")
      ->capture_default_str();
  cmd->add_flag("--no-clean", a->no_clean, "Write the mesh as extracted (levelled only)");
  cmd->add_option("--tone", a->tone, "Tone mapping of the PLY's display colours: OP[,key=value...]")->capture_default_str();
  return {cmd, [a] {
    // Everything that can be refused is checked before any work.
    const tonemap::Spec spec = tonemap::ParseSpec(a->tone);
    const auto& decl = tonemap::FindOperator(spec.op);
    const tonemap::Params params = tonemap::ResolveParams(decl, spec.values);
    a->clean.Check();
    std::optional<mesh::Box> crop;
    if (!a->crop.empty()) crop = ParseBox(a->crop);
    const fs::path in(a->in), out(a->out);
    const fs::path ply = fs::is_directory(in) ? in / "mesh.ply" : in;
    if (!fs::exists(ply))
      throw InputError(ply, fs::is_directory(in) ? "no mesh.ply in this folder (is it a scan output folder?)" : "file is missing");
    const mesh::Mesh raw = io::ReadPly(ply);
    if (raw.triangles.empty()) throw InputError(ply, "holds no triangles: nothing to export");

    mesh::CleanOptions co = a->clean;
    if (a->no_clean) co.min_piece_area = 0, co.max_hole_perimeter = 0, co.weld_tolerance = 0, co.fill_radiance = false;
    mesh::CleanMesh c = mesh::Clean(raw, co);
    mesh::WorldFrameOptions wo;
    wo.up = a->up == "y" ? mesh::UpAxis::kY : mesh::UpAxis::kZ;
    const mesh::WorldFrame wf = mesh::EstimateWorldFrame(c.mesh, wo);
    mesh::TransformMesh(c.mesh, wf.transform);
    if (crop) {
      mesh::CleanOptions only_crop;
      only_crop.weld_tolerance = 0, only_crop.min_piece_area = 0, only_crop.max_hole_perimeter = 0, only_crop.fill_radiance = false;
      only_crop.crop = crop;
      mesh::CleanMesh cc = mesh::Clean(c.mesh, only_crop);
      std::vector<std::uint8_t> flags(cc.mesh.position.size());
      for (std::size_t v = 0; v < flags.size(); ++v) flags[v] = c.radiance_filled[std::size_t(cc.source[v])];
      c.report.cropped = cc.report.cropped;
      c.mesh = std::move(cc.mesh);
      c.radiance_filled = std::move(flags);
      if (c.mesh.triangles.empty()) throw SettingError("--crop", "the box holds none of the mesh (" + wf.Describe() + ")");
    }
    double simplify_error = 0;
    const std::size_t before_simplify = c.mesh.triangles.size();
    if (a->triangles > 0) {
      io::SimplifyResult s = io::Simplify(c.mesh, a->triangles);
      std::vector<std::uint8_t> flags(s.mesh.position.size());
      for (std::size_t v = 0; v < flags.size(); ++v) flags[v] = c.radiance_filled[std::size_t(s.source[v])];
      c.mesh = std::move(s.mesh);
      c.radiance_filled = std::move(flags);
      simplify_error = s.error_m;
    }
    // Display colours: the operator's curve from the scan's last render where there is one.
    auto op = decl.make(params, Device::kCpu);
    const fs::path render = in / "render_last.exr";
    if (fs::is_directory(in) && fs::exists(render)) {
      Image<Float3> shown;
      op->Map(io::ReadExr(render), shown, tonemap::FrameTime::Still());
    }
    const std::vector<Rgb8> display = io::OcioDisplay().Encode(op->MapList(c.mesh.radiance));
    fs::create_directories(out);
    io::WritePly(out / "mesh.ply", c.mesh, &display, &c.radiance_filled);
    const mesh::CleanReport& r = c.report;
    json transform = json::array();
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) transform.push_back(wf.transform(i, j));
    const json report = {
        {"source", ply.string()},
        {"up_axis", a->up},
        {"transform_output_from_model", transform},
        {"transform_note", "row-major 4x4; model = the first camera's frame (x right, y down, z forward), metres"},
        {"world_frame", wf.Describe()},
        {"floor_found", wf.floor_found},
        {"tone_mapping", tonemap::FormatSpec(spec)},
        {"vertices", c.mesh.position.size()},
        {"triangles", c.mesh.triangles.size()},
        {"simplify", {{"budget", a->triangles}, {"triangles_before", before_simplify}, {"error_m", simplify_error}}},
        {"clean", {{"welded", r.welded}, {"degenerate_removed", r.degenerate_removed}, {"duplicate_removed", r.duplicate_removed},
                   {"cropped", r.cropped}, {"pieces_kept", r.pieces_kept}, {"pieces_removed", r.pieces_removed},
                   {"holes_filled", r.holes_filled}, {"holes_left", r.holes_left}, {"radiance_filled", r.radiance_filled},
                   {"radiance_missing", r.radiance_missing}}}};
    io::WriteFileAtomically(out / "export.json", report.dump(1) + "\n");
    std::printf("%s: %zu vertices, %zu triangles; %s\nclean-up: %d welded, %d degenerate and %d duplicate triangles removed, "
                "%d pieces kept and %d dropped, %d holes closed (%d left open), %d vertices' radiance from neighbours "
                "(flagged)\n%swrote %s/{mesh.ply, export.json}\n",
                ply.string().c_str(), c.mesh.position.size(), c.mesh.triangles.size(), wf.Describe().c_str(), r.welded,
                r.degenerate_removed, r.duplicate_removed, r.pieces_kept, r.pieces_removed, r.holes_filled, r.holes_left,
                r.radiance_filled,
                a->triangles > 0 ? ("simplified from " + std::to_string(before_simplify) + " triangles (largest deviation " +
                                    std::to_string(simplify_error * 1000).substr(0, 5) + " mm)\n").c_str()
                                 : "",
                out.string().c_str());
    return 0;
  }};
}

}  // namespace hdrf::cli
