#pragma once
// Asking the caches for an object ahead of its use, in a large system where it is a miss.
//
// An object of an array whose size is not a multiple of 64 B straddles cache lines differently
// from one element to the next, and a large array is not 64-byte aligned (glibc maps a block of
// 1 MiB and more at 16 B past a page boundary): a list record of 176 B covers three lines or four,
// a sphere's 48-byte state one or two, and asking for an object's first and last byte leaves any
// middle line out. Here each line it covers is asked for once. (A rod's state is aligned to 32 B
// so that it always covers two: core/linear_rotor.hpp.)
#include <cstddef>
#include <cstdint>

namespace terrace::dmd {

inline constexpr std::uintptr_t cacheLine = 64; // bytes

/// The start of the first cache line the `bytes` (> 0) bytes at `address` touch, and how many.
struct LinesCovered {
    std::uintptr_t first;
    std::size_t count;
};
constexpr LinesCovered linesCovered(std::uintptr_t address, std::size_t bytes) {
    const std::uintptr_t first = address & ~(cacheLine - 1);
    const std::uintptr_t last = (address + bytes - 1) & ~(cacheLine - 1);
    return {first, static_cast<std::size_t>((last - first) / cacheLine + 1)};
}

/// Prefetches every cache line that the `bytes` bytes from `p` touch, each once.
[[gnu::always_inline]] inline void prefetchLines(const void* p, std::size_t bytes) {
    const LinesCovered lines = linesCovered(reinterpret_cast<std::uintptr_t>(p), bytes);
    for (std::size_t k = 0; k < lines.count; ++k)
        __builtin_prefetch(reinterpret_cast<const void*>(lines.first + k * cacheLine));
}

} // namespace terrace::dmd
