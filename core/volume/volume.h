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

namespace hdrf::volume {

struct VolumeOptions {
  int resolution = 256;          // voxels per side (a multiple of 8)
  float size_m = 6.0f;           // side of the cube, metres, centred on the first camera
  float truncation_voxels = 4;   // TSDF truncation distance, in voxels
  float max_weight = 64;         // cap of the TSDF weight (running mean window)
  float max_radiance_weight = 64;  // cap of the radiance weight
  float tau0 = 0.1f;             // radiance fused only where the largest channel PCF > tau0
  float tau1_deg = 75;           // ... and the angle between normal and view ray < tau1
  double max_memory_mb = 4096;   // voxel memory the volume may use
  void Check() const;            // throws SettingError naming --volume-res / --volume-size
  float voxel_m() const { return size_m / float(resolution); }
  float truncation_m() const { return truncation_voxels * voxel_m(); }
};

struct Voxel {
  float tsdf = 1;                 // signed distance / truncation, in [-1, 1]
  float w = 0;                    // TSDF weight
  Float3 radiance{0, 0, 0};       // HDR radiance, model units
  float nr = 0;                   // normalized radiance
  float wr = 0;                   // radiance weight
};

inline constexpr int kBrick = 8;

class Volume {
 public:
  explicit Volume(const VolumeOptions& o);

  const VolumeOptions& options() const { return o_; }
  Float3 origin() const { return origin_; }  // world position of voxel (0,0,0)'s corner
  int bricks_per_side() const { return nb_; }
  std::size_t allocated_bricks() const { return brick_coord_.size(); }
  std::size_t bytes() const;
  bool full() const { return full_; }  // allocation stopped at max_memory_mb

  // Voxel at integer coordinates, or nullptr where unallocated / outside.
  const Voxel* Get(int x, int y, int z) const {
    if (x < 0 || y < 0 || z < 0 || x >= n_ || y >= n_ || z >= n_) return nullptr;
    const int b = index_[BrickIndex(x >> 3, y >> 3, z >> 3)];
    return b < 0 ? nullptr : &pool_[std::size_t(b) * 512 + std::size_t(((z & 7) * 8 + (y & 7)) * 8 + (x & 7))];
  }
  bool BrickAllocated(int bx, int by, int bz) const {
    return bx >= 0 && by >= 0 && bz >= 0 && bx < nb_ && by < nb_ && bz < nb_ &&
           index_[BrickIndex(bx, by, bz)] >= 0;
  }
  // Trilinear TSDF at a world point (voxel-centre grid); false where any corner is unseen.
  bool SampleTsdf(Float3 p, float* tsdf) const;
  // Trilinear radiance and NR over corners with radiance weight; false if none has any.
  bool SampleRadiance(Float3 p, Float3* radiance, float* nr) const;
  // Normal from the TSDF gradient; false where undefined.
  bool Gradient(Float3 p, Float3* n) const;

  // Integration of one frame (see integrate.cpp).
  struct FrameInput {
    const DepthImage* depth_m;
    const Image<Float3>* normals;       // camera frame, for w_F = |n.v|
    const RadianceImage* radiance;      // already scaled to model units (exposure compensated)
    const Image<float>* nr;             // normalized radiance
    const Image<float>* confidence;     // mean PCF -> w_R
    const Image<float>* max_confidence; // largest channel PCF -> tau0 gate
    PinholeCamera camera;
    Pose T_world_camera;
  };
  struct IntegrateStats {
    std::size_t visible_bricks = 0, new_bricks = 0, voxels_updated = 0, radiance_updates = 0;
  };
  IntegrateStats Integrate(const FrameInput& in);

  // Ray casting from a pose (see raycast.cpp): per pixel world vertex, world normal,
  // radiance, NR and camera depth; zero where the ray hit nothing.
  struct Rendering {
    Image<Float3> vertex, normal;
    RadianceImage radiance;
    Image<float> nr;
    DepthImage depth;
  };
  Rendering Raycast(const PinholeCamera& cam, const Pose& T_world_camera, float near_m = 0.2f,
                    float far_m = 8.0f) const;

  // Voxel coordinates of allocated bricks (for meshing).
  const std::vector<std::array<int, 3>>& bricks() const { return brick_coord_; }

 private:
  int BrickIndex(int bx, int by, int bz) const { return (bz * nb_ + by) * nb_ + bx; }
  Voxel* Allocate(int bx, int by, int bz);
  Voxel* MutableBrick(int b) { return &pool_[std::size_t(b) * 512]; }

  VolumeOptions o_;
  int n_ = 0, nb_ = 0;
  Float3 origin_{};
  std::vector<int> index_;
  std::vector<std::uint8_t> coarse_;  // per 4x4x4 bricks: any allocated (ray skipping)
  int nc_ = 0;
  std::vector<Voxel> pool_;
  std::vector<std::array<int, 3>> brick_coord_;
  std::size_t max_bricks_ = 0;
  bool full_ = false;
};

}  // namespace hdrf::volume
