// HDR meshes as binary little-endian PLY (docs/formats.md): x y z, nx ny nz (float), red green
// blue (uchar, tone-mapped sRGB), radiance_r/g/b (float, linear); faces as
// "list uchar int vertex_indices".
#pragma once

#include <filesystem>

#include "mesh/mesh.h"

namespace hdrf::io {

// Display colours are `display` (one per vertex, from a chosen tone-mapping operator) or,
// without them, a global Reinhard tone mapping of the vertex radiance. Written through a
// temporary file and a rename: an interrupted export leaves nothing half-written.
// With `radiance_filled` (one flag per vertex) the vertices carry a 13th property,
// `uchar radiance_filled` (1 = the radiance came from neighbours, not from the volume).
void WritePly(const std::filesystem::path& file, const mesh::Mesh& mesh, const std::vector<Rgb8>* display = nullptr,
              const std::vector<std::uint8_t>* radiance_filled = nullptr);

// Reads what WritePly writes (and any binary little-endian PLY with the same vertex
// properties in the same order). Throws InputError naming the file on anything else.
// The optional 13th property is returned through `radiance_filled` when given (all 0 when
// the file has none).
mesh::Mesh ReadPly(const std::filesystem::path& file, std::vector<std::uint8_t>* radiance_filled = nullptr);

}  // namespace hdrf::io
