// A byte array for a store that only grows (the volume's voxel pool), grown in place.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace hdrf {

// The bytes live in a private anonymous mapping grown with mremap: the kernel moves the
// pages' table entries, not the bytes, so growing a pool of gigabytes neither copies it nor
// needs the old and the new array at once (std::vector's growth did both: a stall of tens of
// milliseconds at every growth of a 20 MiB pool, growing with the model). New bytes are zero.
// Host only; Linux. Failures to map throw std::bad_alloc.
class GrowableBytes {
 public:
  GrowableBytes() = default;
  explicit GrowableBytes(std::span<const std::uint8_t> from);
  GrowableBytes(const GrowableBytes& o) : GrowableBytes(o.span()) {}
  GrowableBytes(GrowableBytes&& o) noexcept;
  GrowableBytes& operator=(const GrowableBytes& o);
  GrowableBytes& operator=(GrowableBytes&& o) noexcept;
  ~GrowableBytes();

  std::uint8_t* data() { return p_; }
  const std::uint8_t* data() const { return p_; }
  std::size_t size() const { return size_; }
  std::size_t capacity() const { return cap_; }
  std::span<const std::uint8_t> span() const { return {p_, size_}; }
  // Room for n bytes without moving again (whole pages).
  void reserve(std::size_t n);
  // n bytes; those past the old size are zero.
  void resize(std::size_t n);

 private:
  std::uint8_t* p_ = nullptr;
  std::size_t size_ = 0, cap_ = 0;
  std::size_t used_ = 0;  // the largest size so far: bytes past it are still zero
};

}  // namespace hdrf
