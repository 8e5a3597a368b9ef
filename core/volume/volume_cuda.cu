// The model on the GPU (device_volume.h): brick allocation by a scan over the brick index,
// integration one block per brick, ray casting through the shared driver.
#include <cub/device/device_scan.cuh>

#include <algorithm>
#include <array>
#include <vector>

#include "common/parallel_cuda.cuh"
#include "volume/device_volume.h"

namespace hdrf::volume {

namespace {
// One block of 512 threads per visible brick (a voxel each), blocks striding over the list.
template <typename V>
__global__ void IntegrateBricksKernel(IntegrateArgs a, V* pool, const BrickCoord* coords, const int* todo,
                                      const int* counts) {
    const int n_todo = counts[1];
    for (int k = blockIdx.x; k < n_todo; k += gridDim.x) {
      const int slot = todo[k];
      const BrickCoord bc = coords[slot];
      IntegrateVoxel(a, bc.x, bc.y, bc.z, threadIdx.x, pool[long(slot) * 512 + threadIdx.x]);
    }
}
template <typename V>
void IntegrateBricks(const IntegrateArgs& a, V* pool, const BrickCoord* coords, const int* todo, const int* counts) {
  IntegrateBricksKernel<V><<<1024, 512>>>(a, pool, coords, todo, counts);
  HDRF_CUDA_CHECK_LAUNCH();
}

// Fresh voxels for slots [first, first + count) of the pool.
template <typename V>
void FillDefault(V* pool, long first, long count) {
  par::ForEach(par::Gpu{}, int(count), [=] __device__(int i) { pool[first + i] = V{}; });
}

}  // namespace

DeviceVolume::DeviceVolume(const VolumeOptions& o) : mirror_(o), vbytes_(EncodingBytes(o.encoding)) {
  const int nb = mirror_.bricks_per_side();
  const std::size_t nb3 = std::size_t(nb) * nb * nb;
  index_ = DeviceBuffer<int>(nb3);
  HDRF_CUDA_CHECK(cudaMemset(index_.data(), 0xff, nb3 * sizeof(int)));  // -1
  flags_ = DeviceBuffer<int>(nb3);
  scan_ = DeviceBuffer<int>(nb3);
  todo_ = DeviceBuffer<int>(nb3);
  visible_ = DeviceBuffer<std::uint8_t>(nb3);
  const int nc = (nb + 3) / 4;
  coarse_ = DeviceBuffer<std::uint8_t>(std::size_t(nc) * nc * nc);
  HDRF_CUDA_CHECK(cudaMemset(coarse_.data(), 0, coarse_.size()));
  counts_ = DeviceBuffer<int>(2);
  HDRF_CUDA_CHECK(cudaMemset(counts_.data(), 0, 2 * sizeof(int)));
  std::size_t scan_bytes = 0;
  HDRF_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, scan_bytes, flags_.data(), scan_.data(), int(nb3)));
  temp_ = DeviceBuffer<std::uint8_t>(std::max(scan_bytes, std::size_t(16)));
  Grow(4096);
}

std::size_t DeviceVolume::last_visible_bricks() const {
  int n = 0;
  HDRF_CUDA_CHECK(cudaMemcpy(&n, counts_.data() + 1, sizeof(int), cudaMemcpyDeviceToHost));
  return std::size_t(n);
}

std::size_t DeviceVolume::bytes() const {
  return index_.size() * sizeof(int) + std::size_t(allocated_) * 512 * std::size_t(vbytes_);
}

void DeviceVolume::Grow(int want) {
  const int max_bricks = int(std::min<std::size_t>(mirror_.max_bricks(), 1u << 30));
  const int cap = std::min(max_bricks, std::max(want, capacity_ * 2));
  if (cap <= capacity_) return;
  DeviceBuffer<std::uint8_t> pool{std::size_t(cap) * 512 * std::size_t(vbytes_)};
  DeviceBuffer<BrickCoord> coords{std::size_t(cap)};
  if (allocated_ > 0) {
    HDRF_CUDA_CHECK(cudaMemcpy(pool.data(), pool_.data(), std::size_t(allocated_) * 512 * std::size_t(vbytes_),
                               cudaMemcpyDeviceToDevice));
    HDRF_CUDA_CHECK(cudaMemcpy(coords.data(), coords_.data(), std::size_t(allocated_) * sizeof(BrickCoord),
                               cudaMemcpyDeviceToDevice));
  }
  pool_ = std::move(pool);
  coords_ = std::move(coords);
  const long first = long(capacity_) * 512, count = long(cap) * 512 - first;
  VisitEncoding(options().encoding,
                [&](auto tag) { FillDefault(reinterpret_cast<decltype(tag)*>(pool_.data()), first, count); });
  capacity_ = cap;
}

