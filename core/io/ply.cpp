#include "io/ply.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "common/input_file.h"
#include "io/output_file.h"
#include "common/error.h"
#include "tonemap/display.h"

namespace hdrf::io {

namespace {
const char* kVertexProps[] = {"float x", "float y", "float z", "float nx", "float ny", "float nz",
                              "uchar red", "uchar green", "uchar blue", "float radiance_r",
                              "float radiance_g", "float radiance_b"};
const char* kFlagProp = "uchar radiance_filled";
}

void WritePly(const std::filesystem::path& file, const mesh::Mesh& m, const std::vector<Rgb8>* given,
              const std::vector<std::uint8_t>* flags) {
  if (flags && flags->size() != m.position.size())
    throw Error(file.string() + ": " + std::to_string(flags->size()) + " radiance flags for " +
                std::to_string(m.position.size()) + " vertices");
  // Display colours: the given ones, or one Reinhard scale over all vertices with radiance.
  if (given && given->size() != m.position.size())
    throw Error(file.string() + ": " + std::to_string(given->size()) + " display colours for " +
                std::to_string(m.position.size()) + " vertices");
  RadianceImage rad(int(m.radiance.size()), 1);
  for (std::size_t i = 0; i < m.radiance.size(); ++i) rad[i] = m.radiance[i];
  ColorImage display = m.radiance.empty() || given ? ColorImage() : tonemap::Reinhard(rad);
  if (given) {
    display = ColorImage(int(given->size()), 1);
    std::copy(given->begin(), given->end(), display.data());
  }
  std::ostringstream h;
  h << "ply\nformat binary_little_endian 1.0\ncomment HDRFusion Studio: linear HDR radiance in "
       "radiance_r/g/b (model units), display colour tone-mapped\n"
    << "element vertex " << m.position.size() << "\n";
  for (const char* p : kVertexProps) h << "property " << p << "\n";
  if (flags) h << "property " << kFlagProp << "\n";
  h << "element face " << m.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  OutputFile out(file);
  {
    out.Write(h.str());
    std::vector<char> buf;
    buf.reserve(m.position.size() * 39);
    auto put = [&](const void* p, std::size_t n) {
      buf.insert(buf.end(), static_cast<const char*>(p), static_cast<const char*>(p) + n);
    };
    for (std::size_t i = 0; i < m.position.size(); ++i) {
      put(&m.position[i], 12);
      put(&m.normal[i], 12);
      const Rgb8 c = display.empty() ? Rgb8{0, 0, 0} : display[i];
      put(&c, 3);
      put(&m.radiance[i], 12);
      if (flags) put(&(*flags)[i], 1);
    }
    for (const auto& t : m.triangles) {
      const std::uint8_t three = 3;
      put(&three, 1);
      put(t.data(), 12);
    }
    out.Write(std::string_view(buf.data(), buf.size()));
  }
  out.Commit();
}

namespace {
// An element count: digits only, and no more than the file could hold.
std::size_t Count(const std::filesystem::path& file, int line_no, const std::string& text, std::uintmax_t file_size) {
  std::size_t v = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || ptr != text.data() + text.size() || v > file_size)
    throw InputError(file, line_no, "element count '" + text + "' is not a count this file can hold");
  return v;
}
}  // namespace

mesh::Mesh ReadPly(const std::filesystem::path& file, std::vector<std::uint8_t>* flags_out) {
  const std::uintmax_t file_size = CheckInputFile(file, std::uintmax_t(64) << 30, "a mesh");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "cannot be opened");
  std::string line;
  std::size_t nv = 0, nf = 0;
  int line_no = 0, prop = 0;
  bool in_vertex = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (line_no == 1 && line != "ply") throw InputError(file, 1, "not a PLY file");
    if (line == "end_header") break;
    if (line.rfind("format", 0) == 0 && line != "format binary_little_endian 1.0")
      throw InputError(file, line_no, "only binary little-endian PLY is read, found '" + line + "'");
    if (line.rfind("element vertex ", 0) == 0) {
      nv = Count(file, line_no, line.substr(15), file_size);
      in_vertex = true;
    } else if (line.rfind("element face ", 0) == 0) {
      nf = Count(file, line_no, line.substr(13), file_size);
      in_vertex = false;
    } else if (in_vertex && line.rfind("property ", 0) == 0) {
      if (prop > 12 || (prop < 12 && line.substr(9) != kVertexProps[prop]) || (prop == 12 && line.substr(9) != kFlagProp))
        throw InputError(file, line_no, "unexpected vertex property '" + line.substr(9) + "'");
      ++prop;
    }
  }
  if (prop != 12 && prop != 13) throw InputError(file, "vertex properties do not follow the HDR PLY layout (docs/formats.md)");
  // The counts must fit in the file before anything is allocated for them.
  const std::size_t record = prop == 13 ? 40 : 39;
  const std::uintmax_t header_end = std::uintmax_t(in.tellg());
  if (double(nv) * double(record) + double(nf) * 13.0 > double(file_size - std::min(file_size, header_end)))
    throw InputError(file, "its header claims " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                               " faces, more than the file's " + std::to_string(file_size) + " bytes hold (truncated?)");
  mesh::Mesh m;
  m.position.resize(nv);
  m.normal.resize(nv);
  m.radiance.resize(nv);
  if (flags_out) flags_out->assign(nv, 0);
  for (std::size_t i = 0; i < nv; ++i) {
    char rec[40];
    if (!in.read(rec, std::streamsize(record))) throw InputError(file, "truncated vertex data at vertex " + std::to_string(i));
    std::memcpy(&m.position[i], rec, 12);
    std::memcpy(&m.normal[i], rec + 12, 12);
    std::memcpy(&m.radiance[i], rec + 27, 12);
    if (flags_out && record == 40) (*flags_out)[i] = std::uint8_t(rec[39]);
    // A damaged file's values would travel on into every export: positions and normals must
    // be finite, radiance finite and not negative (0 is "never seen").
    const Float3& p = m.position[i], &n = m.normal[i], &r = m.radiance[i];
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(n.x) && std::isfinite(n.y) &&
          std::isfinite(n.z)))
      throw InputError(file, "vertex " + std::to_string(i) + " has a position or normal that is not a finite number");
    if (!(r.x >= 0 && r.y >= 0 && r.z >= 0 && std::isfinite(r.x) && std::isfinite(r.y) && std::isfinite(r.z)))
      throw InputError(file, "vertex " + std::to_string(i) + " has a radiance that is negative or not a finite number");
  }
  m.triangles.resize(nf);
  for (std::size_t i = 0; i < nf; ++i) {
    char rec[13];
    if (!in.read(rec, 13) || rec[0] != 3)
      throw InputError(file, "truncated or non-triangle face " + std::to_string(i));
    std::memcpy(m.triangles[i].data(), rec + 1, 12);
    for (int k = 0; k < 3; ++k)
      if (m.triangles[i][k] < 0 || std::size_t(m.triangles[i][k]) >= nv)
        throw InputError(file, "face " + std::to_string(i) + " refers to a vertex that does not exist");
  }
  return m;
}

}  // namespace hdrf::io
