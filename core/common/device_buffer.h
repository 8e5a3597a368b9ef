// RAII device memory: a move-only array of T on the GPU, with explicit transfers.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "common/cuda_runtime.h"
#include "common/image.h"
#include "common/image_view.h"

namespace hdrf {

template <typename T>
class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  explicit DeviceBuffer(std::size_t count)
      : ptr_(count ? static_cast<T*>(cuda::Malloc(count * sizeof(T))) : nullptr), count_(count) {}
  ~DeviceBuffer() { cuda::Free(ptr_); }
  DeviceBuffer(DeviceBuffer&& o) noexcept
      : ptr_(std::exchange(o.ptr_, nullptr)), count_(std::exchange(o.count_, 0)) {}
  DeviceBuffer& operator=(DeviceBuffer&& o) noexcept {
    if (this != &o) {
      cuda::Free(ptr_);
      ptr_ = std::exchange(o.ptr_, nullptr);
      count_ = std::exchange(o.count_, 0);
    }
    return *this;
  }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;

  T* data() { return ptr_; }
  const T* data() const { return ptr_; }
  std::size_t size() const { return count_; }

  void Upload(const T* host, std::size_t count) {
    if (count != count_) *this = DeviceBuffer(count);
    cuda::CopyHostToDevice(ptr_, host, count * sizeof(T));
  }
  void Download(T* host) const { cuda::CopyDeviceToHost(host, ptr_, count_ * sizeof(T)); }

 private:
  T* ptr_ = nullptr;
  std::size_t count_ = 0;
};

// A device image: the buffer plus its size.
template <typename T>
class DeviceImage {
 public:
  DeviceImage() = default;
  DeviceImage(int width, int height)
      : width_(width), height_(height), buffer_(std::size_t(width) * std::size_t(height)) {}
  explicit DeviceImage(const Image<T>& host) : width_(host.width()), height_(host.height()) {
    buffer_.Upload(host.data(), host.size());
  }
  Image<T> ToHost() const {
    Image<T> out(width_, height_);
    buffer_.Download(out.data());
    return out;
  }
  int width() const { return width_; }
  int height() const { return height_; }
  ImageView<T> view() { return {buffer_.data(), width_, height_}; }
  ImageView<const T> view() const { return {buffer_.data(), width_, height_}; }
  T* data() { return buffer_.data(); }
  const T* data() const { return buffer_.data(); }

 private:
  int width_ = 0;
  int height_ = 0;
  DeviceBuffer<T> buffer_;
};

}  // namespace hdrf