void DeviceVolume::Integrate(const IntegrateArgs& a, const Pose& T) {
  const int nb = mirror_.bricks_per_side(), nb3 = nb * nb * nb;
  // 1. Bricks in the truncation band of every second depth pixel.
  std::uint8_t* vis = visible_.data();
  HDRF_CUDA_CHECK(cudaMemset(vis, 0, std::size_t(nb3)));
  const RigidTransform Twc = ToRigidTransform(T);
  const int bw = nb;
  par::ForEachPixel(par::Gpu{}, (a.cam.width + 1) / 2, (a.cam.height + 1) / 2, [=] __device__(int x, int y) {
    ForBricksAlongRay(a, Twc, bw, 2 * x, 2 * y,
                              [&](int bx, int by, int bz) { vis[(bz * bw + by) * bw + bx] = 1; });
  });
  // 2. New bricks take pool slots in brick-index order (as on the CPU), up to the limit.
  int* index = index_.data();
  int* flags = flags_.data();
  par::ForEach(par::Gpu{}, nb3, [=] __device__(int i) { flags[i] = vis[i] && index[i] < 0 ? 1 : 0; });
  std::size_t bytes = temp_.size();
  int* pos = scan_.data();
  HDRF_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(temp_.data(), bytes, flags, pos, nb3));
  int last[2];
  HDRF_CUDA_CHECK(cudaMemcpy(&last[0], pos + nb3 - 1, sizeof(int), cudaMemcpyDeviceToHost));
  HDRF_CUDA_CHECK(cudaMemcpy(&last[1], flags + nb3 - 1, sizeof(int), cudaMemcpyDeviceToHost));
  const int wanted = last[0] + last[1];
  const int max_bricks = int(std::min<std::size_t>(mirror_.max_bricks(), 1u << 30));
  const int allowed = std::min(wanted, max_bricks - allocated_);
  if (allowed < wanted) full_ = true;
  if (allocated_ + allowed > capacity_) Grow(allocated_ + allowed);
  if (allowed > 0) {
    BrickCoord* coords = coords_.data();
    std::uint8_t* coarse = coarse_.data();
    const int base = allocated_, nc = (nb + 3) / 4;
    par::ForEach(par::Gpu{}, nb3, [=] __device__(int i) {
      if (!flags[i] || pos[i] >= allowed) return;
      const int slot = base + pos[i];
      const int bx = i % bw, by = (i / bw) % bw, bz = i / (bw * bw);
      index[i] = slot;
      coords[slot] = {bx, by, bz};
      coarse[((bz >> 2) * nc + (by >> 2)) * nc + (bx >> 2)] = 1;
    });
    allocated_ += allowed;
  }
  // 3. The allocated visible bricks, compacted; one block of 512 threads per brick.
  par::ForEach(par::Gpu{}, nb3, [=] __device__(int i) { flags[i] = vis[i] && index[i] >= 0 ? 1 : 0; });
  bytes = temp_.size();
  HDRF_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(temp_.data(), bytes, flags, pos, nb3));
  int* todo = todo_.data();
  int* counts = counts_.data();
  par::ForEach(par::Gpu{}, nb3, [=] __device__(int i) {
    if (flags[i]) todo[pos[i]] = index[i];
    if (i == nb3 - 1) counts[1] = pos[i] + flags[i];
  });
  VisitEncoding(options().encoding, [&](auto tag) {
    IntegrateBricks<decltype(tag)>(a, reinterpret_cast<decltype(tag)*>(pool_.data()), coords_.data(), todo_.data(),
                                   counts_.data());
  });
  mirror_fresh_ = false;
}

void DeviceVolume::Raycast(const RaycastArgs& a, const RenderingViews& out) const {
  VisitEncoding(options().encoding, [&](auto tag) { RaycastInto(par::Gpu{}, view<decltype(tag)>(), a, out); });
}

const Volume& DeviceVolume::Download() {
  if (mirror_fresh_) return mirror_;
  std::vector<int> index(index_.size());
  index_.Download(index.data());
  std::vector<std::uint8_t> pool(std::size_t(allocated_) * 512 * std::size_t(vbytes_));
  std::vector<BrickCoord> bc(static_cast<std::size_t>(allocated_));
  if (allocated_ > 0) {
    cuda::CopyDeviceToHost(pool.data(), pool_.data(), pool.size());
    cuda::CopyDeviceToHost(bc.data(), coords_.data(), bc.size() * sizeof(BrickCoord));
  }
  std::vector<std::array<int, 3>> coords(bc.size());
  for (std::size_t i = 0; i < bc.size(); ++i) coords[i] = {bc[i].x, bc[i].y, bc[i].z};
  mirror_.Assign(std::move(index), std::move(pool), std::move(coords), full_);
  mirror_fresh_ = true;
  return mirror_;
}

}  // namespace hdrf::volume
