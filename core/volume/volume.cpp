#include "volume/volume.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <omp.h>

#include "common/error.h"
#include "volume/project_brick.h"
#include "volume/raycast_driver.h"

namespace hdrf::volume {

VoxelEncoding ParseVoxelEncoding(const std::string& s) {
  if (s == "full") return VoxelEncoding::kFull;
  if (s == "no-nr") return VoxelEncoding::kNoNr;
  if (s == "compact") return VoxelEncoding::kCompact;
  throw SettingError("volume.voxel", "unknown voxel encoding '" + s + "'; choose full, no-nr or compact");
}
const char* VoxelEncodingName(VoxelEncoding e) {
  switch (e) {
    case VoxelEncoding::kFull: return "full";
    case VoxelEncoding::kNoNr: return "no-nr";
    case VoxelEncoding::kCompact: return "compact";
  }
  return "?";
}

void VolumeOptions::Check() const {
  if (!(voxel_m >= 1e-3f && voxel_m <= 1.f))
    throw SettingError("volume.voxel_m", "must be between 0.001 and 1 metre, got " + std::to_string(voxel_m));
  if (!(truncation_voxels >= 1 && truncation_voxels <= 64))
    throw SettingError("volume.truncation_voxels", "must be between 1 and 64 voxels");
  if (!(max_weight > 0) || !std::isfinite(max_weight)) throw SettingError("volume.max_weight", "must be > 0");
  if (!(max_radiance_weight > 0) || !std::isfinite(max_radiance_weight))
    throw SettingError("volume.max_radiance_weight", "must be > 0");
  if (encoding == VoxelEncoding::kCompact && (max_weight > 65 || max_radiance_weight > 65))
    throw SettingError(max_weight > 65 ? "volume.max_weight" : "volume.max_radiance_weight",
                       "compact voxels hold weights up to 65; lower the cap or use volume.voxel full");
  if (!(tau1_deg > 0 && tau1_deg <= 90)) throw SettingError("volume.tau1_deg", "must be in (0, 90] degrees");
  if (!(tau0 >= 0 && tau0 < 1)) throw SettingError("volume.tau0", "must be in [0, 1)");
  if (!(raycast_near_m > 0) || !(raycast_far_m > raycast_near_m) || !std::isfinite(raycast_far_m))
    throw SettingError("volume.raycast_far_m", "ray casting needs 0 < near < far (finite metres)");
  if (!(max_memory_mb >= 1 && max_memory_mb <= double(1 << 24)))
    throw SettingError("volume.max_memory_mb", "must be between 1 MiB and 16 TiB");
  if (!(gpu_memory_mb == 0 || (gpu_memory_mb >= 4 && gpu_memory_mb <= double(1 << 24))))
    throw SettingError("volume.gpu_memory_mb", "must be 0 (no GPU budget) or between 4 MiB and 16 TiB");
}

std::size_t VolumeOptions::BricksIn(double mb) const {
  // A brick also costs its entries in the two hash tables (at most half full: 4 slots of 12 bytes).
  const double per_brick = double(brick_bytes()) + 48.0;
  return std::size_t(std::min(mb * 1024 * 1024 / per_brick, double(1 << 30)));
}
std::size_t VolumeOptions::max_bricks() const { return BricksIn(max_memory_mb); }
std::size_t VolumeOptions::gpu_bricks() const { return gpu_memory_mb > 0 ? BricksIn(gpu_memory_mb) : 0; }

void BrickTable::Reset(std::size_t capacity) {
  keys_.assign(capacity, kEmptyKey);
  values_.assign(capacity, -1);
  size_ = 0;
}

void BrickTable::Insert(std::uint64_t key, int value) {
  if (2 * (size_ + 1) > keys_.size()) {  // grow: reinsert everything at twice the capacity
    std::vector<std::uint64_t> keys = std::move(keys_);
    std::vector<int> values = std::move(values_);
    Reset(keys.size() * 2);
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (keys[i] != kEmptyKey) Insert(keys[i], values[i]);
  }
  const std::uint32_t mask = std::uint32_t(keys_.size() - 1);
  std::uint32_t h = HashBrickKey(key) & mask;
  while (keys_[h] != kEmptyKey) h = (h + 1) & mask;
  keys_[h] = key;
  values_[h] = value;
  ++size_;
}

Volume::Volume(const VolumeOptions& o) : o_(o) {
  o_.Check();
  max_bricks_ = o_.max_bricks();
}

std::size_t Volume::bytes() const { return table_.bytes() + groups_.bytes() + pool_.size(); }

bool Volume::Allocate(std::uint64_t key) {
  if (!full_reason_.empty()) return false;
  if (brick_coord_.size() >= max_bricks_) {
    full_reason_ = "the model reached its memory budget of " + std::to_string(long(o_.max_memory_mb)) +
                   " MiB (volume.max_memory_mb): " + std::to_string(brick_coord_.size()) + " bricks";
    return false;
  }
  const std::size_t bytes = o_.brick_bytes();
  if (pool_.size() + bytes > pool_.capacity()) {
    // Grow by half (at least 256 bricks), within the budget and what the system has free.
    const std::size_t bricks = brick_coord_.size();
    const std::size_t want = std::min(max_bricks_, std::max(bricks + 256, bricks + bricks / 2));
    const std::size_t extra = (want - bricks) * bytes;
    const auto avail = AvailableHostBytes();
    if (avail && *avail < extra + (std::size_t(256) << 20)) {
      full_reason_ = "the system has " + std::to_string(*avail >> 20) + " MiB of memory available, too little to grow the model past " +
                     std::to_string(bricks) + " bricks";
      return false;
    }
    pool_.reserve(want * bytes);
  }
  int bx, by, bz;
  DecodeBrickKey(key, &bx, &by, &bz);
  const int slot = int(brick_coord_.size());
  table_.Insert(key, slot);
  const std::uint64_t g = GroupKey(bx, by, bz);
  if (groups_.Find(g) < 0) groups_.Insert(g, 1);
  box_.Add(bx, by, bz);
  brick_coord_.push_back({bx, by, bz});
  stamp_.push_back(clock_);
  pool_.resize(pool_.size() + bytes);
  VisitEncoding(o_.encoding, [&](auto tag) {
    using V = decltype(tag);
    V* p = reinterpret_cast<V*>(pool_.data() + pool_.size() - bytes);
    for (int i = 0; i < 512; ++i) p[i] = V{};
  });
  return true;
}

bool Volume::Get(int x, int y, int z, Voxel* out) const {
  return VisitEncoding(o_.encoding, [&](auto tag) {
    const auto* v = view<decltype(tag)>().Get(x, y, z);
    if (v) *out = v->Decode();
    return v != nullptr;
  });
}
bool Volume::BrickAllocated(int bx, int by, int bz) const {
  return view<FullVoxel>().BrickAllocated(bx, by, bz);  // the index only
}
bool Volume::SampleTsdf(Float3 p, float* tsdf) const {
  return VisitEncoding(o_.encoding, [&](auto tag) { return view<decltype(tag)>().SampleTsdf(p, tsdf); });
}
bool Volume::SampleRadiance(Float3 p, Float3* radiance, float* nr) const {
  return VisitEncoding(o_.encoding, [&](auto tag) { return view<decltype(tag)>().SampleRadiance(p, radiance, nr); });
}
bool Volume::Gradient(Float3 p, Float3* n) const {
  return VisitEncoding(o_.encoding, [&](auto tag) { return view<decltype(tag)>().Gradient(p, n); });
}

void Volume::Assign(std::span<const std::uint8_t> pool, std::vector<std::array<int, 3>> coords, std::string full_reason) {
  if (pool.size() != coords.size() * o_.brick_bytes()) throw Error("volume copy: inconsistent sizes");
  std::size_t cap = 1024;
  while (cap < 2 * coords.size() + 2) cap *= 2;
  table_.Reset(cap);
  groups_.Reset(cap);
  for (std::size_t i = 0; i < coords.size(); ++i) {
    const auto& c = coords[i];
    if (!BrickInRange(c[0], c[1], c[2])) throw Error("volume copy: brick coordinates out of range");
    const std::uint64_t key = BrickKey(c[0], c[1], c[2]);
    if (table_.Find(key) >= 0) throw Error("volume copy: a brick is named twice");
    table_.Insert(key, int(i));
    const std::uint64_t g = GroupKey(c[0], c[1], c[2]);
    if (groups_.Find(g) < 0) groups_.Insert(g, 1);
  }
  pool_ = GrowableBytes(pool);
  brick_coord_ = std::move(coords);
  box_ = {};
  for (const auto& c : brick_coord_) box_.Add(c[0], c[1], c[2]);
  full_reason_ = std::move(full_reason);
  stamp_.assign(brick_coord_.size(), ++clock_);
}

BrickSet Volume::CopyChanged(std::uint32_t since) const {
  BrickSet out;
  const std::size_t B = o_.brick_bytes();
  std::size_t n = 0;
  for (const std::uint32_t s : stamp_) n += s > since;
  out.coords.reserve(n);
  out.voxels.resize(n * B);
  std::size_t k = 0;
  for (std::size_t slot = 0; slot < stamp_.size(); ++slot) {
    if (stamp_[slot] <= since) continue;
    out.coords.push_back(brick_coord_[slot]);
    std::memcpy(out.voxels.data() + k * B, pool_.data() + slot * B, B);
    ++k;
  }
  return out;
}

bool Volume::Store(const BrickSet& bricks) {
  const std::size_t B = o_.brick_bytes();
  if (bricks.voxels.size() != bricks.coords.size() * B) throw Error("volume copy: inconsistent sizes");
  ++clock_;
  for (std::size_t i = 0; i < bricks.size(); ++i) {
    const auto& c = bricks.coords[i];
    if (!BrickInRange(c[0], c[1], c[2])) throw Error("volume copy: brick coordinates out of range");
    const std::uint64_t key = BrickKey(c[0], c[1], c[2]);
    int slot = table_.Find(key);
    if (slot < 0) {
      if (!Allocate(key)) return false;
      slot = int(brick_coord_.size()) - 1;
    }
    std::memcpy(pool_.data() + std::size_t(slot) * B, bricks.voxels.data() + i * B, B);
    stamp_[std::size_t(slot)] = clock_;
  }
  return true;
}

std::array<Float3, 2> Volume::Bounds() const { return box_.World(o_.voxel_m * kBrick); }

IntegrateArgs Volume::MakeIntegrateArgs(const VolumeOptions& o, const PinholeCamera& cam, const Pose& T_world_camera,
                                        float radiance_scale) {
  IntegrateArgs a{};
  a.radiance_scale = radiance_scale;
  a.cam = cam;
  a.T_camera_world = ToRigidTransform(T_world_camera.inverse());
  a.voxel_m = o.voxel_m;
  a.trunc_m = o.truncation_m();
  a.max_weight = o.max_weight;
  a.max_radiance_weight = o.max_radiance_weight;
  a.tau0 = o.tau0;
  a.cos_tau1 = std::cos(o.tau1_deg * 3.14159265f / 180.f);
  return a;
}

namespace {

// Distinct brick keys in the order first named: an open-addressing set (at most half full,
// doubled as it fills) beside the list of its keys.
struct BrickKeySet {
  std::vector<std::uint64_t> keys;
  std::vector<std::uint64_t> set = std::vector<std::uint64_t>(std::size_t(1) << 12, kEmptyKey);
  void Insert(std::uint64_t k) {
    std::size_t mask = set.size() - 1, h = HashBrickKey(k) & mask;
    while (set[h] != kEmptyKey) {
      if (set[h] == k) return;
      h = (h + 1) & mask;
    }
    set[h] = k;
    keys.push_back(k);
    if (2 * keys.size() > set.size()) {  // twice the room, the keys again
      set.assign(set.size() * 2, kEmptyKey);
      mask = set.size() - 1;
      for (const std::uint64_t e : keys) {
        std::size_t g = HashBrickKey(e) & mask;
        while (set[g] != kEmptyKey) g = (g + 1) & mask;
        set[g] = e;
      }
    }
  }
};

}  // namespace

Volume::IntegrateStats Volume::Integrate(const FrameInput& in) {
  IntegrateStats st;
  IntegrateArgs args = MakeIntegrateArgs(o_, in.camera, in.T_world_camera, in.radiance_scale);
  args.depth = View(*in.depth_m);
  args.normals = View(*in.normals);
  if (in.radiance) {
    args.radiance = View(*in.radiance);
    args.nr = View(*in.nr);
    args.confidence = View(*in.confidence);
    args.max_confidence = View(*in.max_confidence);
  }
  const RigidTransform T = ToRigidTransform(in.T_world_camera);
  const DepthImage& depth = *in.depth_m;
  // 1. Bricks within the truncation band of every depth sample (every 2nd pixel), in key
  // order; new ones take the next slots in that order (as on the GPU). The CPU's threads
  // each take rows and keep each distinct brick once as it is named (BrickKeySet); their
  // sets are then merged, so that only the distinct bricks are sorted: the same keys
  // whichever thread named which.
  std::vector<BrickKeySet> named(std::size_t(std::max(1, omp_get_max_threads())));
#pragma omp parallel
  {
    BrickKeySet& mine = named[std::size_t(omp_get_thread_num()) % named.size()];
    std::uint64_t last = kEmptyKey;
#pragma omp for schedule(dynamic, 4)
    for (int y = 0; y < depth.height(); y += 2)
      for (int x = 0; x < depth.width(); x += 2)
        ForBricksAlongRay(args, T, x, y, [&](int bx, int by, int bz) {
          const std::uint64_t k = BrickKey(bx, by, bz);
          if (k != last) mine.Insert(k);
          last = k;
        });
  }
  BrickKeySet all;
  for (const BrickKeySet& n : named)
    for (const std::uint64_t k : n.keys) all.Insert(k);
  std::vector<std::uint64_t> keys = std::move(all.keys);
  par::Sort(par::Host{}, keys.begin(), keys.end());
  std::vector<int> todo;
  todo.reserve(keys.size());
  for (const std::uint64_t k : keys) {
    int slot = table_.Find(k);
    if (slot < 0) {
      if (!Allocate(k)) continue;
      slot = int(brick_coord_.size()) - 1;
      ++st.new_bricks;
    }
    todo.push_back(slot);
  }
  st.visible_bricks = todo.size();
  ++clock_;
  for (const int slot : todo) stamp_[std::size_t(slot)] = clock_;
  // 2. Update the voxels of those bricks.
  std::size_t updated = 0, rad_updates = 0;
  VisitEncoding(o_.encoding, [&](auto tag) {
    using V = decltype(tag);
    V* pool = view<V>().pool;
#pragma omp parallel for schedule(dynamic, 8) reduction(+ : updated, rad_updates)
    for (long k = 0; k < long(todo.size()); ++k) {
      const int b = todo[std::size_t(k)];
      const auto bc = brick_coord_[std::size_t(b)];
      V* vox = pool + std::size_t(b) * 512;
      // The brick's voxels in view first, then their updates (IntegrateVoxel's operations):
      // the pixel look-ups of the first pass then wait on each other less.
      VoxelInView seen[512];
      std::int16_t at[512];
      const int n = ProjectBrick(args, bc[0], bc[1], bc[2], seen, at);
      for (int j = 0; j < n; ++j) {
        const int done = UpdateVoxel(args, seen[j], vox[at[j]]);
        updated += done & 1;
        rad_updates += (done >> 1) & 1;
      }
    }
  });
  st.voxels_updated = updated;
  st.radiance_updates = rad_updates;
  return st;
}

Volume::Rendering Volume::Raycast(const PinholeCamera& cam, const Pose& T_wc, const Image<float>* guide) const {
  Rendering r;
  const int w = cam.width, h = cam.height;
  r.vertex = Image<Float3>(w, h);
  r.normal = Image<Float3>(w, h);
  r.radiance = RadianceImage(w, h);
  r.nr = Image<float>(w, h);
  r.depth = DepthImage(w, h);
  RaycastArgs a{cam, ToRigidTransform(T_wc), o_.raycast_near_m, o_.raycast_far_m};
  if (guide && !guide->empty()) a.start = View(*guide);
  a.SetBox(Bounds());
  const RenderingViews out{View(r.vertex), View(r.normal), View(r.radiance), View(r.nr), View(r.depth)};
  VisitEncoding(o_.encoding, [&](auto tag) { RaycastInto(par::Host{}, view<decltype(tag)>(), a, out); });
  return r;
}

#if !HDRF_HAS_CUDA
void SetDevicePlaceLimit(int) {}
#endif

}  // namespace hdrf::volume
