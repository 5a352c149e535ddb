#pragma once
// A hint to the CPU to start loading memory that is about to be read (MonitorBatch steps thousands of
// items whose objects are not in cache). No effect on any result.
#include <cstddef>
#include <cstdint>

namespace rocking_monitor::core {

/// Every 64-byte cache line that [p, p + bytes) touches.
inline void prefetch_lines(const void* p, std::size_t bytes = 8) {
  const auto begin = reinterpret_cast<std::uintptr_t>(p);
  for (std::uintptr_t a = begin & ~std::uintptr_t{63}; a < begin + bytes; a += 64)
    __builtin_prefetch(reinterpret_cast<const void*>(a));
}

/// Every cache line of [begin, end) (two members of one object: the range between them).
inline void prefetch_lines(const void* begin, const void* end) {
  prefetch_lines(begin, static_cast<std::size_t>(static_cast<const char*>(end) - static_cast<const char*>(begin)));
}

}  // namespace rocking_monitor::core
