// The model: a truncated signed distance function with HDR radiance in voxels of a fixed
// size, with no fixed extent. Storage is sparse: 8^3-voxel bricks, allocated where depth was
// seen and found through a spatial hash of their coordinates (volume_impl.h), so memory
// follows the observed surface wherever the camera goes.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/growable_bytes.h"
#include "common/host_memory.h"
#include "common/camera.h"
#include "common/image.h"
#include "common/se3.h"
#include "volume/raycast_impl.h"
#include "volume/volume_impl.h"

namespace hdrf::volume {

// "full", "no-nr", "compact" (throws SettingError naming --voxel otherwise).
VoxelEncoding ParseVoxelEncoding(const std::string& s);
const char* VoxelEncodingName(VoxelEncoding e);

struct VolumeOptions {
  float voxel_m = 0.02f;         // voxel side, metres (docs/engine.md: the choice measured)
  float truncation_voxels = 4;   // TSDF truncation distance, in voxels
  float max_weight = 64;         // cap of the TSDF weight (running mean window)
  float max_radiance_weight = 64;  // cap of the radiance weight
  float tau0 = 0.1f;             // radiance fused only where the largest channel PCF > tau0
  float tau1_deg = 75;           // ... and the angle between normal and view ray < tau1
  double max_memory_mb = 4096;   // voxel memory the volume may use (the whole model)
  // GPU only: bricks the GPU holds at most (MiB; 0: as many as max_memory_mb and the GPU's
  // free memory allow). Beyond it, bricks out of view move to host memory and come back
  // when seen again (DeviceVolume).
  double gpu_memory_mb = 0;
  float raycast_near_m = 0.2f;   // ray casting starts this far from the camera ...
  float raycast_far_m = 8.0f;    // ... and gives up this far
  // Voxel storage (volume_impl.h, volume.voxel): compact by default, as accurate as full on the
  // engine's tests at 12 instead of 28 bytes (VoxelEncoding.CompactVoxelsKeepTheAccuracyOfFullOnes).
  VoxelEncoding encoding = VoxelEncoding::kCompact;
  void Check() const;            // throws SettingError naming the setting (volume.*)
  float truncation_m() const { return truncation_voxels * voxel_m; }
  // Bytes of one brick's voxels, and the most bricks max_memory_mb holds.
  std::size_t brick_bytes() const { return 512 * std::size_t(EncodingBytes(encoding)); }
  std::size_t max_bricks() const;
  std::size_t gpu_bricks() const;  // bricks gpu_memory_mb holds (0: no GPU budget)
  std::size_t BricksIn(double mb) const;  // bricks (with their hash entries) in mb MiB
};

// An open-addressing hash table in host memory (the layout HashView reads): brick or group
// key -> pool slot; kept at most half full, doubling as it fills.
class BrickTable {
 public:
  BrickTable() { Reset(1024); }
  int Find(std::uint64_t key) const { return view().Find(key); }
  // Inserts a key not yet present.
  void Insert(std::uint64_t key, int value);
  void Reset(std::size_t capacity);  // empty, with room for `capacity` entries (a power of two)
  HashView view() const { return {keys_.data(), values_.data(), std::uint32_t(keys_.size() - 1)}; }
  std::size_t size() const { return size_; }
  std::size_t capacity() const { return keys_.size(); }
  std::size_t bytes() const { return keys_.size() * (sizeof(std::uint64_t) + sizeof(int)); }

 private:
  std::vector<std::uint64_t> keys_;
  std::vector<int> values_;
  std::size_t size_ = 0;
};

// Some of a model's bricks with their voxels (a copy: the bricks a frame changed, handed to
// a mesher on another thread): coords[i]'s 512 encoded voxels at voxels[i * brick bytes].
struct BrickSet {
  std::vector<std::array<int, 3>> coords;
  std::vector<std::uint8_t> voxels;
  std::size_t size() const { return coords.size(); }
};

// The range of the brick coordinates added since it was made, and its world box (the
// volume's Bounds on either device: the ray cast casts only inside it).
struct BrickBox {
  std::array<int, 3> lo{}, hi{};
  bool empty = true;
  void Add(int x, int y, int z) {
    const std::array<int, 3> c = {x, y, z};
    for (std::size_t k = 0; k < 3; ++k) {
      lo[k] = empty ? c[k] : std::min(lo[k], c[k]);
      hi[k] = empty ? c[k] : std::max(hi[k], c[k]);
    }
    empty = false;
  }
  // From the first brick's low corner to the last one's high corner; all zero when empty.
  std::array<Float3, 2> World(float brick_m) const {
    if (empty) return {Float3{0, 0, 0}, Float3{0, 0, 0}};
    return {Float3{lo[0] * brick_m, lo[1] * brick_m, lo[2] * brick_m},
            Float3{(hi[0] + 1) * brick_m, (hi[1] + 1) * brick_m, (hi[2] + 1) * brick_m}};
  }
};

class Volume {
 public:
  explicit Volume(const VolumeOptions& o);

  const VolumeOptions& options() const { return o_; }
  std::size_t allocated_bricks() const { return brick_coord_.size(); }
  std::size_t bytes() const;
  // Allocation stopped: at max_memory_mb, or where the system had no more memory; why, in
  // a sentence naming the limit ("" while not full).
  bool full() const { return !full_reason_.empty(); }
  const std::string& full_reason() const { return full_reason_; }

