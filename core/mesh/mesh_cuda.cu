// Surface extraction on the GPU from the device-resident model: the same per-cube
// functions (mesh_impl.h) as the CPU's ExtractMesh, with CUB's scan, sort and unique where
// the CPU uses std::sort and std::unique, giving the same vertices in the same order.
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>
#include <cub/device/device_select.cuh>

#include <algorithm>

#include "common/parallel_cuda.cuh"
#include "mesh/mesh.h"
#include "mesh/mesh_impl.h"
#include "volume/device_volume.h"

namespace hdrf::mesh {

namespace {
template <typename V>
Mesh Extract(const volume::DeviceVolume& volume) {
  Mesh m;
  const int cubes = int(volume.allocated_bricks()) * 512;
  if (cubes == 0) return m;
  const volume::VolumeView<V> view = volume.view<V>();
  const volume::BrickCoord* coords = volume.brick_coords();
  // 1. Triangles per cube, their offsets, then the triangles as edge keys in cube order.
  DeviceBuffer<int> count{static_cast<std::size_t>(cubes) + 1}, offset{static_cast<std::size_t>(cubes) + 1};
  int* cnt = count.data();
  par::ForEach(par::Gpu{}, cubes + 1, [=] __device__(int c) {
    if (c == cubes) {
      cnt[c] = 0;
      return;
    }
    const volume::BrickCoord b = coords[c / 512];
    const int i = c % 512;
    std::uint64_t t[kMaxCubeTriangles][3];
    cnt[c] = CubeTriangles(view, b.x * 8 + (i & 7), b.y * 8 + ((i >> 3) & 7), b.z * 8 + (i >> 6), t);
  });
  std::size_t bytes = 0;
  HDRF_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, bytes, cnt, offset.data(), cubes + 1));
  DeviceBuffer<std::uint8_t> temp{std::max<std::size_t>(bytes, 16)};
  HDRF_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(temp.data(), bytes, cnt, offset.data(), cubes + 1));
  int n_tri = 0;
  HDRF_CUDA_CHECK(cudaMemcpy(&n_tri, offset.data() + cubes, sizeof(int), cudaMemcpyDeviceToHost));
  if (n_tri == 0) return m;
  const int n_keys = 3 * n_tri;
  DeviceBuffer<std::uint64_t> tri_keys{static_cast<std::size_t>(n_keys)}, sorted{static_cast<std::size_t>(n_keys)};
  std::uint64_t* tk = tri_keys.data();
  const int* off = offset.data();
  par::ForEach(par::Gpu{}, cubes, [=] __device__(int c) {
    if (cnt[c] == 0) return;
    const volume::BrickCoord b = coords[c / 512];
    const int i = c % 512;
    std::uint64_t t[kMaxCubeTriangles][3];
    const int nt = CubeTriangles(view, b.x * 8 + (i & 7), b.y * 8 + ((i >> 3) & 7), b.z * 8 + (i >> 6), t);
    for (int k = 0; k < nt; ++k)
      for (int j = 0; j < 3; ++j) tk[3 * (off[c] + k) + j] = t[k][j];
  });
  // 2. Distinct edges in key order: the vertices.
  bytes = 0;
  HDRF_CUDA_CHECK(cub::DeviceRadixSort::SortKeys(nullptr, bytes, tk, sorted.data(), n_keys));
  DeviceBuffer<std::uint64_t> unique{static_cast<std::size_t>(n_keys)};
  DeviceBuffer<int> n_unique{1};
  std::size_t bytes2 = 0;
  HDRF_CUDA_CHECK(cub::DeviceSelect::Unique(nullptr, bytes2, sorted.data(), unique.data(), n_unique.data(), n_keys));
  temp = DeviceBuffer<std::uint8_t>{std::max({bytes, bytes2, std::size_t(16)})};
  bytes = temp.size();
  HDRF_CUDA_CHECK(cub::DeviceRadixSort::SortKeys(temp.data(), bytes, tk, sorted.data(), n_keys));
  bytes = temp.size();
  HDRF_CUDA_CHECK(cub::DeviceSelect::Unique(temp.data(), bytes, sorted.data(), unique.data(), n_unique.data(), n_keys));
  int nv = 0;
  HDRF_CUDA_CHECK(cudaMemcpy(&nv, n_unique.data(), sizeof(int), cudaMemcpyDeviceToHost));
  DeviceBuffer<Float3> pos{static_cast<std::size_t>(nv)}, nrm{static_cast<std::size_t>(nv)}, rad{static_cast<std::size_t>(nv)};
  const std::uint64_t* uk = unique.data();
  Float3 *pp = pos.data(), *pn = nrm.data(), *pr = rad.data();
  par::ForEach(par::Gpu{}, nv, [=] __device__(int i) { EdgeVertex(view, uk[i], &pp[i], &pn[i], &pr[i]); });
  // 3. Triangles as vertex indices (binary search of their keys), facing the free space.
  DeviceBuffer<std::int32_t> tris{static_cast<std::size_t>(n_keys)};
  std::int32_t* tr = tris.data();
  par::ForEach(par::Gpu{}, n_tri, [=] __device__(int t) {
    std::int32_t idx[3];
    for (int j = 0; j < 3; ++j) {
      const std::uint64_t key = tk[3 * t + j];
      int lo = 0, hi = nv;
      while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (uk[mid] < key) lo = mid + 1;
        else hi = mid;
      }
      idx[j] = lo;
    }
    OrientTriangle(pp, pn, idx);
    for (int j = 0; j < 3; ++j) tr[3 * t + j] = idx[j];
  });
  m.position.resize(std::size_t(nv));
  m.normal.resize(std::size_t(nv));
  m.radiance.resize(std::size_t(nv));
  m.triangles.resize(std::size_t(n_tri));
  pos.Download(m.position.data());
  nrm.Download(m.normal.data());
  rad.Download(m.radiance.data());
  cuda::CopyDeviceToHost(m.triangles.data(), tr, std::size_t(n_keys) * sizeof(std::int32_t));
  return m;
}
}  // namespace

Mesh ExtractMeshOnGpu(const volume::DeviceVolume& volume) {
  return volume::VisitEncoding(volume.options().encoding,
                               [&](auto tag) { return Extract<decltype(tag)>(volume); });
}

}  // namespace hdrf::mesh
