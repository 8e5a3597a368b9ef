// The export of a scan as assets for other tools (docs/export.md): the mesh cleaned and
// levelled, a UV atlas, an HDR texture baked from the scan's keyframes, and the files --
// PLY, OBJ + MTL, glTF binary, OpenEXR and PNG textures, renders with alpha and depth, and
// export.json recording every step. Used by `hdrfusion export` and the studio's Export
// dialog. Everything is written into a private folder inside the output folder and moved
// into place at the end: a failure or a cancel leaves the output folder as it was.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/image.h"
#include "io/keyframes_io.h"
#include "pipeline/scan_session.h"
#include "mesh/cleanup.h"
#include "mesh/texture_bake.h"
#include "mesh/uv_atlas.h"
#include "mesh/world_frame.h"

namespace hdrf::io {

// The host memory a render takes per pixel, about: the radiance, alpha and depth images, the
// rasteriser's buffers and the encoders' copies. A render larger than the free memory allows
// is refused before any work.
inline constexpr std::uint64_t kRenderBytesPerPixel = 104;

struct AssetOptions {
  bool clean = true;
  mesh::CleanOptions clean_options;
  mesh::UpAxis up = mesh::UpAxis::kZ;
  std::optional<mesh::Box> crop;          // metres, output frame
  std::size_t triangles = 0;              // simplification budget (0: none)
  std::string tone = "mantiuk08";         // OP[,key=value...] of display colours and the PNG texture
  bool texture = true;                    // atlas + baked texture (OBJ and glTF need it)
  mesh::AtlasOptions atlas;
  mesh::BakeOptions bake;
  bool ply = true, obj = true, glb = true;
  int render_width = 0, render_height = 0;  // > 0: render.exr (RGB, A, Z) and render.png
  int render_frame = 0;                     // the trajectory's pose to render from
  void Check() const;                       // throws SettingError naming the option
};

// What an export starts from: a scan output folder, a project file (.hdrproj) or an HDR PLY.
struct ScanData {
  std::filesystem::path source;
  mesh::Mesh mesh;
  std::optional<RadianceImage> tone_reference;  // the scan's last render (sets the tone curve)
  std::optional<KeyframeSet> keyframes;
  std::vector<Pose> trajectory;                 // model frame
};
// Throws InputError naming the file on anything missing or malformed.
ScanData LoadScan(const std::filesystem::path& in);
// A scan in memory (the studio, benchmarks): the mesh extracted now (`progress` as
// Pipeline::ExtractMesh), the model rendered from the last pose as the tone reference,
// copies of the keyframes.
ScanData ScanDataFromSession(pipeline::ScanSession& session, const std::string& source,
                             const std::function<bool(double)>& progress = {});

struct AssetResult {
  std::vector<std::string> files;  // written, relative to the output folder
  std::vector<std::string> warnings;
  std::string report_json;         // export.json's content
  ColorImage preview;              // a tone-mapped render of the result (480 wide)
  std::size_t vertices = 0, triangles = 0;
  int atlas_width = 0, atlas_height = 0;
  double texel_mm = 0;
  long texels_from_frames = 0, texels_from_volume = 0;
  double seconds = 0;
  std::string Summary() const;  // a few lines for a terminal or a dialog
};

// `progress(stage, fraction of the whole)` returning false cancels (throws hdrf::Cancelled,
// leaving `out` as it was). Options are checked before any work.
AssetResult ExportAsset(const ScanData& scan, const AssetOptions& o, const std::filesystem::path& out,
                        const std::function<bool(const std::string&, double)>& progress = {});

}  // namespace hdrf::io