  // Decoded voxel at integer coordinates; false where unallocated.
  bool Get(int x, int y, int z, Voxel* out) const;
  bool BrickAllocated(int bx, int by, int bz) const;
  // Trilinear TSDF at a world point (voxel-centre grid); false where the observed corners
  // carry less than half of the weight.
  bool SampleTsdf(Float3 p, float* tsdf) const;
  // Trilinear radiance and NR over corners with radiance weight; false if none has any.
  bool SampleRadiance(Float3 p, Float3* radiance, float* nr) const;
  // Normal from the TSDF gradient; false where undefined.
  bool Gradient(Float3 p, Float3* n) const;
  // The arrays for the per-element functions of volume_impl.h; V must be the options'
  // encoding.
  template <typename V>
  VolumeView<V> view() const {
    VolumeView<V> v;
    v.bricks = table_.view();
    v.groups = groups_.view();
    v.pool = reinterpret_cast<V*>(const_cast<std::uint8_t*>(pool_.data()));
    v.voxel_m = o_.voxel_m;
    v.trunc_m = o_.truncation_m();
    return v;
  }
  int voxel_bytes() const { return EncodingBytes(o_.encoding); }

  // Integration of one frame (volume.cpp; per voxel: IntegrateVoxel in volume_impl.h).
  struct FrameInput {
    const DepthImage* depth_m;
    const Image<Float3>* normals;       // camera frame, for w_F = |n.v|
    const RadianceImage* radiance;      // live radiance; times radiance_scale = model units
    const Image<float>* nr;             // normalized radiance
    const Image<float>* confidence;     // mean PCF -> w_R
    const Image<float>* max_confidence; // largest channel PCF -> tau0 gate
    PinholeCamera camera;
    Pose T_world_camera;
    float radiance_scale = 1;           // exposure compensation (model / live)
  };
  struct IntegrateStats {
    std::size_t visible_bricks = 0, new_bricks = 0, voxels_updated = 0, radiance_updates = 0;
  };
  IntegrateStats Integrate(const FrameInput& in);

  // Ray casting from a pose (per pixel: RaycastPixel in raycast_impl.h): world vertex, world normal,
  // radiance, NR and camera depth; zero where the ray hit nothing.
  struct Rendering {
    Image<Float3> vertex, normal;
    RadianceImage radiance;
    Image<float> nr;
    DepthImage depth;
  };
  // `guide` (raycast_driver.h, RaycastGuide): where each tile's rays may start; none: near.
  Rendering Raycast(const PinholeCamera& cam, const Pose& T_world_camera, const Image<float>* guide = nullptr) const;

  // Brick coordinates of each pool slot, in allocation order (for meshing).
  const std::vector<std::array<int, 3>>& bricks() const { return brick_coord_; }
  // The world box (min and max corners, metres) of the allocated bricks; zeros when empty.
  std::array<Float3, 2> Bounds() const;

  // The raw state, for a copy made elsewhere (the CUDA volume's host mirror, project files):
  // the voxel pool (512 encoded voxels per brick, in slot order), each slot's brick
  // coordinates, and why allocation had stopped ("" if it had not). The hash tables are
  // rebuilt from the coordinates.
  std::span<const std::uint8_t> pool() const { return pool_.span(); }
  void Assign(std::span<const std::uint8_t> pool, std::vector<std::array<int, 3>> brick_coords, std::string full_reason);
  // Changes: a clock that each Integrate and Assign advances, each brick stamped with the
  // clock of its last change. CopyChanged: the bricks changed after clock value `since`.
  std::uint32_t change_clock() const { return clock_; }
  BrickSet CopyChanged(std::uint32_t since) const;
  // Writes bricks in (allocating those not yet here; a mirror of another volume): false,
  // with full() set, where the memory limit stopped one.
  bool Store(const BrickSet& bricks);
  // Integration and ray casting argument blocks shared with the CUDA backend.
  // (the caller sets the image views).
  static IntegrateArgs MakeIntegrateArgs(const VolumeOptions& o, const PinholeCamera& cam, const Pose& T_world_camera,
                                         float radiance_scale);
  std::size_t max_bricks() const { return max_bricks_; }

 private:
  // Allocates the brick with this key in the next slot; false when a limit stops it.
  bool Allocate(std::uint64_t key);

  VolumeOptions o_;
  BrickTable table_;   // brick key -> slot
  BrickTable groups_;  // group key -> 1 (empty-space skipping)
  GrowableBytes pool_;  // 512 encoded voxels per brick
  std::vector<std::array<int, 3>> brick_coord_;
  BrickBox box_;  // of brick_coord_ (Bounds)
  std::vector<std::uint32_t> stamp_;  // per slot: the change clock of its last update
  std::uint32_t clock_ = 0;
  std::size_t max_bricks_ = 0;
  std::string full_reason_;
};

// For tests: the most new bricks a frame's integration on the GPU places on the device, without
// the host (DeviceVolume::kPlaceMost, 1024, by default, and for a negative number; 0: every
// frame's through the host; any number gives the same model). Nothing without a CUDA build.
void SetDevicePlaceLimit(int most);

}  // namespace hdrf::volume
