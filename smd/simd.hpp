#pragma once
// Run-time choice of the AVX2 loops (smd/lj_pairs_avx2.hpp, the cell scan of
// smd/neighbour_list.hpp): they are compiled for AVX2 alone, function by function (target
// attribute), not for FMA, so that no multiply-add is fused (the build's -ffp-contract=off holds
// there too) and the rest of the binary keeps the baseline x86-64 target. A processor without AVX2,
// or a build for another architecture, runs the portable scalar loops; so does a build with
// -DTERRACE_NO_AVX2, which leaves the AVX2 code out (to check that the fallback builds alone).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(TERRACE_NO_AVX2)
#include <immintrin.h>
#define TERRACE_SMD_AVX2 1
// The entry points never inlined into their baseline callers: GCC would not anyway, and clang 14
// does under the sanitisers and then fails to select AVX2 instructions ("Cannot select").
#define TERRACE_AVX2 __attribute__((target("avx2"), noinline))
#define TERRACE_AVX2_INLINE __attribute__((target("avx2"), always_inline))
#else
#define TERRACE_SMD_AVX2 0
#endif

namespace terrace::smd {

/// True when the processor runs the AVX2 loops; checked once.
inline bool avx2Available() {
#if TERRACE_SMD_AVX2
    static const bool available = __builtin_cpu_supports("avx2");
    return available;
#else
    return false;
#endif
}

} // namespace terrace::smd
