#pragma once
// How long a pair is sure to stay on its terrace, from bounds on its free motion alone: a screen
// in front of the adaptive search (dmd/root_search.hpp), which spends two or more samples of U on
// every pair it examines even when no level is within reach before the horizon.
//
// For a potential that is a function φ(r_e) of one effective distance r_e = r + ζ(½ − c²) (the
// paper's rods, eq. 24; plain Lennard-Jones with ζ = 0), a terrace (lower, upper) is a band of r_e:
// φ falls along the repulsive wall and rises along the tail, so {φ ∈ (lower, upper)} is one
// interval on each side of the minimum, or a single interval across it when lower lies below the
// minimum. In free flight the pair stays in its band for a while that bounds on its motion give:
//   - r(τ) = |r₀ + v_ij τ| is convex, so r(τ) ≥ r₀ + ṙ₀τ, and √(r₀² + X) ≤ r₀ + X/(2r₀) gives
//     r(τ) ≤ r₀ + ṙ₀τ + |v_ij|²τ²/(2r₀);
//   - the alignment c = s_i·s_j changes at most at |ċ| ≤ |ṡ_i| + |ṡ_j| = Ω and, for linear rotors
//     (|s̈| = |ω|²), |c̈| ≤ |s̈_i| + 2|ṡ_i||ṡ_j| + |s̈_j| = Ω² = K, so by Taylor's theorem c(τ)
//     lies between c₀ + ċ₀τ − ½Kτ² and c₀ + ċ₀τ + ½Kτ², and within Ωτ of c₀; the upper parabola
//     is convex and the lower one concave, so over [0, T] each is extreme at an end, and
//         c ≤ c_hi = min(1, c₀ + min(ΩT, max(0, T(ċ₀ + ½KT)))),
//         c ≥ c_lo = max(−1, c₀ − min(ΩT, max(0, T(½KT − ċ₀))))
//     (the sign of ċ₀ counts: an alignment turning one way only nears the band's edge on that
//     side, and the other side only once the curvature has turned it round), and |c| lies
//     between max(0, c_lo, −c_hi) and max(c_hi, −c_lo);
// all these bounds widen with T, so over [0, T] r_e ≥ r_lo + ζ(½ − max|c|²) and
// r_e ≤ r_hi + ζ(½ − min|c|²) (ζ ≥ 0) with the envelopes taken at T. No level can be reached
// while both stay inside the band. In a dense liquid this holds most of the pairs a collision
// would have the search examine for the whole horizon, often for several.
//
// The smoothed model g(r)·φ(r_e) (core/smoothed_potential.hpp) equals φ wherever r ≤ r_l, so the
// bands of φ serve it as long as the centre distance stays below r_l too: its upper envelope is
// held under a ceiling r_l. When r_m ≤ r_l no ceiling is needed: a pair off terrace 0 inside its
// band has r < r_e + ζ/2 ≤ r_m (the band's edge is a root of a level no farther out than those of
// terrace 0), and a pair on terrace 0 can meet a level of the model only inside r_m, where g = 1.
// Units: Å, time unit 100 fs (rates per time unit, angles in rad).
#include "core/branch_free.hpp"
#include "dmd/terrace_levels.hpp"
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <algorithm>
#include <cassert>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace terrace::dmd {

/// A pair potential that is φ(r_e) of one effective distance, with the roots of φ = u on each side
/// of the minimum (core/pair_potential.hpp, detail::RadialRoots).
template <class P>
concept EffectiveDistanceForm = requires(const P p, double r, double c, double u) {
    { p.effectiveDistance(r, c) } -> std::convertible_to<double>;
    { p.alignmentLength() } -> std::convertible_to<double>; // ζ, Å
    { p.radialRoots(u).inner } -> std::convertible_to<double>;
    { p.radialRoots(u).outer } -> std::convertible_to<double>;
    { p.minimumEnergy() } -> std::convertible_to<double>;
};

/// An interval of effective distance, Å (lo may be 0, hi +∞; empty when lo ≥ hi).
struct DistanceBand {
    double lo = 0.0, hi = 0.0;
};

/// The bands of r_e over which φ lies strictly between lower and upper: on the wall side of the
/// minimum and on the tail side (the same interval twice when the terrace holds the minimum).
struct TerraceBands {
    DistanceBand wall, tail;
    double bottom; // effective distance of the minimum, where the two sides meet
};

template <EffectiveDistanceForm P>
TerraceBands terraceBands(const P& p, double lower, double upper) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    const double uMin = p.minimumEnergy();
    TerraceBands b;
    b.bottom = p.radialRoots(uMin).inner;
    if (!(upper > uMin)) { // the terrace lies below the minimum: no distance is on it
        b.wall = b.tail = {b.bottom, b.bottom};
        return b;
    }
    const auto top =
        std::isfinite(upper) ? p.radialRoots(upper) : decltype(p.radialRoots(upper)){0.0, inf};
    if (!(lower > uMin)) { // the minimum is on the terrace: one band across it
        b.wall = b.tail = {top.inner, top.outer};
        return b;
    }
    const auto floor = p.radialRoots(lower); // outer = +∞ when lower ≥ 0: no tail part
    b.wall = {top.inner, floor.inner};
    b.tail = {floor.outer, top.outer};
    return b;
}

