#include "io/obj.h"

#include <cstdio>
#include <fstream>

#include "common/error.h"
#include "io/text_table.h"

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
  const fs::path tmp = TemporarySibling(obj);
  {
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw InputError(obj, "cannot be written (cannot create a temporary file beside it)");
    std::vector<char> buffer(1 << 20);
    std::setvbuf(f, buffer.data(), _IOFBF, buffer.size());
    for (const std::string& h : header) std::fprintf(f, "# %s\n", h.c_str());
    std::fprintf(f, "mtllib %s\n", materials[0].mtl_file.c_str());
    std::fprintf(f, "o hdrfusion_scan\n");
    for (const Float3& p : m.position) std::fprintf(f, "v %.6f %.6f %.6f\n", p.x, p.y, p.z);
    for (std::size_t v = 0; v < m.position.size(); ++v) {
      const Float2 uv = atlas.UvBottomLeft(v);
      std::fprintf(f, "vt %.7f %.7f\n", uv.x, uv.y);
    }
    if (normals)
      for (const Float3& n : m.normal) std::fprintf(f, "vn %.5f %.5f %.5f\n", n.x, n.y, n.z);
    std::fprintf(f, "usemtl hdrfusion_scan\ns off\n");
    for (const auto& t : m.triangles) {
      const long a = t[0] + 1, b = t[1] + 1, c = t[2] + 1;
      if (normals)
        std::fprintf(f, "f %ld/%ld/%ld %ld/%ld/%ld %ld/%ld/%ld\n", a, a, a, b, b, b, c, c, c);
      else
        std::fprintf(f, "f %ld/%ld %ld/%ld %ld/%ld\n", a, a, b, b, c, c);
    }
    const bool ok = std::ferror(f) == 0;
    if (std::fclose(f) != 0 || !ok) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw InputError(obj, "cannot be written (disk full?)");
    }
  }
  CommitTemporary(tmp, obj);
}

}  // namespace hdrf::io
