// The model: a truncated signed distance function with HDR radiance, in voxels of fixed
// size over a cube centred on the first camera. Storage is sparse: 8^3-voxel bricks,
// allocated where depth was seen, behind a dense brick index (the cube is bounded), so
// memory follows the observed surface, not the cube.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/camera.h"
#include "common/image.h"
#include "common/se3.h"
#include "volume/volume_impl.h"

namespace hdrf::volume {

// "full", "no-nr", "compact" (throws SettingError naming --voxel otherwise).
VoxelEncoding ParseVoxelEncoding(const std::string& s);
const char* VoxelEncodingName(VoxelEncoding e);

struct VolumeOptions {
  int resolution = 256;          // voxels per side (a multiple of 8)
  float size_m = 6.0f;           // side of the cube, metres, centred on the first camera
  float truncation_voxels = 4;   // TSDF truncation distance, in voxels
  float max_weight = 64;         // cap of the TSDF weight (running mean window)
  float max_radiance_weight = 64;  // cap of the radiance weight
  float tau0 = 0.1f;             // radiance fused only where the largest channel PCF > tau0
  float tau1_deg = 75;           // ... and the angle between normal and view ray < tau1
  double max_memory_mb = 4096;   // voxel memory the volume may use
  float raycast_near_m = 0.2f;   // ray casting starts this far from the camera ...
  float raycast_far_m = 8.0f;    // ... and gives up this far
  // Voxel storage (volume_impl.h, volume.voxel): compact by default, as accurate as full on the
  // engine's tests at 12 instead of 28 bytes (docs/benchmarks.md).
  VoxelEncoding encoding = VoxelEncoding::kCompact;
  void Check() const;            // throws SettingError naming the setting (volume.*)
  float voxel_m() const { return size_m / float(resolution); }
  float truncation_m() const { return truncation_voxels * voxel_m(); }
};

class Volume {
 public:
  explicit Volume(const VolumeOptions& o);

  const VolumeOptions& options() const { return o_; }
  Float3 origin() const { return origin_; }  // world position of voxel (0,0,0)'s corner
  int bricks_per_side() const { return nb_; }
  std::size_t allocated_bricks() const { return brick_coord_.size(); }
  std::size_t bytes() const;
  bool full() const { return full_; }  // allocation stopped at max_memory_mb

  // Decoded voxel at integer coordinates; false where unallocated / outside.
  bool Get(int x, int y, int z, Voxel* out) const;
  bool BrickAllocated(int bx, int by, int bz) const;
  // Trilinear TSDF at a world point (voxel-centre grid); false where the observed corners
  // carry less than half of the weight.
  bool SampleTsdf(Float3 p, float* tsdf) const;
  // Trilinear radiance and NR over corners with radiance weight; false if none has any.
  bool SampleRadiance(Float3 p, Float3* radiance, float* nr) const;
  // Normal from the TSDF gradient; false where undefined.
  bool Gradient(Float3 p, Float3* n) const;
  // The arrays and geometry for the per-element functions of volume_impl.h; V must be the
  // options' encoding.
  template <typename V>
  VolumeView<V> view() const {
    VolumeView<V> v;
    v.index = index_.data();
    v.coarse = coarse_.data();
    v.pool = reinterpret_cast<V*>(const_cast<std::uint8_t*>(pool_.data()));
    v.n = n_;
    v.nb = nb_;
    v.nc = nc_;
    v.origin = origin_;
    v.voxel_m = o_.voxel_m();
    v.size_m = o_.size_m;
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

  // Ray casting from a pose (per pixel: RaycastPixel in volume_impl.h): world vertex, world normal,
  // radiance, NR and camera depth; zero where the ray hit nothing.
  struct Rendering {
    Image<Float3> vertex, normal;
    RadianceImage radiance;
    Image<float> nr;
    DepthImage depth;
  };
  Rendering Raycast(const PinholeCamera& cam, const Pose& T_world_camera) const;

  // Voxel coordinates of allocated bricks (for meshing).
  const std::vector<std::array<int, 3>>& bricks() const { return brick_coord_; }

  // The raw state, for a copy made elsewhere (the CUDA volume's host mirror): the brick
  // index (nb^3), the voxel pool (512 per brick, in slot order), each slot's brick
  // coordinates, and whether allocation had stopped at the memory limit.
  const std::vector<int>& brick_index() const { return index_; }
  const std::vector<std::uint8_t>& pool() const { return pool_; }  // encoded voxels
  void Assign(std::vector<int> index, std::vector<std::uint8_t> pool,
              std::vector<std::array<int, 3>> brick_coords, bool full);
  // Integration and ray casting argument blocks shared with the CUDA backend.
  // (the caller sets the image views).
  static IntegrateArgs MakeIntegrateArgs(const VolumeOptions& o, Float3 origin, const PinholeCamera& cam,
                                         const Pose& T_world_camera, float radiance_scale);
  std::size_t max_bricks() const { return max_bricks_; }

 private:
  int BrickIndex(int bx, int by, int bz) const { return (bz * nb_ + by) * nb_ + bx; }
  bool Allocate(int bx, int by, int bz);

  VolumeOptions o_;
  int n_ = 0, nb_ = 0;
  Float3 origin_{};
  std::vector<int> index_;
  std::vector<std::uint8_t> coarse_;  // per 4x4x4 bricks: any allocated (ray skipping)
  int nc_ = 0;
  std::vector<std::uint8_t> pool_;  // 512 encoded voxels per brick
  std::vector<std::array<int, 3>> brick_coord_;
  std::size_t max_bricks_ = 0;
  bool full_ = false;
};

}  // namespace hdrf::volume
