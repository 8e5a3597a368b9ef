#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "common/growable_bytes.h"

namespace hdrf {
namespace {

std::uint8_t Pattern(std::size_t i) { return std::uint8_t((i * 2654435761u) >> 13); }

// Grown a brick at a time past 200 MiB (each growth a new mapping or one moved), the bytes written
// stay, every new byte is zero (also where a smaller size left bytes behind), and copies are
// deep while moves take the bytes over.
TEST(GrowableBytes, KeepsItsBytesAndZeroesNewOnesAsItGrows) {
  constexpr std::size_t kBrick = 6144;  // a compact brick's bytes: not a whole page
  GrowableBytes b;
  std::size_t growths = 0;
  for (std::size_t n = 0; n < 200u * 1024 * 1024 / kBrick; ++n) {
    const std::size_t at = b.size();
    if (b.size() + kBrick > b.capacity()) {
      b.reserve(b.size() + b.size() / 8 + kBrick);
      ++growths;
    }
    b.resize(at + kBrick);
    for (std::size_t i = at; i < b.size(); i += 97) ASSERT_EQ(b.data()[i], 0) << "byte " << i;
    for (std::size_t i = at; i < b.size(); ++i) b.data()[i] = Pattern(i);
  }
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < b.size(); ++i) wrong += b.data()[i] != Pattern(i);
  EXPECT_EQ(wrong, 0u);
  EXPECT_GE(b.capacity(), b.size());
  EXPECT_GT(growths, 50u);

  // Shrunk and grown again: the bytes past the smaller size come back as zeros.
  const std::size_t full = b.size();
  b.resize(1000);
  b.resize(full);
  wrong = 0;
  for (std::size_t i = 0; i < full; ++i) wrong += b.data()[i] != (i < 1000 ? Pattern(i) : 0);
  EXPECT_EQ(wrong, 0u);

  GrowableBytes copy = b;
  ASSERT_EQ(copy.size(), b.size());
  EXPECT_NE(copy.data(), b.data());
  copy.data()[5] = std::uint8_t(Pattern(5) + 1);
  EXPECT_EQ(b.data()[5], Pattern(5));
  const std::uint8_t* bytes = b.data();
  GrowableBytes moved = std::move(b);
  EXPECT_EQ(moved.data(), bytes);
  EXPECT_EQ(moved.size(), full);
  EXPECT_EQ(b.size(), 0u);

  const std::vector<std::uint8_t> v = {1, 2, 3};
  const GrowableBytes from(v);
  ASSERT_EQ(from.size(), 3u);
  EXPECT_EQ(from.data()[2], 3);
  EXPECT_EQ(GrowableBytes(std::vector<std::uint8_t>{}).size(), 0u);
}

}  // namespace
}  // namespace hdrf
