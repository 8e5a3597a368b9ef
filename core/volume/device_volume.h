// The model on the GPU: the same sparse bricks as Volume (volume.h), resident in device
// memory, with their allocation, integration and ray casting as CUDA kernels over the
// per-voxel functions of volume_impl.h (volume_cuda.cu). Built only with CUDA.
#pragma once

#include <cstdint>

#include "common/device_buffer.h"
#include "common/se3.h"
#include "volume/raycast_driver.h"
#include "volume/volume.h"

namespace hdrf::volume {

struct BrickCoord {
  int x, y, z;
};

class DeviceVolume {
 public:
  explicit DeviceVolume(const VolumeOptions& o);
  DeviceVolume(const DeviceVolume&) = delete;
  DeviceVolume& operator=(const DeviceVolume&) = delete;

  // Fuses one frame (the argument block's image views are device views): marks the bricks
  // in the truncation band of every second depth pixel, allocates new ones in brick-index
  // order (as Volume::Integrate does) up to the memory limit, then updates each voxel of the
  // visible bricks.
  void Integrate(const IntegrateArgs& a, const Pose& T_world_camera);
  // Ray casts into device images (the shared driver, raycast_driver.h).
  void Raycast(const RaycastArgs& a, const RenderingViews& out) const;

  const VolumeOptions& options() const { return mirror_.options(); }
  Float3 origin() const { return mirror_.origin(); }
  std::size_t allocated_bricks() const { return std::size_t(allocated_); }
  std::size_t last_visible_bricks() const;  // bricks the last Integrate updated
  std::size_t bytes() const;
  bool full() const { return full_; }
  // Device views of the arrays for the per-element functions (V: the options' encoding).
  template <typename V>
  VolumeView<V> view() const {
    VolumeView<V> v = mirror_.view<V>();  // geometry from the host twin
    v.index = const_cast<int*>(index_.data());
    v.coarse = const_cast<std::uint8_t*>(coarse_.data());
    v.pool = reinterpret_cast<V*>(const_cast<std::uint8_t*>(pool_.data()));
    return v;
  }
  const BrickCoord* brick_coords() const { return coords_.data(); }
  // A host copy of the whole model (every allocated brick), refreshed after new frames.
  const Volume& Download();

 private:
  void Grow(int bricks);

  Volume mirror_;  // geometry and limits; the host copy on request
  bool mirror_fresh_ = true;
  int vbytes_ = 0;
  DeviceBuffer<int> index_, flags_, scan_, todo_;
  DeviceBuffer<std::uint8_t> coarse_, visible_;
  DeviceBuffer<std::uint8_t> pool_;  // 512 encoded voxels per brick
  DeviceBuffer<BrickCoord> coords_;
  DeviceBuffer<int> counts_;  // (new bricks, todo bricks)
  DeviceBuffer<std::uint8_t> temp_;
  int allocated_ = 0, capacity_ = 0;
  bool full_ = false;
};

}  // namespace hdrf::volume
