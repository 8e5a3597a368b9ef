#include "io/obj.h"

#include <cstdio>
#include <fstream>

#include "common/error.h"
#include "io/output_file.h"

namespace hdrf::io {

namespace fs = std::filesystem;

void WriteObj(const fs::path& obj, const mesh::Atlas& atlas, const std::vector<ObjMaterial>& materials,
              const std::vector<std::string>& header) {
  if (materials.empty()) throw Error("WriteObj: no material given");
  const mesh::Mesh& m = atlas.mesh;
  const bool normals = m.normal.size() == m.position.size();
  for (const ObjMaterial& mat : materials) {
    std::string mtl = "# HDRFusion Studio material\nnewmtl hdrfusion_scan\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\nd 1\nillum 1\n";
    mtl += "map_Kd " + mat.texture + "\n";
    WriteFileAtomically(obj.parent_path() / mat.mtl_file, mtl);
  }
  OutputFile out(obj);
  // Formatted into a buffer that is written out whenever it holds a megabyte.
  std::string buf;
  buf.reserve(1 << 21);
  char line[160];
  const auto put = [&](int n) {
    buf.append(line, std::size_t(n));
    if (buf.size() >= (1 << 20)) {
      out.Write(buf);
      buf.clear();
    }
  };
  for (const std::string& h : header) buf += "# " + h + "\n";
  buf += "mtllib " + materials[0].mtl_file + "\no hdrfusion_scan\n";
  for (const Float3& p : m.position) put(std::snprintf(line, sizeof line, "v %.6f %.6f %.6f\n", p.x, p.y, p.z));
  for (std::size_t v = 0; v < m.position.size(); ++v) {
    const Float2 uv = atlas.UvBottomLeft(v);
    put(std::snprintf(line, sizeof line, "vt %.7f %.7f\n", uv.x, uv.y));
  }
  if (normals)
    for (const Float3& n : m.normal) put(std::snprintf(line, sizeof line, "vn %.5f %.5f %.5f\n", n.x, n.y, n.z));
  buf += "usemtl hdrfusion_scan\ns off\n";
  for (const auto& t : m.triangles) {
    const long a = t[0] + 1, b = t[1] + 1, c = t[2] + 1;
    if (normals)
      put(std::snprintf(line, sizeof line, "f %ld/%ld/%ld %ld/%ld/%ld %ld/%ld/%ld\n", a, a, a, b, b, b, c, c, c));
    else
      put(std::snprintf(line, sizeof line, "f %ld/%ld %ld/%ld %ld/%ld\n", a, a, b, b, c, c));
  }
  out.Write(buf);
  out.Commit();
}

}  // namespace hdrf::io
