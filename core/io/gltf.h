// glTF 2.0 binary (.glb) of a textured mesh: positions, normals, TEXCOORD_0, the linear
// radiance as the application attribute _RADIANCE (float RGB per vertex), indices, and a
// material whose base colour is the tone-mapped texture (PNG, embedded).
#pragma once

#include <filesystem>
#include <cstdint>
#include <string>
#include <vector>

#include "common/image.h"
#include "mesh/uv_atlas.h"
#include "mesh/world_frame.h"

namespace hdrf::io {

// glTF is Y-up: a Z-up mesh (`up` = kZ) is turned (x, y, z) -> (x, z, -y) as it is written.
// `base_colour_png`: the texture's PNG bytes (none: no texture). `radiance_units` goes in
// the asset's extras. Written through a temporary file and a rename.
void WriteGlb(const std::filesystem::path& file, const mesh::Atlas& atlas, const std::vector<std::uint8_t>& base_colour_png,
              mesh::UpAxis up, const std::string& radiance_units);

}  // namespace hdrf::io
