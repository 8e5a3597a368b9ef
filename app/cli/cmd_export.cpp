// hdrfusion export SCAN_DIR|MESH.ply --out DIR [options]
// A scan as assets for other tools (docs/export.md): the mesh cleaned and levelled, a UV
// atlas with an HDR texture baked from the scan's keyframes, PLY, OBJ + MTL and glTF
// binary, renders with alpha and depth, and export.json recording every step.
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <unistd.h>

#include "cli/commands.h"
#include "cli/interrupt.h"
#include "io/asset_export.h"
#include "io/output_file.h"
#include "common/error.h"

namespace hdrf::cli {

namespace {
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
    std::string in, out, up = "z", crop, formats = "ply,obj,gltf", render;
    double texel_mm = 2;
    bool no_clean = false, no_texture = false;
    io::AssetOptions o;
  };

  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("export", "Export a scan for other tools: cleaned, levelled mesh with an HDR texture "
                                           "(PLY, OBJ + MTL, glTF binary, OpenEXR), renders");
  cmd->add_option("IN", a->in, "A scan output folder (hdrfusion scan --out), a project (.hdrproj) or an HDR PLY")->required();
  cmd->add_option("--out", a->out, "Output folder (created; the files it names are replaced, nothing else is touched)")
      ->required();
  cmd->add_option("--formats", a->formats, "Comma-separated: ply, obj, gltf")->capture_default_str();
  cmd->add_option("--up", a->up, "Up axis of the output: z (Blender) or y; mesh.glb is always Y-up")
      ->check(CLI::IsMember({"z", "y"}))
      ->capture_default_str();
  cmd->add_option("--min-piece-area", a->o.clean_options.min_piece_area, "Drop connected pieces smaller than this (m^2; 0 keeps all)")
      ->capture_default_str();
  cmd->add_option("--max-hole", a->o.clean_options.max_hole_perimeter, "Close holes up to this perimeter (m; 0 closes none)")
      ->capture_default_str();
  cmd->add_option("--weld", a->o.clean_options.weld_tolerance, "Merge vertices closer than this (m)")->capture_default_str();
  cmd->add_option("--crop", a->crop, "Keep only what is inside xmin,ymin,zmin,xmax,ymax,zmax (metres, output frame)");
  cmd->add_option("--triangles", a->o.triangles, "Simplify to at most this many triangles (0: keep all); normals, radiance "
                                                 "and flags are kept, boundaries are not moved")
      ->capture_default_str();
  cmd->add_flag("--no-clean", a->no_clean, "Write the mesh as extracted (levelled only)");
  cmd->add_option("--texel-mm", a->texel_mm, "Texture density: millimetres of surface per texel")->capture_default_str();
  cmd->add_option("--texture-size", a->o.atlas.fit_size, "Instead of --texel-mm: the density that fits an N x N texture");
  cmd->add_option("--padding", a->o.atlas.padding, "Texels of margin around every chart")->capture_default_str();
  cmd->add_option("--sample-sigma", a->o.bake.sample_sigma_px,
                  "Texture from the frames: each pixel weighted by a Gaussian of its distance to the texel (pixels); "
                  "smaller is sharper and noisier, 0 interpolates each frame bilinearly")
      ->capture_default_str();
  cmd->add_flag("--no-texture", a->no_texture, "No atlas or texture (PLY only, with per-vertex radiance)");
  cmd->add_option("--render", a->render, "Also render the textured mesh at WxH (render.exr with alpha and depth, render.png)");
  cmd->add_option("--render-frame", a->o.render_frame, "The scan frame whose pose the render takes")->capture_default_str();
  cmd->add_option("--tone", a->o.tone, "Tone mapping of the PNG texture, renders and PLY colours: OP[,key=value...]")
      ->capture_default_str();
  return {cmd, [a] {
    io::AssetOptions o = a->o;
    // Everything that can be refused is checked before any work.
    o.clean = !a->no_clean;
    o.up = a->up == "y" ? mesh::UpAxis::kY : mesh::UpAxis::kZ;
    if (!a->crop.empty()) o.crop = ParseBox(a->crop);
    o.atlas.texel_m = a->texel_mm / 1000;
    o.texture = !a->no_texture;
    o.ply = o.obj = o.glb = false;
    std::stringstream fs_list(a->formats);
    std::string f;
    while (std::getline(fs_list, f, ',')) {
      if (f == "ply") o.ply = true;
      else if (f == "obj") o.obj = true;
      else if (f == "gltf" || f == "glb") o.glb = true;
      else throw SettingError("--formats", "'" + f + "' is not one of ply, obj, gltf");
    }
    if (a->no_texture && (o.obj || o.glb)) throw SettingError("--no-texture", "OBJ and glTF carry the texture: use --formats ply");
    if (!a->render.empty()) {
      int w = 0, h = 0;
      char extra = 0;
      if (std::sscanf(a->render.c_str(), "%dx%d%c", &w, &h, &extra) != 2 || w <= 0 || h <= 0)
        throw SettingError("--render", "'" + a->render + "' is not WxH (e.g. 1920x1080)");
      o.render_width = w, o.render_height = h;
    }
    o.Check();
    // The export replaces mesh.ply: into the scan's own folder it took the raw mesh, and the
    // next export of that folder baked its texture from the levelled one.
    io::CheckOutputFolderEarly(a->out);
    if (io::IsWithin(a->out, a->in))
      throw InputError(a->out, "is the scan being exported: the export's mesh.ply would replace the scan's own; "
                               "choose another --out");
    const io::ScanData scan = io::LoadScan(a->in);
    StopOnInterrupt stop;  // Ctrl-C cancels: the output folder is left as it was
    std::string last_stage;
    int last_pct = -1;
    const bool tty = isatty(fileno(stderr));
    const io::AssetResult r = io::ExportAsset(scan, o, a->out, [&](const std::string& stage, double fr) {
      const int pct = int(100 * fr);
      if (stage != last_stage || (tty ? pct != last_pct : pct / 10 != last_pct / 10)) {
        std::fprintf(stderr, tty ? "\rexport: %-10s %3d %%   " : "export: %s %d %%\n", stage.c_str(), pct);
        last_stage = stage;
        last_pct = pct;
      }
      return !stop.raised();
    });
    if (tty) std::fprintf(stderr, "\n");
    for (const std::string& w : r.warnings) std::fprintf(stderr, "export: warning: %s\n", Printable(w).c_str());
    std::printf("%s\nwrote %s/{", r.Summary().c_str(), a->out.c_str());
    for (std::size_t i = 0; i < r.files.size(); ++i) std::printf("%s%s", i ? ", " : "", r.files[i].c_str());
    std::printf("}\n");
    return 0;
  }};
}

}  // namespace hdrf::cli