/// A pair's motion now, as far as the bounds on its effective distance need it.
struct PairMotion {
    double r = 0.0;            // centre distance |r_ij|, Å
    double rRate = 0.0;        // d|r_ij|/dt = r̂_ij·v_ij
    double speedSquared = 0.0; // |v_ij|²
    double c = 0.0;            // alignment s_i·s_j
    double cRate = 0.0;        // dc/dt = (ω_i − ω_j)·(s_i × s_j)
    double turn = 0.0;         // bound on |dc/dt| during the flight, |ṡ_i| + |ṡ_j|
    double turnCurvature = std::numeric_limits<double>::infinity(); // on |d²c/dt²| (∞: none)
};

/// The envelopes of one pair's effective distance r_e = r + ζ(½ − c²), prepared once and asked
/// at several times T (time units).
class BandHold {
public:
    /// ceiling: the centre distance must stay below it too (Å; +∞ for none).
    BandHold(const DistanceBand& band, const PairMotion& m, double zeta,
             double ceiling = std::numeric_limits<double>::infinity())
        : r_(m.r), rRate_(m.rRate), rBend_(0.5 * m.speedSquared / m.r), c_(m.c), cRate_(m.cRate),
          turn_(m.turn),
          // Finite even without a curvature bound (∞), so that T = 0 gives 0·finite, not 0·∞.
          cBend_(lesser(0.5 * m.turnCurvature, std::numeric_limits<double>::max())), zeta_(zeta),
          // An edge is kept a relative 1e-9 closer than it is, far above the round-off of r_e and
          // of the band's roots, so that the answer holds for the computed U as well.
          lo_(band.lo + edgeMargin * m.r), hi_(band.hi - edgeMargin * m.r),
          ceiling_(ceiling - edgeMargin * m.r) {}

    /// Whether r_e is sure to stay inside the band throughout [0, T]. (Inlined: the few flops
    /// cost less than the call the compiler would otherwise make for each of the ladder's rungs.)
    [[gnu::always_inline]] bool through(double T) const {
        // Without branches (core/branch_free.hpp): each comparison here is a coin toss.
        const double rLow = r_ + lesser(0.0, rRate_ * T);
        const double rHigh = r_ + greater(0.0, T * (rRate_ + rBend_ * T));
        // Each max(0, T(a + bT)) with b ≥ 0 grows with T, as rHigh's does: the ladder needs that.
        const double reach = turn_ * T, up = T * (cRate_ + cBend_ * T),
                     down = T * (cBend_ * T - cRate_);
        const double cHigh = lesser(1.0, c_ + lesser(reach, greater(0.0, up)));
        const double cLow = greater(-1.0, c_ - lesser(reach, greater(0.0, down)));
        const double cMost = greater(cHigh, -cLow);
        const double cLeast = greater(0.0, greater(cLow, -cHigh));
        // & rather than &&: both sides are cheap, and a branch between them would mispredict.
        return (rLow + zeta_ * (0.5 - cMost * cMost) > lo_) &
               (rHigh + zeta_ * (0.5 - cLeast * cLeast) < hi_) & (rHigh < ceiling_);
    }

    /// through(T0) + through(T1): the same operations on both times at once, lane by lane in one
    /// SSE2 register (baseline on x86-64), so the same answers in half the instructions.
    [[gnu::always_inline]] int throughBoth(double T0, double T1) const {
#if defined(__SSE2__)
        const __m128d T = _mm_set_pd(T1, T0), zero = _mm_setzero_pd(), one = _mm_set1_pd(1.0),
                      half = _mm_set1_pd(0.5), r = _mm_set1_pd(r_), rRate = _mm_set1_pd(rRate_),
                      c = _mm_set1_pd(c_), zeta = _mm_set1_pd(zeta_);
        const __m128d rLow = _mm_add_pd(r, _mm_min_pd(zero, _mm_mul_pd(rRate, T)));
        const __m128d rHigh = _mm_add_pd(
            r,
            _mm_max_pd(zero, _mm_mul_pd(T, _mm_add_pd(rRate, _mm_mul_pd(_mm_set1_pd(rBend_), T)))));
        const __m128d cRate = _mm_set1_pd(cRate_), cBendT = _mm_mul_pd(_mm_set1_pd(cBend_), T);
        const __m128d reach = _mm_mul_pd(_mm_set1_pd(turn_), T),
                      up = _mm_mul_pd(T, _mm_add_pd(cRate, cBendT)),
                      down = _mm_mul_pd(T, _mm_sub_pd(cBendT, cRate));
        const __m128d cHigh =
            _mm_min_pd(one, _mm_add_pd(c, _mm_min_pd(reach, _mm_max_pd(zero, up))));
        const __m128d cLow =
            _mm_max_pd(_mm_set1_pd(-1.0), _mm_sub_pd(c, _mm_min_pd(reach, _mm_max_pd(zero, down))));
        const __m128d sign = _mm_set1_pd(-0.0); // x ^ sign = −x, as in through()
        const __m128d cMost = _mm_max_pd(cHigh, _mm_xor_pd(cLow, sign));
        const __m128d cLeast = _mm_max_pd(zero, _mm_max_pd(cLow, _mm_xor_pd(cHigh, sign)));
        const __m128d low =
            _mm_add_pd(rLow, _mm_mul_pd(zeta, _mm_sub_pd(half, _mm_mul_pd(cMost, cMost))));
        const __m128d high =
            _mm_add_pd(rHigh, _mm_mul_pd(zeta, _mm_sub_pd(half, _mm_mul_pd(cLeast, cLeast))));
        const int inside = _mm_movemask_pd(_mm_and_pd(
            _mm_and_pd(_mm_cmpgt_pd(low, _mm_set1_pd(lo_)), _mm_cmplt_pd(high, _mm_set1_pd(hi_))),
            _mm_cmplt_pd(rHigh, _mm_set1_pd(ceiling_))));
        return (inside & 1) + (inside >> 1);
#else
        return int(through(T0)) + int(through(T1));
#endif
    }

private:
    static constexpr double edgeMargin = 1e-9;
    double r_, rRate_, rBend_, c_, cRate_, turn_, cBend_, zeta_, lo_, hi_, ceiling_;
};

