// The GPU model's bricks moved between the device and the host (device_volume.h): the whole
// model copied down (Download) or up (Upload), the bricks changed since the last copy
// (CopyChanged), and, with a GPU budget, the bricks seen longest ago moved to host memory
// (SwapOut). Integration and ray casting are in volume_cuda.cu.
#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

#include "common/error.h"
#include "common/parallel_cuda.cuh"
#include "volume/device_volume.h"

namespace hdrf::volume {

namespace {
// Bricks keep[0..kept) of a pool (words per brick: `words`) into slots 0..kept of another.
void GatherBricks(const std::uint32_t* src, std::uint32_t* dst, const int* keep, long words, int kept,
                  const BrickCoord* old_c, BrickCoord* new_c) {
  par::ForEach(par::Gpu{}, kept, [=] __device__(int j) { new_c[j] = old_c[keep[j]]; });
  for (long first = 0; first < long(kept) * words; first += long(1) << 30) {
    const long n = std::min(long(kept) * words - first, long(1) << 30);
    par::ForEach(par::Gpu{}, int(n), [=] __device__(int i) {
      const long w = first + i;
      dst[w] = src[long(keep[w / words]) * words + w % words];
    });
  }
}
}  // namespace

void DeviceVolume::SwapOut(int count) {
  // The bricks seen longest ago, none of this frame's.
  std::vector<int> order;
  for (int s = 0; s < allocated_; ++s)
    if (last_seen_[std::size_t(s)] < frame_) order.push_back(s);
  count = std::min<int>(count, int(order.size()));
  if (count <= 0) return;
  std::nth_element(order.begin(), order.begin() + (count - 1), order.end(), [&](int a, int b) {
    return last_seen_[std::size_t(a)] != last_seen_[std::size_t(b)] ? last_seen_[std::size_t(a)] < last_seen_[std::size_t(b)]
                                                                     : a < b;
  });
  std::vector<char> out(static_cast<std::size_t>(allocated_), 0);
  for (int i = 0; i < count; ++i) out[std::size_t(order[std::size_t(i)])] = 1;
  std::vector<BrickCoord> coords(static_cast<std::size_t>(allocated_));
  cuda::CopyDeviceToHost(coords.data(), coords_.data(), coords.size() * sizeof(BrickCoord));
  std::vector<std::uint8_t> dirty(static_cast<std::size_t>(allocated_));
  cuda::CopyDeviceToHost(dirty.data(), dirty_.data(), dirty.size());
  const std::size_t B = 512 * std::size_t(vbytes_);
  std::vector<int> keep;
  std::vector<int> seen;
  for (int s = 0; s < allocated_; ++s) {
    if (out[std::size_t(s)]) {
      std::vector<std::uint8_t> voxels(B);
      cuda::CopyDeviceToHost(voxels.data(), pool_.data() + std::size_t(s) * B, B);
      const BrickCoord& c = coords[std::size_t(s)];
      host_[BrickKey(c.x, c.y, c.z)] = std::move(voxels);
      if (dirty[std::size_t(s)]) host_dirty_.insert(BrickKey(c.x, c.y, c.z));
      host_bytes_ += B + sizeof(std::uint64_t);
    } else {
      keep.push_back(s);
      seen.push_back(last_seen_[std::size_t(s)]);
    }
  }
  // The kept bricks, in slot order, into a fresh pool; the rest of it default voxels.
  DeviceBuffer<int> keep_d{std::max<std::size_t>(keep.size(), 1)};
  if (!keep.empty()) cuda::CopyHostToDevice(keep_d.data(), keep.data(), keep.size() * sizeof(int));
  DeviceBuffer<std::uint8_t> pool{std::size_t(capacity_) * B};
  DeviceBuffer<BrickCoord> moved{std::size_t(capacity_)};
  const int kept = int(keep.size());
  GatherBricks(reinterpret_cast<const std::uint32_t*>(pool_.data()), reinterpret_cast<std::uint32_t*>(pool.data()),
               keep_d.data(), long(B / 4), kept, coords_.data(), moved.data());
  pool_ = std::move(pool);
  coords_ = std::move(moved);
  FillDefaultSlots(kept);
  last_seen_ = std::move(seen);
  // The kept bricks' change flags follow them to their new slots.
  std::vector<std::uint8_t> kept_dirty(dirty_.size(), 0);
  for (int j = 0; j < kept; ++j) kept_dirty[std::size_t(j)] = dirty[std::size_t(keep[std::size_t(j)])];
  cuda::CopyHostToDevice(dirty_.data(), kept_dirty.data(), kept_dirty.size());
  swapped_out_ += count;
  allocated_ = kept;
  RebuildTables(keys_.size());
  mirror_fresh_ = false;
}

const Volume& DeviceVolume::Download() {
  Settled();
  if (mirror_fresh_) return mirror_;
  std::vector<std::uint8_t> pool(std::size_t(allocated_) * 512 * std::size_t(vbytes_));
  std::vector<BrickCoord> bc(static_cast<std::size_t>(allocated_));
  if (allocated_ > 0) {
    cuda::CopyDeviceToHost(pool.data(), pool_.data(), pool.size());
    cuda::CopyDeviceToHost(bc.data(), coords_.data(), bc.size() * sizeof(BrickCoord));
  }
  std::vector<std::array<int, 3>> coords(bc.size());
  for (std::size_t i = 0; i < bc.size(); ++i) coords[i] = {bc[i].x, bc[i].y, bc[i].z};
  // Bricks in host memory follow, in key order.
  if (!host_.empty()) {
    std::vector<std::uint64_t> keys;
    for (const auto& h : host_) keys.push_back(h.first);
    std::sort(keys.begin(), keys.end());
    for (const std::uint64_t k : keys) {
      const std::vector<std::uint8_t>& v = host_.at(k);
      pool.insert(pool.end(), v.begin(), v.end());
      std::array<int, 3> c;
      DecodeBrickKey(k, &c[0], &c[1], &c[2]);
      coords.push_back(c);
    }
  }
  mirror_.Assign(std::move(pool), std::move(coords), full_reason_);
  mirror_fresh_ = true;
  return mirror_;
}

void DeviceVolume::Upload(const Volume& v) {
  Settled();
  const int n = int(v.allocated_bricks());
  // With a GPU budget the model may not fit: the bricks allocated last (nearest the end of
  // the scan, where it goes on) go to the GPU, the earlier ones to host memory.
  const int gpu_budget = int(options().gpu_bricks());
  const int first = gpu_budget > 0 && n > gpu_budget ? n - (gpu_budget - gpu_budget / 8) : 0;
  const int on_gpu = n - first;
  const std::size_t B = 512 * std::size_t(vbytes_);
  allocated_ = 0;
  host_.clear();
  host_bytes_ = 0;
  swapped_out_ = swapped_in_ = 0;
  full_reason_.clear();
  if (!Reserve(std::max(on_gpu, 1024))) throw Error("the GPU has too little memory free for the model: " + full_reason_);
  FillDefaultSlots(on_gpu);
  std::vector<BrickCoord> all(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) all[std::size_t(i)] = {v.bricks()[std::size_t(i)][0], v.bricks()[std::size_t(i)][1], v.bricks()[std::size_t(i)][2]};
  host_dirty_.clear();
  HDRF_CUDA_CHECK(cudaMemset(dirty_.data(), 0, dirty_.size()));
  if (on_gpu > 0) HDRF_CUDA_CHECK(cudaMemset(dirty_.data(), 1, std::size_t(on_gpu)));
  for (int i = 0; i < first; ++i) {
    const std::uint8_t* src = v.pool().data() + std::size_t(i) * B;
    host_dirty_.insert(BrickKey(all[std::size_t(i)].x, all[std::size_t(i)].y, all[std::size_t(i)].z));
    host_[BrickKey(all[std::size_t(i)].x, all[std::size_t(i)].y, all[std::size_t(i)].z)] = std::vector<std::uint8_t>(src, src + B);
    host_bytes_ += B + sizeof(std::uint64_t);
  }
  if (on_gpu > 0) {
    cuda::CopyHostToDevice(pool_.data(), v.pool().data() + std::size_t(first) * B, std::size_t(on_gpu) * B);
    cuda::CopyHostToDevice(coords_.data(), all.data() + first, std::size_t(on_gpu) * sizeof(BrickCoord));
  }
  box_ = {};
  if (n > 0) Extend(all.data(), n);
  WriteBox();
  allocated_ = on_gpu;
  frame_ = 0;
  last_seen_.assign(std::size_t(on_gpu), 0);
  RebuildTables(keys_.size());
  full_reason_ = v.full_reason();
  mirror_.Assign(v.pool(), v.bricks(), v.full_reason());
  mirror_fresh_ = first == 0;  // else the mirror's slot order is the download's, not the file's
}

BrickSet DeviceVolume::CopyChanged() {
  Settled();
  BrickSet out;
  const std::size_t B = 512 * std::size_t(vbytes_);
  std::vector<int> slots;
  if (allocated_ > 0) {
    std::vector<std::uint8_t> dirty(static_cast<std::size_t>(allocated_));
    cuda::CopyDeviceToHost(dirty.data(), dirty_.data(), dirty.size());
    HDRF_CUDA_CHECK(cudaMemset(dirty_.data(), 0, dirty.size()));
    for (int s = 0; s < allocated_; ++s)
      if (dirty[std::size_t(s)]) slots.push_back(s);
  }
  const int n = int(slots.size());
  out.coords.resize(slots.size() + host_dirty_.size());
  out.voxels.resize(out.coords.size() * B);
  if (n > 0) {
    DeviceBuffer<int> list{slots.size()};
    cuda::CopyHostToDevice(list.data(), slots.data(), slots.size() * sizeof(int));
    DeviceBuffer<std::uint8_t> voxels{slots.size() * B};
    DeviceBuffer<BrickCoord> coords{slots.size()};
    GatherBricks(reinterpret_cast<const std::uint32_t*>(pool_.data()), reinterpret_cast<std::uint32_t*>(voxels.data()),
                 list.data(), long(B / 4), n, coords_.data(), coords.data());
    std::vector<BrickCoord> c(slots.size());
    cuda::CopyDeviceToHost(c.data(), coords.data(), c.size() * sizeof(BrickCoord));
    cuda::CopyDeviceToHost(out.voxels.data(), voxels.data(), slots.size() * B);
    for (int i = 0; i < n; ++i) out.coords[std::size_t(i)] = {c[std::size_t(i)].x, c[std::size_t(i)].y, c[std::size_t(i)].z};
  }
  std::size_t k = std::size_t(n);
  for (const std::uint64_t key : host_dirty_) {
    const auto it = host_.find(key);
    if (it == host_.end()) continue;
    DecodeBrickKey(key, &out.coords[k][0], &out.coords[k][1], &out.coords[k][2]);
    std::memcpy(out.voxels.data() + k * B, it->second.data(), B);
    ++k;
  }
  out.coords.resize(k);
  out.voxels.resize(k * B);
  host_dirty_.clear();
  return out;
}

}  // namespace hdrf::volume
