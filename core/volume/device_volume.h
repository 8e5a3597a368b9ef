// The model on the GPU: the same sparse, hashed bricks as Volume (volume.h), resident in
// device memory, with their allocation, integration and ray casting as CUDA kernels over the
// per-voxel functions of volume_impl.h (volume_cuda.cu). Built only with CUDA.
#pragma once

#include <cuda_runtime_api.h>

#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "common/device_buffer.h"
#include "common/se3.h"
#include "volume/raycast_driver.h"
#include "volume/volume.h"

namespace hdrf::volume {

struct BrickCoord {
  int x, y, z;
};
struct NewBricks;  // the new bricks the integration places itself (volume_cuda.cu)

// RaycastGuide (raycast_driver.h) on the GPU: device views.
void RaycastGuideOnGpu(ImageView<const float> depth, float margin_m, const ImageView<float>& tiles);

class DeviceVolume {
 public:
  explicit DeviceVolume(const VolumeOptions& o);
  ~DeviceVolume();
  DeviceVolume(const DeviceVolume&) = delete;
  DeviceVolume& operator=(const DeviceVolume&) = delete;

  // Fuses one frame (the argument block's image views are device views): collects the
  // bricks in the truncation band of every second depth pixel (a per-frame hash set), gives
  // the new ones slots in key order (as Volume::Integrate does) up to the memory limit, then
  // updates each voxel of the visible bricks.
  //
  // Where the pool has room for a block's worth of new bricks (and there is no GPU budget
  // and no limit reached), the whole frame is queued without a wait: one block places up to
  // kPlaceMost new bricks on the device. The host's side (the counts, the box, and the new
  // bricks the device could not place) is finished by Settle, which everything that reads
  // the model's state on the host calls first (the accessors below refuse to answer before).
  void Integrate(const IntegrateArgs& a, const Pose& T_world_camera);
  // Finishes the last Integrate on the host (waits for its counts, queued behind it). True
  // where it placed and fused new bricks only now, after the queued work: a ray cast queued
  // since then saw the model without them and must be cast again. The work it queues for
  // them waits for `after` first (that ray cast's end, which reads the tables it changes).
  bool Settle(cudaEvent_t after = nullptr);
  bool settled() const { return !pending_; }
  // Queues the read-back of the last Integrate's counts (Settle does, where not yet queued):
  // the caller queues it after the work that should not wait for the copy (the ray cast's
  // start).
  void QueueCounts();
  // Ray casts into device images (the shared driver, raycast_driver.h), on `stream`.
  void Raycast(const RaycastArgs& a, const RenderingViews& out, cudaStream_t stream = nullptr) const;
  // The box of the allocated bricks on the device (brick coordinates: low x, y, z, high x, y,
  // z; low above high while empty), kept by the kernels that place bricks: a ray cast queued
  // behind an Integrate clips its rays to it without waiting for the host (RaycastArgs).
  const int* device_box() const { return counts_.data() + kBoxAt; }
  // The most new bricks one frame places on the device without the host (SetDevicePlaceLimit
  // lowers it, for tests).
  static constexpr int kPlaceMost = 1024;

  const VolumeOptions& options() const { return mirror_.options(); }
  // Bricks in the model: on the GPU and, with a GPU budget, moved to host memory.
  // (Each of these after Settle: before it they throw.)
  std::size_t allocated_bricks() const { return Settled(), std::size_t(allocated_) + host_.size(); }
  std::size_t gpu_bricks() const { return Settled(), std::size_t(allocated_); }
  std::size_t host_bricks() const { return Settled(), host_.size(); }
  long swapped_out() const { return swapped_out_; }  // bricks moved to host memory so far
  long swapped_in() const { return swapped_in_; }    // ... and back
  std::size_t gpu_bytes() const;
  std::size_t last_visible_bricks() const { return Settled(), std::size_t(last_visible_); }
  std::size_t bytes() const;
  bool full() const { return Settled(), !full_reason_.empty(); }
  const std::string& full_reason() const { return Settled(), full_reason_; }
  // The world box of the allocated bricks (Volume::Bounds), read with the counts.
  std::array<Float3, 2> Bounds() const;
  // Device views of the arrays for the per-element functions (V: the options' encoding).
  template <typename V>
  VolumeView<V> view() const {
    VolumeView<V> v;
    v.bricks = {keys_.data(), values_.data(), std::uint32_t(keys_.size() - 1)};
    v.groups = {group_keys_.data(), group_values_.data(), std::uint32_t(group_keys_.size() - 1)};
    v.pool = reinterpret_cast<V*>(const_cast<std::uint8_t*>(pool_.data()));
    v.voxel_m = options().voxel_m;
    v.trunc_m = options().truncation_m();
    return v;
  }
  const BrickCoord* brick_coords() const { return coords_.data(); }
  // A host copy of the whole model (every allocated brick, on the GPU or moved to host
  // memory), refreshed after new frames.
  const Volume& Download();
  // Replaces the model with a host one (a project reopened).
  void Upload(const Volume& v);
  // The bricks changed since the last call (every brick on the first call and after
  // Upload), copied to the host: a flag per slot set by Integrate, read and cleared here.
  BrickSet CopyChanged();

