// The model on the GPU (device_volume.h): brick allocation through a per-frame hash set and
// the model's hash table, integration one block per brick, ray casting through the shared
// driver. Moving bricks between the device and the host: volume_transfer_cuda.cu.
#include <cub/device/device_radix_sort.cuh>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <vector>

#include "common/error.h"
#include "common/parallel_cuda.cuh"
#include "volume/device_volume.h"

namespace hdrf::volume {

// The tables a new brick enters (PlaceBrick).
struct PlaceTables {
  std::uint64_t *keys, *gkeys;
  int *values, *gvalues;
  std::uint32_t mask;
  BrickCoord* coords;
  int* todo;
};
// The frame's new bricks as the integration places them itself (the device's path, no host
// in between): the counts[1] keys of `fresh` take slots base + their rank in key order (as on
// the host and the CPU), all of them or, where they are more than `room`, none (counts[3]
// says so; DeviceVolume::Settle places them). counts[4]: the number placed. The frame's set
// (`set`, each visible key's entry at `set_at`) is emptied for the next frame.
struct NewBricks {
  const std::uint64_t* fresh = nullptr;  // null: the host's path (placed and emptied before)
  int room = 0, base = 0;
  PlaceTables t{};
  int* box = nullptr;
  std::uint64_t* set = nullptr;
  const std::uint32_t* set_at = nullptr;
};

namespace {
using ull = unsigned long long;
int place_limit = DeviceVolume::kPlaceMost;  // SetDevicePlaceLimit

// Inserts a key into a table of HashView's layout; false where it was there already. Each
// slot is read first and only an empty one is claimed atomically: a key is set once and never
// changes while keys are inserted, so a slot seen holding a key holds it. (Hundreds of a
// frame's depth rays name each brick at 2 cm voxels: an atomic on every visit queued them all
// on one address.)
// `at`, where given: the slot the key was put in.
__device__ bool InsertKey(std::uint64_t* keys, int* values, std::uint32_t mask, std::uint64_t key, int value,
                          std::uint32_t* at = nullptr) {
  std::uint32_t h = HashBrickKey(key) & mask;
  for (std::uint32_t probes = 0; probes <= mask; ++probes) {
    const ull seen = __ldcg(reinterpret_cast<const ull*>(keys + h));
    if (seen == ull(key)) return false;
    if (seen != ull(kEmptyKey)) {
      h = (h + 1) & mask;
      continue;
    }
    const ull prev = atomicCAS(reinterpret_cast<ull*>(keys + h), ull(kEmptyKey), ull(key));
    if (prev == ull(kEmptyKey)) {
      if (values) values[h] = value;
      if (at) *at = h;
      return true;
    }
    if (prev == ull(key)) return false;
    h = (h + 1) & mask;
  }
  return false;  // full: never, the tables are kept at most half full
}

// The box of the allocated bricks as the device keeps it (DeviceVolume::device_box).
__device__ void AddToBox(int* box, const BrickCoord& c) {
  atomicMin(box + 0, c.x);
  atomicMin(box + 1, c.y);
  atomicMin(box + 2, c.z);
  atomicMax(box + 3, c.x);
  atomicMax(box + 4, c.y);
  atomicMax(box + 5, c.z);
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

// Visible keys the table has go to the to-do list (their slots), the others to `fresh`;
// `capacity` threads, the first counts[0] of which have a key. Each key's entry in the
// frame's set (its slot there: `at`) is emptied for the next frame.
void SplitKeys(HashView table, const std::uint64_t* visible, int capacity, int* counts, std::uint64_t* fresh, int* todo,
               std::uint64_t* set, const std::uint32_t* at) {
  par::ForEach(par::Gpu{}, capacity, [=] __device__(int i) {
    if (i >= counts[0]) return;
    const std::uint64_t k = visible[i];
    set[at[i]] = kEmptyKey;
    const int slot = table.Find(k);
    if (slot >= 0) todo[atomicAdd(counts + 2, 1)] = slot;
    else fresh[atomicAdd(counts + 1, 1)] = k;
  });
}

std::size_t PowerOfTwoAtLeast(std::size_t n) {
  std::size_t c = 1024;
  while (c < n) c *= 2;
  return c;
}


// A key's place among k[0..n) (the i-th of them): the number of keys before it, smaller or
// equal and earlier. The same order as the radix sort's, without its passes: a frame's new
// bricks are mostly tens, where the radix sort took 13 us on an H100.
__device__ int RankOf(const std::uint64_t* k, int n, int i) {
  const std::uint64_t v = k[i];
  int rank = 0;
  for (int j = 0; j < n; ++j) rank += (k[j] < v || (k[j] == v && j < i)) ? 1 : 0;
  return rank;
}
// A few keys sorted by rank in one block.
constexpr int kRankSortMost = 1024;
__global__ void __launch_bounds__(kRankSortMost) RankSortKernel(const std::uint64_t* in, int n, std::uint64_t* out) {
  __shared__ std::uint64_t k[kRankSortMost];
  for (int i = threadIdx.x; i < n; i += blockDim.x) k[i] = in[i];
  __syncthreads();
  for (int i = threadIdx.x; i < n; i += blockDim.x) out[RankOf(k, n, i)] = k[i];
}

// A new brick into `slot`: its coordinates, the brick and group tables, the box.
__device__ void PlaceBrick(const PlaceTables& t, std::uint64_t key, int slot, int* box) {
  BrickCoord c;
  DecodeBrickKey(key, &c.x, &c.y, &c.z);
  t.coords[slot] = c;
  InsertKey(t.keys, t.values, t.mask, key, slot);
  InsertKey(t.gkeys, t.gvalues, t.mask, GroupKey(c.x, c.y, c.z), 1);
  AddToBox(box, c);
}

// A key's rank among k[0..n) (RankOf) counted by a whole block; every thread gets it.
__device__ int BlockRankOf(const std::uint64_t* k, int n, int i, int* shared_sum) {
  const std::uint64_t v = k[i];
  int part = 0;
  for (int j = int(threadIdx.x); j < n; j += int(blockDim.x)) part += (k[j] < v || (k[j] == v && j < i)) ? 1 : 0;
  for (int d = 16; d > 0; d /= 2) part += __shfl_down_sync(0xffffffffu, part, d);
  if (threadIdx.x == 0) *shared_sum = 0;
  __syncthreads();
  if ((threadIdx.x & 31) == 0) atomicAdd(shared_sum, part);
  __syncthreads();
  const int rank = *shared_sum;
  __syncthreads();  // (read by all before the next brick sets it again)
  return rank;
}

// One block of 512 threads per brick (a voxel each), blocks striding over the to-do list's
// entries from `first` to its count (counts[2], read on the device), then, on the device's
// path, over the new bricks, each placed by its block first. Each brick is flagged as
// changed (CopyChanged).
template <typename V>
__global__ void __launch_bounds__(512) IntegrateBricksKernel(IntegrateArgs a, V* pool, const BrickCoord* coords,
                                                             const int* todo, int* counts, int first,
                                                             std::uint8_t* dirty, NewBricks nb) {
  __shared__ int rank_sum;
  const int n_todo = counts[2];
  int n_new = 0;
  if (nb.fresh) {
    const int wanted = counts[1];
    n_new = wanted <= nb.room ? wanted : 0;
    if (blockIdx.x == 0 && threadIdx.x == 0) {
      if (wanted > nb.room) counts[3] = 1;
      else counts[4] = wanted;
    }
    const int n_visible = counts[0];
    for (int i = int(blockIdx.x * blockDim.x + threadIdx.x); i < n_visible; i += int(gridDim.x * blockDim.x))
      nb.set[nb.set_at[i]] = kEmptyKey;
  }
  for (int k = first + int(blockIdx.x); k < n_todo + n_new; k += int(gridDim.x)) {
    int slot;
    BrickCoord bc;
    if (k < n_todo) {
      slot = todo[k];
      bc = coords[slot];
    } else {
      const int rank = BlockRankOf(nb.fresh, n_new, k - n_todo, &rank_sum);
      const std::uint64_t key = nb.fresh[k - n_todo];
      slot = nb.base + rank;
      DecodeBrickKey(key, &bc.x, &bc.y, &bc.z);
      if (threadIdx.x == 0) PlaceBrick(nb.t, key, slot, nb.box);  // (no to-do entry: only the host's path reads them)
    }
    if (threadIdx.x == 0) dirty[slot] = 1;
    // The voxel is read first, its wait beside the image reads', and written back where
    // it changed.
    V& stored = pool[long(slot) * 512 + threadIdx.x];
    V voxel = stored;
    if (IntegrateVoxel(a, bc.x, bc.y, bc.z, int(threadIdx.x), voxel)) stored = voxel;
  }
}
template <typename V>
void IntegrateBricks(const IntegrateArgs& a, V* pool, const BrickCoord* coords, const int* todo, int* counts,
                     int first, std::uint8_t* dirty, const NewBricks& nb) {
  IntegrateBricksKernel<V><<<1024, 512>>>(a, pool, coords, todo, counts, first, dirty, nb);
  HDRF_CUDA_CHECK_LAUNCH();
}

// `n` new bricks, sorted, into slots base.. (the host's way: Integrate without room on the
// device, or with a GPU budget); their to-do entries after those there are (counts[2]).
void PlaceSorted(const std::uint64_t* sorted, int n, int base, PlaceTables t, int* counts, int* box) {
  par::ForEach(par::Gpu{}, n, [=] __device__(int i) {
    PlaceBrick(t, sorted[i], base + i, box);
    t.todo[atomicAdd(counts + 2, 1)] = base + i;
  });
}
}  // namespace

void SetDevicePlaceLimit(int most) { place_limit = most < 0 ? DeviceVolume::kPlaceMost : std::min(most, int(DeviceVolume::kPlaceMost)); }

DeviceVolume::DeviceVolume(const VolumeOptions& o) : mirror_(o), vbytes_(EncodingBytes(o.encoding)) {
  counts_ = DeviceBuffer<int>(kCounts);
  HDRF_CUDA_CHECK(cudaMemset(counts_.data(), 0, kCounts * sizeof(int)));
  WriteBox();
  HDRF_CUDA_CHECK(cudaMallocHost(&counts_host_, kCounts * sizeof(int)));
  HDRF_CUDA_CHECK(cudaEventCreateWithFlags(&counted_, cudaEventDisableTiming));
  RebuildTables(4096);
  Reserve(1024);
}

DeviceVolume::~DeviceVolume() {
  if (pending_) cudaStreamSynchronize(0);
  cudaEventDestroy(counted_);
  cudaFreeHost(counts_host_);
}

void DeviceVolume::Settled() const {
  if (pending_) throw Error("internal: the GPU model was read on the host before its last frame was settled");
}

std::size_t DeviceVolume::bytes() const { return gpu_bytes() + host_bytes_; }

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
  const int gpu_budget = int(options().gpu_bricks());
  const int max_bricks = gpu_budget > 0 ? std::min(gpu_budget, int(mirror_.max_bricks())) : int(mirror_.max_bricks());
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
  DeviceBuffer<std::uint8_t> dirty{std::size_t(cap)};
  HDRF_CUDA_CHECK(cudaMemset(dirty.data(), 0, std::size_t(cap)));
  if (allocated_ > 0)
    HDRF_CUDA_CHECK(cudaMemcpy(dirty.data(), dirty_.data(), std::size_t(allocated_), cudaMemcpyDeviceToDevice));
  pool_ = std::move(pool);
  coords_ = std::move(coords);
  dirty_ = std::move(dirty);
  capacity_ = cap;
  FillDefaultSlots(allocated_);
  return true;
}

void DeviceVolume::Integrate(const IntegrateArgs& a, const Pose& T) {
  Settled();
  // 1. The distinct bricks in the truncation band of every second depth pixel: a per-frame
  // hash set (at most half full) collects them into a list.
  const int rw = (a.cam.width + 1) / 2, rh = (a.cam.height + 1) / 2;
  const std::size_t most = std::size_t(rw) * std::size_t(rh) * std::size_t(MaxBricksAlongRay(a.trunc_m, a.voxel_m));
  if (visible_.size() < most) {
    visible_ = DeviceBuffer<std::uint64_t>(most);
    visible_at_ = DeviceBuffer<std::uint32_t>(most);
    fresh_ = DeviceBuffer<std::uint64_t>(most);
    fresh_sorted_ = DeviceBuffer<std::uint64_t>(most);
    todo_ = DeviceBuffer<int>(most);
    frame_set_ = DeviceBuffer<std::uint64_t>(PowerOfTwoAtLeast(2 * most));
    // Empty once: each frame empties the entries it filled (SplitKeys or the integration).
    HDRF_CUDA_CHECK(cudaMemsetAsync(frame_set_.data(), 0xff, frame_set_.size() * sizeof(std::uint64_t), 0));
    std::size_t sort_bytes = 0;
    HDRF_CUDA_CHECK(cub::DeviceRadixSort::SortKeys(nullptr, sort_bytes, fresh_.data(), fresh_sorted_.data(), int(most)));
    temp_ = DeviceBuffer<std::uint8_t>(std::max(sort_bytes, std::size_t(16)));
  }
  HDRF_CUDA_CHECK(cudaMemsetAsync(counts_.data(), 0, kBoxAt * sizeof(int), 0));
  const int gpu_budget = int(options().gpu_bricks());
  // The device places the new bricks itself where it can: up to a block's worth, within the
  // pool's room, the tables' half and the memory limit; no GPU budget (its bookkeeping is
  // the host's). Then the whole frame is queued without a wait, each visible key split as
  // it is found (the model's bricks to the to-do list, the others to `fresh`), and the new
  // bricks placed by the integration's blocks. Settle reads the counts (or places what the
  // device could not).
  const int room = std::min({place_limit, capacity_ - allocated_, int((keys_.size() - 2) / 2) - allocated_,
                             int(mirror_.max_bricks()) - allocated_});
  const bool on_device = gpu_budget <= 0 && host_.empty() && full_reason_.empty() && room > 0;
  std::uint64_t* set = frame_set_.data();
  std::uint64_t* visible = visible_.data();
  std::uint32_t* visible_at = visible_at_.data();
  std::uint64_t* fresh = on_device ? fresh_.data() : nullptr;
  int* todo = todo_.data();
  int* counts = counts_.data();
  const HashView table{keys_.data(), values_.data(), std::uint32_t(keys_.size() - 1)};
  const std::uint32_t set_mask = std::uint32_t(frame_set_.size() - 1);
  const RigidTransform Twc = ToRigidTransform(T);
  par::ForEachPixel(par::Gpu{}, rw, rh, [=] __device__(int x, int y) {
    std::uint64_t last = kEmptyKey;
    ForBricksAlongRay(a, Twc, 2 * x, 2 * y, [&](int bx, int by, int bz) {
      const std::uint64_t k = BrickKey(bx, by, bz);
      if (k == last) return;
      last = k;
      std::uint32_t at = 0;
      if (InsertKey(set, nullptr, set_mask, k, 0, &at)) {
        const int i = atomicAdd(counts, 1);
        visible[i] = k;
        visible_at[i] = at;
        if (!fresh) return;
        const int slot = table.Find(k);
        if (slot >= 0) todo[atomicAdd(counts + 2, 1)] = slot;
        else fresh[atomicAdd(counts + 1, 1)] = k;
      }
    });
  });
  ++frame_;
  mirror_fresh_ = false;
  if (on_device) {
    NewBricks nb;
    nb.fresh = fresh_.data();
    nb.room = room;
    nb.base = allocated_;
    nb.t = PlaceTables{keys_.data(), group_keys_.data(), values_.data(), group_values_.data(),
                       std::uint32_t(keys_.size() - 1), coords_.data(), todo_.data()};
    nb.box = counts_.data() + kBoxAt;
    nb.set = frame_set_.data();
    nb.set_at = visible_at_.data();
    IntegrateFrom(a, 0, nb);
    pending_args_ = a;
    pending_ = true;
    counts_queued_ = false;  // (QueueCounts: behind the next ray cast's start, or in Settle)
    return;
  }
  // 2. Split into bricks the model has (straight to the to-do list) and new ones. With a GPU
  // budget that the new ones would pass, the bricks seen longest ago move to host memory
  // first (never one seen in this frame), and the split is made again on the compacted pool.
  int n[3];
  SplitVisible(n);
  if (gpu_budget > 0) {
    last_seen_.resize(std::size_t(allocated_), 0);
    std::vector<int> seen(static_cast<std::size_t>(n[2]));
    if (n[2] > 0) cuda::CopyDeviceToHost(seen.data(), todo_.data(), seen.size() * sizeof(int));
    for (int s : seen) last_seen_[std::size_t(s)] = frame_;
    if (allocated_ + n[1] > gpu_budget) {
      const int room_left = gpu_budget - gpu_budget / 8;  // slack: bricks move out in batches
      const int out = std::min(allocated_ + n[1] - room_left, allocated_ - n[2]);
      if (out > 0) {
        SwapOut(out);
        SplitVisible(n);
      }
    }
  }
  // 3. New bricks take the next slots in key order (as on the CPU), up to the limits.
  last_visible_ = n[2] + PlaceOnHost(n[1]);
  // 4. One block of 512 threads per visible allocated brick.
  IntegrateFrom(a, 0);
}

void DeviceVolume::QueueCounts() {
  if (!pending_ || counts_queued_) return;
  HDRF_CUDA_CHECK(cudaMemcpyAsync(counts_host_, counts_.data(), kCounts * sizeof(int), cudaMemcpyDeviceToHost, 0));
  HDRF_CUDA_CHECK(cudaEventRecord(counted_, 0));
  counts_queued_ = true;
}

bool DeviceVolume::Settle(cudaEvent_t after) {
  if (!pending_) return false;
  QueueCounts();
  pending_ = false;
  HDRF_CUDA_CHECK(cudaEventSynchronize(counted_));
  const int* c = counts_host_;
  ReadBoxFrom(c + kBoxAt);
  if (!c[3]) {
    allocated_ += c[4];
    last_visible_ = c[2] + c[4];
    return false;
  }
  // The device left the new bricks (more than it places at once, or than the pool had room
  // for); the visible bricks the model had are fused. The new ones are placed and fused now.
  const int todo = c[2];
  if (after) HDRF_CUDA_CHECK(cudaStreamWaitEvent(0, after, 0));
  const int placed = PlaceOnHost(c[1]);
  last_visible_ = todo + placed;
  if (placed == 0) return false;
  IntegrateFrom(pending_args_, todo);
  return true;
}

void DeviceVolume::IntegrateFrom(const IntegrateArgs& a, int first, const NewBricks& nb) {
  VisitEncoding(options().encoding, [&](auto tag) {
    IntegrateBricks<decltype(tag)>(a, reinterpret_cast<decltype(tag)*>(pool_.data()), coords_.data(), todo_.data(),
                                   counts_.data(), first, dirty_.data(), nb);
  });
}
void DeviceVolume::IntegrateFrom(const IntegrateArgs& a, int first) { IntegrateFrom(a, first, NewBricks{}); }

void DeviceVolume::FillDefaultSlots(int first) {
  VisitEncoding(options().encoding, [&](auto tag) {
    FillDefault(reinterpret_cast<decltype(tag)*>(pool_.data()), long(first) * 512, long(capacity_ - first) * 512);
  });
}

void DeviceVolume::ReadBoxFrom(const int* b) {
  box_ = {};
  if (b[0] > b[3]) return;
  box_.empty = false;
  for (std::size_t k = 0; k < 3; ++k) box_.lo[k] = b[k], box_.hi[k] = b[3 + k];
}

int DeviceVolume::PlaceOnHost(int wanted) {
  if (wanted <= 0 || !full_reason_.empty()) return 0;
  const int gpu_budget = int(options().gpu_bricks());
  std::size_t bytes = temp_.size();
  if (wanted <= kRankSortMost) {
    RankSortKernel<<<1, (wanted + 31) / 32 * 32>>>(fresh_.data(), wanted, fresh_sorted_.data());
    HDRF_CUDA_CHECK_LAUNCH();
  } else {
    HDRF_CUDA_CHECK(cub::DeviceRadixSort::SortKeys(temp_.data(), bytes, fresh_.data(), fresh_sorted_.data(), wanted));
  }
  int allowed = std::min<int>(wanted, int(mirror_.max_bricks()) - int(allocated_bricks()));
  if (allowed < wanted)
    full_reason_ = "the model reached its memory budget of " + std::to_string(long(options().max_memory_mb)) +
                   " MiB (volume.max_memory_mb): " + std::to_string(mirror_.max_bricks()) + " bricks";
  if (gpu_budget > 0 && allocated_ + allowed > gpu_budget) {
    allowed = std::max(0, gpu_budget - allocated_);
    if (full_reason_.empty())
      full_reason_ = "one view needs more bricks than the GPU budget of " +
                     std::to_string(long(options().gpu_memory_mb)) + " MiB holds (volume.gpu_memory_mb: " +
                     std::to_string(gpu_budget) + " bricks)";
  }
  if (allowed > 0 && !Reserve(allocated_ + allowed)) allowed = std::max(0, capacity_ - allocated_);
  if (allowed <= 0) return 0;
  const int base = allocated_;
  PlaceSorted(fresh_sorted_.data(), allowed, base,
              PlaceTables{keys_.data(), group_keys_.data(), values_.data(), group_values_.data(),
                          std::uint32_t(keys_.size() - 1), coords_.data(), todo_.data()},
              counts_.data(), counts_.data() + kBoxAt);
  std::vector<BrickCoord> added(static_cast<std::size_t>(allowed));
  cuda::CopyDeviceToHost(added.data(), coords_.data() + base, added.size() * sizeof(BrickCoord));
  Extend(added.data(), allowed);
  // Bricks that had moved to host memory come back into their new slots.
  if (!host_.empty()) {
    std::vector<std::uint64_t> host_keys(static_cast<std::size_t>(allowed));
    cuda::CopyDeviceToHost(host_keys.data(), fresh_sorted_.data(), host_keys.size() * sizeof(std::uint64_t));
    const std::size_t B = 512 * std::size_t(vbytes_);
    for (int i = 0; i < allowed; ++i) {
      const auto it = host_.find(host_keys[std::size_t(i)]);
      if (it == host_.end()) continue;
      cuda::CopyHostToDevice(pool_.data() + std::size_t(base + i) * B, it->second.data(), B);
      host_dirty_.erase(it->first);
      host_.erase(it);
      host_bytes_ -= B + sizeof(std::uint64_t);
      ++swapped_in_;
    }
  }
  allocated_ += allowed;
  if (gpu_budget > 0) last_seen_.resize(std::size_t(allocated_), frame_);
  return allowed;
}

int DeviceVolume::SplitVisible(int* n) {
  HDRF_CUDA_CHECK(cudaMemset(counts_.data() + 1, 0, 2 * sizeof(int)));
  // Over the list's capacity: the kernel reads the visible count on the device (no wait here).
  SplitKeys(HashView{keys_.data(), values_.data(), std::uint32_t(keys_.size() - 1)}, visible_.data(),
            int(visible_.size()), counts_.data(), fresh_.data(), todo_.data(), frame_set_.data(), visible_at_.data());
  HDRF_CUDA_CHECK(cudaMemcpy(n, counts_.data(), 3 * sizeof(int), cudaMemcpyDeviceToHost));
  return n[0];
}

std::size_t DeviceVolume::gpu_bytes() const {
  Settled();
  return (keys_.size() + group_keys_.size()) * (sizeof(std::uint64_t) + sizeof(int)) +
         std::size_t(capacity_) * 512 * std::size_t(vbytes_);
}

void RaycastGuideOnGpu(ImageView<const float> depth, float margin_m, const ImageView<float>& tiles) {
  RaycastGuide(par::Gpu{}, depth, margin_m, tiles);
}

void DeviceVolume::Raycast(const RaycastArgs& a, const RenderingViews& out, cudaStream_t stream) const {
  VisitEncoding(options().encoding, [&](auto tag) { RaycastInto(par::Gpu{stream}, view<decltype(tag)>(), a, out); });
}

void DeviceVolume::Extend(const BrickCoord* c, int n) {
  for (int i = 0; i < n; ++i) box_.Add(c[i].x, c[i].y, c[i].z);
}

void DeviceVolume::WriteBox() {
  int b[6];
  for (std::size_t k = 0; k < 3; ++k) {
    b[k] = box_.empty ? std::numeric_limits<int>::max() : box_.lo[k];
    b[3 + k] = box_.empty ? std::numeric_limits<int>::min() : box_.hi[k];
  }
  cuda::CopyHostToDevice(counts_.data() + kBoxAt, b, sizeof b);
}

std::array<Float3, 2> DeviceVolume::Bounds() const {
  Settled();
  if (allocated_ == 0) return {Float3{0, 0, 0}, Float3{0, 0, 0}};
  return box_.World(options().voxel_m * kBrick);
}

}  // namespace hdrf::volume
