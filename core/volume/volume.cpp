#include "volume/volume.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
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
  if (resolution < 8 || resolution % 8 != 0)
    throw SettingError("volume.resolution", "must be a positive multiple of 8, got " + std::to_string(resolution));
  if (resolution > 4096)
    throw SettingError("volume.resolution", std::to_string(resolution) + " is more than 4096 voxels per side");
  if (!(size_m > 0) || !std::isfinite(size_m))
    throw SettingError("volume.size_m", "must be a positive number of metres");
  if (!(truncation_voxels >= 1)) throw SettingError("volume.truncation_voxels", "must be >= 1");
  if (!(max_weight > 0)) throw SettingError("volume.max_weight", "must be > 0");
  if (!(max_radiance_weight > 0)) throw SettingError("volume.max_radiance_weight", "must be > 0");
  if (encoding == VoxelEncoding::kCompact && (max_weight > 65 || max_radiance_weight > 65))
    throw SettingError(max_weight > 65 ? "volume.max_weight" : "volume.max_radiance_weight",
                       "compact voxels hold weights up to 65; lower the cap or use volume.voxel full");
  if (!(tau1_deg > 0 && tau1_deg <= 90)) throw SettingError("volume.tau1_deg", "must be in (0, 90] degrees");
  if (!(tau0 >= 0 && tau0 < 1)) throw SettingError("volume.tau0", "must be in [0, 1)");
  if (!(raycast_near_m > 0) || !(raycast_far_m > raycast_near_m) || !std::isfinite(raycast_far_m))
    throw SettingError("volume.raycast_far_m", "ray casting needs 0 < near < far (finite metres)");
  const double nb = resolution / 8.0;
  const double index_mb = nb * nb * nb * 4.0 / (1024.0 * 1024.0);
  const double brick_mb = 512.0 * EncodingBytes(encoding) / (1024.0 * 1024.0);
  if (index_mb + 64 * brick_mb > max_memory_mb)
    throw SettingError("volume.resolution", "a " + std::to_string(resolution) + "^3 volume needs " +
                                           std::to_string(int(index_mb)) + " MiB for its brick index alone, more than the " +
                                           std::to_string(int(max_memory_mb)) + " MiB allowed (volume.max_memory_mb)");
}

Volume::Volume(const VolumeOptions& o) : o_(o) {
  o_.Check();
  n_ = o_.resolution;
  nb_ = n_ / kBrick;
  const float half = 0.5f * o_.size_m;
  origin_ = {-half, -half, -half};
  index_.assign(std::size_t(nb_) * nb_ * nb_, -1);
  nc_ = (nb_ + 3) / 4;
  coarse_.assign(std::size_t(nc_) * nc_ * nc_, 0);
  const double brick_bytes = 512.0 * EncodingBytes(o_.encoding);
  max_bricks_ = std::size_t(std::max(0.0, (o_.max_memory_mb * 1024 * 1024 - double(index_.size()) * 4) / brick_bytes));
}

std::size_t Volume::bytes() const {
  return index_.size() * sizeof(int) + pool_.size();
}

bool Volume::Allocate(int bx, int by, int bz) {
  int& slot = index_[BrickIndex(bx, by, bz)];
  if (slot >= 0) return true;
  if (brick_coord_.size() >= max_bricks_) {
    full_ = true;
    return false;
  }
  slot = int(brick_coord_.size());
  brick_coord_.push_back({bx, by, bz});
  coarse_[std::size_t(((bz >> 2) * nc_ + (by >> 2)) * nc_ + (bx >> 2))] = 1;
  const std::size_t bytes = 512 * std::size_t(voxel_bytes());
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

void Volume::Assign(std::vector<int> index, std::vector<std::uint8_t> pool,
                    std::vector<std::array<int, 3>> coords, bool full) {
  if (index.size() != index_.size() || pool.size() != coords.size() * 512 * std::size_t(voxel_bytes()))
    throw Error("volume copy: inconsistent sizes");
  index_ = std::move(index);
  pool_ = std::move(pool);
  brick_coord_ = std::move(coords);
  full_ = full;
  std::fill(coarse_.begin(), coarse_.end(), 0);
  for (const auto& c : brick_coord_)
    coarse_[std::size_t(((c[2] >> 2) * nc_ + (c[1] >> 2)) * nc_ + (c[0] >> 2))] = 1;
}

IntegrateArgs Volume::MakeIntegrateArgs(const VolumeOptions& o, Float3 origin, const PinholeCamera& cam,
                                        const Pose& T_world_camera, float radiance_scale) {
  IntegrateArgs a{};
  a.radiance_scale = radiance_scale;
  a.cam = cam;
  a.T_camera_world = ToRigidTransform(T_world_camera.inverse());
  a.origin = origin;
  a.voxel_m = o.voxel_m();
  a.trunc_m = o.truncation_m();
  a.max_weight = o.max_weight;
  a.max_radiance_weight = o.max_radiance_weight;
  a.tau0 = o.tau0;
  a.cos_tau1 = std::cos(o.tau1_deg * 3.14159265f / 180.f);
  return a;
}

Volume::IntegrateStats Volume::Integrate(const FrameInput& in) {
  IntegrateStats st;
  IntegrateArgs args = MakeIntegrateArgs(o_, origin_, in.camera, in.T_world_camera, in.radiance_scale);
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
  // 1. Bricks within the truncation band of every depth sample (every 2nd pixel).
  std::vector<std::uint8_t> visible(index_.size(), 0);
  for (int y = 0; y < depth.height(); y += 2)
    for (int x = 0; x < depth.width(); x += 2)
      ForBricksAlongRay(args, T, nb_, x, y,
                        [&](int bx, int by, int bz) { visible[std::size_t(BrickIndex(bx, by, bz))] = 1; });
  std::vector<int> todo;
  for (int bz = 0; bz < nb_; ++bz)
    for (int by = 0; by < nb_; ++by)
      for (int bx = 0; bx < nb_; ++bx) {
        const int i = BrickIndex(bx, by, bz);
        if (!visible[std::size_t(i)]) continue;
        const bool existed = index_[std::size_t(i)] >= 0;
        if (!Allocate(bx, by, bz)) continue;
        st.new_bricks += !existed;
        todo.push_back(index_[std::size_t(i)]);
      }
  st.visible_bricks = todo.size();
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
      for (int i = 0; i < 512; ++i) {
        const int done = IntegrateVoxel(args, bc[0], bc[1], bc[2], i, vox[i]);
        updated += done & 1;
        rad_updates += (done >> 1) & 1;
      }
    }
  });
  st.voxels_updated = updated;
  st.radiance_updates = rad_updates;
  return st;
}

Volume::Rendering Volume::Raycast(const PinholeCamera& cam, const Pose& T_wc) const {
  Rendering r;
  const int w = cam.width, h = cam.height;
  r.vertex = Image<Float3>(w, h);
  r.normal = Image<Float3>(w, h);
  r.radiance = RadianceImage(w, h);
  r.nr = Image<float>(w, h);
  r.depth = DepthImage(w, h);
  const RaycastArgs a{cam, ToRigidTransform(T_wc), o_.raycast_near_m, o_.raycast_far_m};
  const RenderingViews out{View(r.vertex), View(r.normal), View(r.radiance), View(r.nr), View(r.depth)};
  VisitEncoding(o_.encoding, [&](auto tag) { RaycastInto(par::Host{}, view<decltype(tag)>(), a, out); });
  return r;
}

}  // namespace hdrf::volume
