// Host images: a width x height grid of pixels, row-major, move-only (copy with Clone()).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "common/camera.h"

namespace hdrf {

struct Rgb8 {
  std::uint8_t r, g, b;
  friend bool operator==(const Rgb8&, const Rgb8&) = default;
};

template <typename T>
class Image {
 public:
  Image() = default;
  Image(int width, int height, T fill = T{})
      : width_(width), height_(height), data_(std::size_t(width) * std::size_t(height), fill) {}
  Image(Image&&) noexcept = default;
  Image& operator=(Image&&) noexcept = default;
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;

  Image Clone() const {
    Image out(width_, height_);
    out.data_ = data_;
    return out;
  }

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t size() const { return data_.size(); }
  bool empty() const { return data_.empty(); }
  T* data() { return data_.data(); }
  const T* data() const { return data_.data(); }
  T& operator()(int x, int y) { return data_[std::size_t(y) * std::size_t(width_) + std::size_t(x)]; }
  const T& operator()(int x, int y) const {
    return data_[std::size_t(y) * std::size_t(width_) + std::size_t(x)];
  }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<T> data_;
};

using ColorImage = Image<Rgb8>;             // 8-bit colour as delivered by the sensor
using DepthRawImage = Image<std::uint16_t>;  // depth in sensor units (value / scale = metres)
using DepthImage = Image<float>;            // depth in metres, 0 = no data
using RadianceImage = Image<Float3>;        // linear radiance, RGB

}  // namespace hdrf
