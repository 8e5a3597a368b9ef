// What the machine has: checked before large allocations, so that a request the machine
// cannot hold is refused with a message rather than ending in std::bad_alloc.
#pragma once

#include <cstddef>
#include <optional>

namespace hdrf {

// Bytes of host memory the system could give now (MemAvailable), or nullopt where unknown.
std::optional<std::size_t> AvailableHostBytes();

}  // namespace hdrf