 private:
  // Room for `bricks` in the pool (false, with the reason set, where the GPU has too little
  // memory free) and hash tables at most half full for them.
  bool Reserve(int bricks);
  void RebuildTables(std::size_t capacity);
  // With a GPU budget: the `count` bricks seen longest ago (none seen this frame) move to
  // host memory and the pool is compacted.
  void SwapOut(int count);
  int SplitVisible(int* n);  // step 2 of Integrate: counts of visible, new, to-do
  // Step 3 of Integrate on the host: the `wanted` new bricks (in fresh_) take slots up to
  // the limits, their to-do entries after those there are; the number placed.
  int PlaceOnHost(int wanted);
  // The to-do list's bricks from entry `first` on (to its count on the device) fused, then
  // the new bricks of `nb` placed and fused (the device's path; none by default).
  void IntegrateFrom(const IntegrateArgs& a, int first, const NewBricks& nb);
  void IntegrateFrom(const IntegrateArgs& a, int first);
  void FillDefaultSlots(int first);  // pool slots [first, capacity_): fresh voxels
  void Settled() const;            // throws where an Integrate is not settled
  void ReadBoxFrom(const int* b);  // box_ from the device's layout (device_box)
  void WriteBox();                 // the device's box from box_

  // counts_: visible, new, to-do, the device's placing refused (0/1), placed on the device,
  // then the box (kBoxAt: low x, y, z, high x, y, z).
  static constexpr int kBoxAt = 5, kCounts = kBoxAt + 6;
  int* counts_host_ = nullptr;      // pinned: counts_ read back behind a queued Integrate
  cudaEvent_t counted_ = nullptr;   // ... there
  bool pending_ = false;            // an Integrate queued, not settled
  bool counts_queued_ = false;      // ... its counts' read-back queued (QueueCounts)
  IntegrateArgs pending_args_{};    // its frame (Settle fuses the bricks the device left)

  Volume mirror_;  // options and limits; the host copy on request
  bool mirror_fresh_ = true;
  int vbytes_ = 0;
  DeviceBuffer<std::uint64_t> keys_, group_keys_;  // the hash tables (HashView's layout)
  DeviceBuffer<int> values_, group_values_;
  DeviceBuffer<std::uint64_t> frame_set_;           // per-frame set of visible brick keys (empty between frames)
  DeviceBuffer<std::uint64_t> visible_, fresh_, fresh_sorted_;
  DeviceBuffer<std::uint32_t> visible_at_;  // each visible key's slot in frame_set_
  DeviceBuffer<int> todo_;
  DeviceBuffer<int> counts_;  // kCounts: see above
  DeviceBuffer<std::uint8_t> temp_;
  DeviceBuffer<std::uint8_t> pool_;  // 512 encoded voxels per brick
  DeviceBuffer<BrickCoord> coords_;
  DeviceBuffer<std::uint8_t> dirty_;  // per slot: changed since the last CopyChanged
  std::unordered_set<std::uint64_t> host_dirty_;  // bricks moved out before they were copied
  int allocated_ = 0, capacity_ = 0, last_visible_ = 0;
  BrickBox box_;  // of every brick allocated since the last Upload
  std::unordered_map<std::uint64_t, std::vector<std::uint8_t>> host_;  // bricks moved out: key -> voxels
  std::vector<int> last_seen_;  // per slot: the frame that last updated it
  int frame_ = 0;
  long swapped_out_ = 0, swapped_in_ = 0;
  std::size_t host_bytes_ = 0;  // of host_
  void Extend(const BrickCoord* coords, int n);  // host coordinates
  std::string full_reason_;
};

}  // namespace hdrf::volume
