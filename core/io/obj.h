// Wavefront OBJ + MTL for a textured mesh (the atlas's split vertices, its UVs, normals).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "mesh/uv_atlas.h"

namespace hdrf::io {

struct ObjMaterial {
  std::string mtl_file;  // written beside the OBJ (a file name, no folder)
  std::string texture;   // map_Kd, a file name beside it
};

// Writes `obj` naming materials[0]'s MTL (mtllib), and every material's MTL (one material,
// "hdrfusion_scan", with its map_Kd): the first is what importers load, the others are
// alternatives with the same material name (docs/export.md). UV origin bottom-left, as OBJ
// readers expect. `header` lines are written as comments. Each file through a temporary
// file and a rename.
void WriteObj(const std::filesystem::path& obj, const mesh::Atlas& atlas, const std::vector<ObjMaterial>& materials,
              const std::vector<std::string>& header = {});

}  // namespace hdrf::io
