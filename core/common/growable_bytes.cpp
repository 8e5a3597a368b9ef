#include "common/growable_bytes.h"

#include <sys/mman.h>
#include <unistd.h>

#include <cstring>
#include <new>
#include <utility>

namespace hdrf {
namespace {

std::size_t WholePages(std::size_t n) {
  static const std::size_t page = std::size_t(sysconf(_SC_PAGESIZE));
  return (n + page - 1) / page * page;
}

}  // namespace

GrowableBytes::GrowableBytes(std::span<const std::uint8_t> from) {
  resize(from.size());
  if (!from.empty()) std::memcpy(p_, from.data(), from.size());
}

GrowableBytes::GrowableBytes(GrowableBytes&& o) noexcept
    : p_(std::exchange(o.p_, nullptr)),
      size_(std::exchange(o.size_, 0)),
      cap_(std::exchange(o.cap_, 0)),
      used_(std::exchange(o.used_, 0)) {}

GrowableBytes& GrowableBytes::operator=(const GrowableBytes& o) {
  if (this != &o) *this = GrowableBytes(o);
  return *this;
}

GrowableBytes& GrowableBytes::operator=(GrowableBytes&& o) noexcept {
  std::swap(p_, o.p_);
  std::swap(size_, o.size_);
  std::swap(cap_, o.cap_);
  std::swap(used_, o.used_);
  return *this;
}

GrowableBytes::~GrowableBytes() {
  if (p_) munmap(p_, cap_);
}

void GrowableBytes::reserve(std::size_t n) {
  if (n <= cap_) return;
  const std::size_t cap = WholePages(n);
  void* p = p_ ? mremap(p_, cap_, cap, MREMAP_MAYMOVE)
               : mmap(nullptr, cap, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) throw std::bad_alloc();
  p_ = static_cast<std::uint8_t*>(p);
  cap_ = cap;
}

void GrowableBytes::resize(std::size_t n) {
  if (n > size_) {
    reserve(n);
    // A fresh mapping's pages are zero: only bytes an earlier, larger size used are cleared.
    if (used_ > size_) std::memset(p_ + size_, 0, (n < used_ ? n : used_) - size_);
  }
  size_ = n;
  used_ = used_ > n ? used_ : n;
}

}  // namespace hdrf
