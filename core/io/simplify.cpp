#include "io/simplify.h"

#include <meshoptimizer.h>

#include "common/error.h"

namespace hdrf::io {

SimplifyResult Simplify(const mesh::Mesh& in, std::size_t target_triangles, double max_error_m) {
  if (target_triangles == 0) throw SettingError("--triangles", "the triangle budget must be at least 1");
  SimplifyResult r;
  if (in.triangles.size() <= target_triangles) {
    r.mesh = in;
    r.source.resize(in.position.size());
    for (std::size_t v = 0; v < r.source.size(); ++v) r.source[v] = std::int32_t(v);
    return r;
  }
  std::vector<unsigned> indices;
  indices.reserve(in.triangles.size() * 3);
  for (const auto& t : in.triangles)
    for (std::int32_t i : t) indices.push_back(unsigned(i));
  const float* pos = &in.position.data()->x;
  const float scale = meshopt_simplifyScale(pos, in.position.size(), sizeof(Float3));
  std::vector<unsigned> out(indices.size());
  float rel_error = 0;
  const std::size_t n = meshopt_simplify(out.data(), indices.data(), indices.size(), pos, in.position.size(), sizeof(Float3),
                                         target_triangles * 3, float(max_error_m / std::max(scale, 1e-12f)),
                                         meshopt_SimplifyLockBorder, &rel_error);
  r.error_m = double(rel_error) * scale;
  // Keep the vertices still used, in their order.
  std::vector<std::int32_t> map(in.position.size(), -1);
  for (std::size_t k = 0; k < n; ++k) map[out[k]] = 0;
  for (std::size_t v = 0; v < in.position.size(); ++v) {
    if (map[v] < 0) continue;
    map[v] = std::int32_t(r.mesh.position.size());
    r.source.push_back(std::int32_t(v));
    r.mesh.position.push_back(in.position[v]);
    if (v < in.normal.size()) r.mesh.normal.push_back(in.normal[v]);
    if (v < in.radiance.size()) r.mesh.radiance.push_back(in.radiance[v]);
  }
  for (std::size_t k = 0; k + 2 < n; k += 3) r.mesh.triangles.push_back({map[out[k]], map[out[k + 1]], map[out[k + 2]]});
  return r;
}

}  // namespace hdrf::io