/// The potential whose bands the hold screen uses: P itself, or the bare potential of a smoothed
/// model (core/smoothed_potential.hpp).
template <class P> const auto& bandPotential(const P& p) {
    if constexpr (requires {
                      p.bare;
                      p.cut;
                  })
        return p.bare;
    else
        return p;
}

/// Whether the hold screen applies to P: its bands' potential has the effective-distance form.
template <class P>
concept HoldScreenable =
    EffectiveDistanceForm<std::decay_t<decltype(bandPotential(std::declval<const P&>()))>>;

/// The ceiling on the centre distance under which the bands of bandPotential(p) describe p, for an
/// interaction range rm (Å): none for a bare potential, or when rm ≤ r_l (see above); else r_l.
template <class P> double bandCeiling(const P& p, double rm) {
    if constexpr (requires {
                      p.bare;
                      p.cut;
                  })
        if (rm > p.cut.inner()) return p.cut.inner();
    return std::numeric_limits<double>::infinity();
}

/// The longest of first, 2·first, 4·first, … (none beyond last; first > 0, last finite) through
/// which the pair is sure to stay in its band; 0 when not even through first (right after an
/// event the pair sits on a level: 0). through(T) only fails more as T grows (both envelopes
/// widen monotonically, and rounding keeps that order), so the number of rungs it holds through
/// gives the answer: every rung is tried, with no branch on the outcome, which no predictor could
/// guess (in a liquid each rung is a common answer). Inlined into its one caller in the engine,
/// which then passes the hold in registers instead of through memory.
[[gnu::always_inline]] inline double holdTime(const BandHold& hold, double first, double last) {
    assert(first > 0.0 && last < 0x1p60 * first); // the loop ends, the shift below is defined
    int rungs = 0;
    double T = first;
    for (; 2.0 * T <= last; T *= 4.0)
        rungs += hold.throughBoth(T, 2.0 * T);
    if (T <= last) rungs += hold.through(T);
    // 2^(rungs − 1) rungs' worth, and 0 for none, without a branch on rungs = 0 (a coin toss too)
    return first * static_cast<double>((std::uint64_t{2} << rungs) >> 2);
}

/// terraceBands of every terrace the pairs have visited, computed once each (two pow() per level).
class TerraceBandTable {
public:
    template <EffectiveDistanceForm P>
    const TerraceBands& of(int n, const P& p, const TerraceLevels& levels) {
        const auto k = static_cast<std::size_t>(n - first_); // wraps for n < first_
        if (k < bands_.size() && bands_[k].known) return bands_[k].bands;
        return add(n, p, levels);
    }
    std::size_t bytesReserved() const { return bands_.capacity() * sizeof(Entry); }

private:
    struct Entry {
        TerraceBands bands;
        bool known = false;
    };
    template <EffectiveDistanceForm P>
    [[gnu::noinline]] const TerraceBands& add(int n, const P& p, const TerraceLevels& levels) {
        if (bands_.empty()) first_ = n;
        if (n < first_) {
            bands_.insert(bands_.begin(), static_cast<std::size_t>(first_ - n), Entry{});
            first_ = n;
        }
        const auto k = static_cast<std::size_t>(n - first_);
        if (k >= bands_.size()) bands_.resize(k + 1);
        bands_[k] = {terraceBands(p, levels.lower(n), levels.upper(n)), true};
        return bands_[k].bands;
    }
    std::vector<Entry> bands_; // terrace first_ + k at k
    int first_ = 0;
};

} // namespace terrace::dmd
