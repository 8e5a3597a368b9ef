// Non-owning views of a width x height pixel grid, usable in per-element code on host and
// device: the CPU loops take them from hdrf::Image, the CUDA kernels from DeviceImage.
#pragma once

#include <type_traits>

#include "common/host_device.h"
#include "common/image.h"

namespace hdrf {

template <typename T>
struct ImageView {
  T* data = nullptr;
  int width = 0;
  int height = 0;

  HDRF_HD T& operator()(int x, int y) const { return data[y * width + x]; }
  HDRF_HD T& operator[](int i) const { return data[i]; }
  HDRF_HD int size() const { return width * height; }
  // A read-only view of the same pixels.
  template <typename U = T>
    requires(!std::is_const_v<U>)
  HDRF_HD operator ImageView<const U>() const { return {data, width, height}; }
};

template <typename T>
ImageView<T> View(Image<T>& im) {
  return {im.data(), im.width(), im.height()};
}
template <typename T>
ImageView<const T> View(const Image<T>& im) {
  return {im.data(), im.width(), im.height()};
}

}  // namespace hdrf
