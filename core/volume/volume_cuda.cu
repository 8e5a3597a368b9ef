// The model on the GPU (device_volume.h): brick allocation through a per-frame hash set and
// the model's hash table, integration one block per brick, ray casting through the shared
// driver.
#include <cub/device/device_radix_sort.cuh>

#include <algorithm>
#include <array>
#include <vector>

#include "common/error.h"
#include "common/parallel_cuda.cuh"
#include "volume/device_volume.h"

namespace hdrf::volume {

namespace {
using ull = unsigned long long;

// Inserts a key into a table of HashView's layout; false where it was there already.
__device__ bool InsertKey(std::uint64_t* keys, int* values, std::uint32_t mask, std::uint64_t key, int value) {
  std::uint32_t h = HashBrickKey(key) & mask;
  for (std::uint32_t probes = 0; probes <= mask; ++probes) {
    const ull prev = atomicCAS(reinterpret_cast<ull*>(keys + h), ull(kEmptyKey), ull(key));
    if (prev == ull(kEmptyKey)) {
      if (values) values[h] = value;
      return true;
    }
    if (prev == ull(key)) return false;
    h = (h + 1) & mask;
  }
  return false;  // full: never, the tables are kept at most half full
}

// One block of 512 threads per visible brick (a voxel each), blocks striding over the list.
template <typename V>
__global__ void IntegrateBricksKernel(IntegrateArgs a, V* pool, const BrickCoord* coords, const int* todo,
                                      const int* counts) {
  const int n_todo = counts[2];
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

// Enters every allocated slot's brick and group into empty tables.
void InsertAll(std::uint64_t* keys, int* values, std::uint64_t* gkeys, int* gvalues, std::uint32_t mask,
               const BrickCoord* coords, int allocated) {
  par::ForEach(par::Gpu{}, allocated, [=] __device__(int s) {
    const BrickCoord c = coords[s];
    InsertKey(keys, values, mask, BrickKey(c.x, c.y, c.z), s);
    InsertKey(gkeys, gvalues, mask, GroupKey(c.x, c.y, c.z), 1);
  });
}

std::size_t PowerOfTwoAtLeast(std::size_t n) {
  std::size_t c = 1024;
  while (c < n) c *= 2;
  return c;
}

}  // namespace

DeviceVolume::DeviceVolume(const VolumeOptions& o) : mirror_(o), vbytes_(EncodingBytes(o.encoding)) {
  counts_ = DeviceBuffer<int>(3);
  HDRF_CUDA_CHECK(cudaMemset(counts_.data(), 0, 3 * sizeof(int)));
  RebuildTables(4096);
  Reserve(1024);
}

std::size_t DeviceVolume::bytes() const {
  return (keys_.size() + group_keys_.size()) * (sizeof(std::uint64_t) + sizeof(int)) +
         std::size_t(capacity_) * 512 * std::size_t(vbytes_);
}

void DeviceVolume::RebuildTables(std::size_t capacity) {
  keys_ = DeviceBuffer<std::uint64_t>(capacity);
  values_ = DeviceBuffer<int>(capacity);
  group_keys_ = DeviceBuffer<std::uint64_t>(capacity);
  group_values_ = DeviceBuffer<int>(capacity);
  HDRF_CUDA_CHECK(cudaMemset(keys_.data(), 0xff, capacity * sizeof(std::uint64_t)));
  HDRF_CUDA_CHECK(cudaMemset(group_keys_.data(), 0xff, capacity * sizeof(std::uint64_t)));
  if (allocated_ > 0)
    InsertAll(keys_.data(), values_.data(), group_keys_.data(), group_values_.data(), std::uint32_t(capacity - 1),
              coords_.data(), allocated_);
}

bool DeviceVolume::Reserve(int want) {
  if (2 * std::size_t(want) + 2 > keys_.size()) RebuildTables(PowerOfTwoAtLeast(4 * std::size_t(want)));
  if (want <= capacity_) return true;
  const int max_bricks = int(mirror_.max_bricks());
  const int cap = std::min(max_bricks, std::max(want, capacity_ + capacity_ / 2));
  std::size_t free_b = 0, total_b = 0;
  HDRF_CUDA_CHECK(cudaMemGetInfo(&free_b, &total_b));
  const std::size_t need = std::size_t(cap) * (512 * std::size_t(vbytes_) + sizeof(BrickCoord));
  // The grown pool lives beside the old one while it is copied; keep 256 MiB for the frames.
  if (need + (std::size_t(256) << 20) > free_b) {
    full_reason_ = "the GPU has " + std::to_string(free_b >> 20) + " MiB free, too little to grow the model past " +
                   std::to_string(allocated_) + " bricks";
    return false;
  }
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
  const long first = long(allocated_) * 512, count = long(cap) * 512 - first;
  VisitEncoding(options().encoding,
                [&](auto tag) { FillDefault(reinterpret_cast<decltype(tag)*>(pool_.data()), first, count); });
  capacity_ = cap;
  return true;
}

void DeviceVolume::Integrate(const IntegrateArgs& a, const Pose& T) {
  // 1. The distinct bricks in the truncation band of every second depth pixel: a per-frame
  // hash set (at most half full) collects them into a list.
  const int rw = (a.cam.width + 1) / 2, rh = (a.cam.height + 1) / 2;
  const std::size_t most = std::size_t(rw) * std::size_t(rh) * std::size_t(MaxBricksAlongRay(a.trunc_m, a.voxel_m));
  if (visible_.size() < most) {
    visible_ = DeviceBuffer<std::uint64_t>(most);
    fresh_ = DeviceBuffer<std::uint64_t>(most);
    fresh_sorted_ = DeviceBuffer<std::uint64_t>(most);
    todo_ = DeviceBuffer<int>(most);
    frame_set_ = DeviceBuffer<std::uint64_t>(PowerOfTwoAtLeast(2 * most));
    std::size_t sort_bytes = 0;
    HDRF_CUDA_CHECK(cub::DeviceRadixSort::SortKeys(nullptr, sort_bytes, fresh_.data(), fresh_sorted_.data(), int(most)));
    temp_ = DeviceBuffer<std::uint8_t>(std::max(sort_bytes, std::size_t(16)));
  }
  HDRF_CUDA_CHECK(cudaMemset(frame_set_.data(), 0xff, frame_set_.size() * sizeof(std::uint64_t)));
  HDRF_CUDA_CHECK(cudaMemset(counts_.data(), 0, 3 * sizeof(int)));
  std::uint64_t* set = frame_set_.data();
  std::uint64_t* visible = visible_.data();
  int* counts = counts_.data();
  const std::uint32_t set_mask = std::uint32_t(frame_set_.size() - 1);
  const RigidTransform Twc = ToRigidTransform(T);
  par::ForEachPixel(par::Gpu{}, rw, rh, [=] __device__(int x, int y) {
    std::uint64_t last = kEmptyKey;
    ForBricksAlongRay(a, Twc, 2 * x, 2 * y, [&](int bx, int by, int bz) {
      const std::uint64_t k = BrickKey(bx, by, bz);
      if (k == last) return;
      last = k;
      if (InsertKey(set, nullptr, set_mask, k, 0)) visible[atomicAdd(counts, 1)] = k;
    });
  });
  // 2. Split into bricks the model has (straight to the to-do list) and new ones.
  {
    const HashView table{keys_.data(), values_.data(), std::uint32_t(keys_.size() - 1)};
    std::uint64_t* fresh = fresh_.data();
    int* todo = todo_.data();
    par::ForEach(par::Gpu{}, int(most), [=] __device__(int i) {
      if (i >= counts[0]) return;
      const std::uint64_t k = visible[i];
      const int slot = table.Find(k);
      if (slot >= 0) todo[atomicAdd(counts + 2, 1)] = slot;
      else fresh[atomicAdd(counts + 1, 1)] = k;
    });
  }
  int n[3];
  HDRF_CUDA_CHECK(cudaMemcpy(n, counts_.data(), sizeof n, cudaMemcpyDeviceToHost));
  // 3. New bricks take the next slots in key order (as on the CPU), up to the limits.
  const int wanted = n[1];
  int allowed = 0;
  if (wanted > 0 && full_reason_.empty()) {
    std::size_t bytes = temp_.size();
    HDRF_CUDA_CHECK(cub::DeviceRadixSort::SortKeys(temp_.data(), bytes, fresh_.data(), fresh_sorted_.data(), wanted));
    allowed = std::min<int>(wanted, int(mirror_.max_bricks()) - allocated_);
    if (allowed < wanted)
      full_reason_ = "the model reached its memory budget of " + std::to_string(long(options().max_memory_mb)) +
                     " MiB (volume.max_memory_mb): " + std::to_string(mirror_.max_bricks()) + " bricks";
    if (allowed > 0 && !Reserve(allocated_ + allowed)) allowed = std::max(0, capacity_ - allocated_);
    if (allowed > 0) {
      const std::uint64_t* sorted = fresh_sorted_.data();
      BrickCoord* coords = coords_.data();
      std::uint64_t *keys = keys_.data(), *gkeys = group_keys_.data();
      int *values = values_.data(), *gvalues = group_values_.data(), *todo = todo_.data();
      const std::uint32_t mask = std::uint32_t(keys_.size() - 1);
      const int base = allocated_;
      par::ForEach(par::Gpu{}, allowed, [=] __device__(int i) {
        const std::uint64_t k = sorted[i];
        BrickCoord c;
        DecodeBrickKey(k, &c.x, &c.y, &c.z);
        coords[base + i] = c;
        InsertKey(keys, values, mask, k, base + i);
        InsertKey(gkeys, gvalues, mask, GroupKey(c.x, c.y, c.z), 1);
        todo[atomicAdd(counts + 2, 1)] = base + i;
      });
      std::vector<BrickCoord> added(static_cast<std::size_t>(allowed));
      cuda::CopyDeviceToHost(added.data(), coords_.data() + base, added.size() * sizeof(BrickCoord));
      Extend(added.data(), allowed);
      allocated_ += allowed;
    }
  }
  last_visible_ = n[2] + allowed;
  // 4. One block of 512 threads per visible allocated brick.
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
  std::vector<std::uint8_t> pool(std::size_t(allocated_) * 512 * std::size_t(vbytes_));
  std::vector<BrickCoord> bc(static_cast<std::size_t>(allocated_));
  if (allocated_ > 0) {
    cuda::CopyDeviceToHost(pool.data(), pool_.data(), pool.size());
    cuda::CopyDeviceToHost(bc.data(), coords_.data(), bc.size() * sizeof(BrickCoord));
  }
  std::vector<std::array<int, 3>> coords(bc.size());
  for (std::size_t i = 0; i < bc.size(); ++i) coords[i] = {bc[i].x, bc[i].y, bc[i].z};
  mirror_.Assign(std::move(pool), std::move(coords), full_reason_);
  mirror_fresh_ = true;
  return mirror_;
}

void DeviceVolume::Upload(const Volume& v) {
  const int n = int(v.allocated_bricks());
  allocated_ = 0;
  full_reason_.clear();
  if (!Reserve(std::max(n, 1024))) throw Error("the GPU has too little memory free for the model: " + full_reason_);
  VisitEncoding(options().encoding, [&](auto tag) {
    FillDefault(reinterpret_cast<decltype(tag)*>(pool_.data()), long(n) * 512, long(capacity_ - n) * 512);
  });
  if (n > 0) {
    std::vector<BrickCoord> bc(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) bc[std::size_t(i)] = {v.bricks()[std::size_t(i)][0], v.bricks()[std::size_t(i)][1], v.bricks()[std::size_t(i)][2]};
    cuda::CopyHostToDevice(pool_.data(), v.pool().data(), v.pool().size());
    cuda::CopyHostToDevice(coords_.data(), bc.data(), bc.size() * sizeof(BrickCoord));
  }
  allocated_ = 0;
  if (n > 0) {
    std::vector<BrickCoord> all(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) all[std::size_t(i)] = {v.bricks()[std::size_t(i)][0], v.bricks()[std::size_t(i)][1], v.bricks()[std::size_t(i)][2]};
    Extend(all.data(), n);
  }
  allocated_ = n;
  RebuildTables(keys_.size());
  full_reason_ = v.full_reason();
  mirror_.Assign(v.pool(), v.bricks(), v.full_reason());
  mirror_fresh_ = true;
}

void DeviceVolume::Extend(const BrickCoord* c, int n) {
  for (int i = 0; i < n; ++i) {
    const std::array<int, 3> p = {c[i].x, c[i].y, c[i].z};
    for (std::size_t k = 0; k < 3; ++k) {
      lo_[k] = allocated_ + i == 0 ? p[k] : std::min(lo_[k], p[k]);
      hi_[k] = allocated_ + i == 0 ? p[k] : std::max(hi_[k], p[k]);
    }
  }
}

std::array<Float3, 2> DeviceVolume::Bounds() const {
  if (allocated_ == 0) return {Float3{0, 0, 0}, Float3{0, 0, 0}};
  const float bs = options().voxel_m * kBrick;
  return {Float3{lo_[0] * bs, lo_[1] * bs, lo_[2] * bs}, Float3{(hi_[0] + 1) * bs, (hi_[1] + 1) * bs, (hi_[2] + 1) * bs}};
}

}  // namespace hdrf::volume
