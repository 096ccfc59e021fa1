#pragma once
// The smaller and larger of two doubles without a branch, for hot code whose comparisons are coin
// tosses to the branch predictor (whether a pair approaches, whether a bound saturates). GCC 12
// at -O2 compiles std::min and std::max on doubles to a compare and a jump in such code; SSE2's
// minsd and maxsd (baseline on x86-64) select in one instruction. They agree with std::min and
// std::max except for the sign of a zero result (min(0, −0)) and for NaN arguments.
#include <algorithm>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace terrace {

/// a < b ? a : b
inline double lesser(double a, double b) {
#if defined(__SSE2__)
    return _mm_cvtsd_f64(_mm_min_sd(_mm_set_sd(a), _mm_set_sd(b)));
#else
    return std::min(a, b);
#endif
}

/// a > b ? a : b
inline double greater(double a, double b) {
#if defined(__SSE2__)
    return _mm_cvtsd_f64(_mm_max_sd(_mm_set_sd(a), _mm_set_sd(b)));
#else
    return std::max(a, b);
#endif
}

} // namespace terrace
