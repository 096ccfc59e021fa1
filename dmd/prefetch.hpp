#pragma once
// Asking the caches for an object ahead of its use, in a large system where it is a miss.
//
// An object of an array whose size is not a multiple of 64 B straddles cache lines differently
// from one element to the next, and a large array is not 64-byte aligned (glibc maps a block of
// 1 MiB and more at 16 B past a page boundary): a rod's 96-byte state covers two lines or three,
// its first and last byte then leaving the middle line unasked for. Every line is asked for here.
#include <cstddef>

namespace terrace::dmd {

/// Prefetches every cache line that the `bytes` bytes from `p` touch.
[[gnu::always_inline]] inline void prefetchLines(const void* p, std::size_t bytes) {
    const char* b = static_cast<const char*>(p);
    for (std::size_t k = 0; k < bytes; k += 64)
        __builtin_prefetch(b + k);
    __builtin_prefetch(b + bytes -
                       1); // the last line, where k's steps from a mid-line start miss it
}

} // namespace terrace::dmd
