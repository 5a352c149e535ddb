#pragma once
// The heap allocation counter of allocation_counter.hpp, without the operator new/delete it
// replaces: for files that read allocation_count() in a program whose one allocation_counter.hpp
// include is in another file.

#include <atomic>

namespace rocking_monitor::testing {
inline std::atomic<long> g_allocation_count{0};
inline long allocation_count() { return g_allocation_count.load(std::memory_order_relaxed); }
}  // namespace rocking_monitor::testing
