// A per-frame series the scan appends to and every snapshot shares (the trajectory, the
// exposure ratios): a snapshot holds the series as it stood at its frame without a copy, so a
// frame costs the same after ten thousand frames as after ten. The scan thread appends; the
// window reads a snapshot's prefix on its own thread.
//
// The values live in a buffer of fixed length, written once each, by index, past the end of
// every prefix already handed out, so a reader's values never change under it. When the
// buffer is full the values move to one twice as long (snapshots keep the old one alive).
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace hdrf::gui {

template <typename T>
class SharedSeries {
 public:
  // The first `size` values as they stood when it was taken; cheap to copy.
  class Prefix {
   public:
    Prefix() = default;
    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    const T& operator[](std::size_t i) const { return (*buffer_)[i]; }
    const T& back() const { return (*buffer_)[size_ - 1]; }
    const T* begin() const { return buffer_ ? buffer_->data() : nullptr; }
    const T* end() const { return begin() + size_; }
    std::span<const T> span() const { return {begin(), size_}; }

   private:
    friend class SharedSeries;
    Prefix(std::shared_ptr<const std::vector<T>> b, std::size_t n) : buffer_(std::move(b)), size_(n) {}
    std::shared_ptr<const std::vector<T>> buffer_;
    std::size_t size_ = 0;
  };

  void Append(const T& v) {
    if (!buffer_ || size_ == buffer_->size()) {
      auto bigger = std::make_shared<std::vector<T>>(std::max<std::size_t>(kFirstLength, 2 * size_));
      if (buffer_) std::copy(buffer_->begin(), buffer_->begin() + long(size_), bigger->begin());
      buffer_ = std::move(bigger);
      ++buffers_made_;
    }
    (*buffer_)[size_++] = v;
  }
  // Forgets every value (a new scan, a project opened); prefixes handed out keep theirs.
  void Clear() {
    buffer_.reset();
    size_ = 0;
  }
  std::size_t size() const { return size_; }
  Prefix prefix() const { return Prefix(buffer_, size_); }
  // Buffers allocated so far (about log2 of the longest series: the test of the growth).
  int buffers_made() const { return buffers_made_; }

  static constexpr std::size_t kFirstLength = 256;

 private:
  std::shared_ptr<std::vector<T>> buffer_;
  std::size_t size_ = 0;
  int buffers_made_ = 0;
};

}  // namespace hdrf::gui
