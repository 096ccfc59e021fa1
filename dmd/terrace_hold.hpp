#pragma once
// How long a pair is sure to stay on its terrace, from bounds on its free motion alone: a screen
// in front of the adaptive search (dmd/root_search.hpp), which spends two or more samples of U on
// every pair it examines even when no level is within reach before the horizon.
//
// For a potential that is a function φ(r_e) of one effective distance r_e = r + ζ(½ − c²) (the
// paper's rods, eq. 24; plain Lennard-Jones with ζ = 0), a terrace (lower, upper) is a band of r_e:
// φ falls along the repulsive wall and rises along the tail, so {φ ∈ (lower, upper)} is one
// interval on each side of the minimum, or a single interval across it when lower lies below the
// minimum. In free flight the centre distance changes at most at the relative speed,
// |dr/dt| ≤ |v_ij|, and the alignment c = s_i·s_j at most at the axes' summed turning rate,
// |dc/dt| ≤ |ṡ_i| + |ṡ_j| = Ω. Hence, over a time τ, with c₀ the alignment now,
//     r_e(τ) ≥ r_e(0) − (|v_ij| + 2ζ|c₀|Ω) τ − ζΩ²τ²     (c² ≤ (|c₀| + Ωτ)²)
//     r_e(τ) ≤ r_e(0) + (|v_ij| + 2ζ|c₀|Ω) τ             (c² ≥ c₀² − 2|c₀|Ωτ)
// and no level can be reached before the first of these bounds meets an edge of the band. In the
// paper's dense liquid at ΔV = kT/2 this rules out about half of the searched pairs for the whole
// horizon, often for several.
// Units: Å, time unit 100 fs (speeds per time unit, Ω in rad per time unit).
#include "dmd/terrace_levels.hpp"
#include <algorithm>
#include <cmath>
#include <concepts>
#include <limits>
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

/// A lower bound (time units) on how long r_e stays inside band, starting at x (Å), when the
/// centres part or close at most at `speed` (|v_ij|, Å per time unit) and the alignment |c| = cAbs
/// changes at most at `turn` (|ṡ_i| + |ṡ_j|); zeta is the potential's alignment length. 0 when x
/// is on an edge or outside (right after an event the pair sits on a level), +∞ for a pair that
/// neither moves nor turns. An edge is kept a relative 1e-9 closer than it is, far above the
/// round-off of x and of the roots, so that the bound holds for the computed U as well.
inline double holdTime(const DistanceBand& band, double x, double speed, double cAbs, double turn,
                       double zeta) {
    constexpr double edgeMargin = 1e-9;
    const double below = x - band.lo - edgeMargin * x;
    const double above = band.hi - x - edgeMargin * x;
    if (!(below > 0.0 && above > 0.0)) return 0.0;
    const double drift = speed + 2.0 * zeta * cAbs * turn; // Å per time unit
    const double bend = zeta * turn * turn;                // Å per time unit²
    // The positive root of bend τ² + drift τ = below, in cancellation-free form.
    const double down = 2.0 * below / (drift + std::sqrt(drift * drift + 4.0 * bend * below));
    const double up = above / drift;
    return std::min(down, up);
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
    const TerraceBands& add(int n, const P& p, const TerraceLevels& levels) {
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
