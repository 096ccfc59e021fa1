#pragma once
// The model both engines simulate: a pair potential U times the switch g(r) of its smoothed cutoff
// (core/smoothed_cutoff.hpp, paper eqs. 22-23),
//     U_s(r_ij, s_i, s_j) = g(|r_ij|) U(r_ij, s_i, s_j).
// SMD integrates U_s; DMD terraces it, so that as the terrace height ΔV → 0 the two converge to the
// same model and every difference left between them is the terracing's. The paper's own DMD, the
// bare U terraced out to r_m, is the same wrapper with no cutoff (SmoothedCutoff::none(), g = 1).
//
// What the engines ask of U_s beyond U's own answers:
//   dU_s/dt = g dU/dt + U g'(r) ṙ,   ṙ = r̂_ij·v_ij  (the chain rule; g depends on r alone);
//   the lowest value: that of U (g ≤ 1 only scales a negative U towards 0; exact when the minimum
//   lies inside r_l, as for every cutoff a scene accepts);
//   the reach of a value u (largest r at which U_s = u for some orientation): U's reach where that
//   is inside r_l; beyond r_l, for u < 0, the root of g(r)·Ulow(r) = u with Ulow(r) the lowest U
//   over orientations at centre distance r, which rises monotonically through the switch (g falls,
//   U is negative and rises towards 0 along the tail), found by bisection and rounded outwards.
// A mixture may switch each pair on its own [r_l, r_u] (core/lj_mixture.hpp, cutOfPair): then
// `cut` is the envelope of the pairs' switches (the least r_l, the largest r_u), which bounds the
// range for cells and lists and the distance under which every pair is its bare U, and each pair
// is switched, and its reach found, on its own.
// Units: Å, kJ/mol (those of the wrapped potential).
#include "core/pair_potential.hpp"
#include "core/smoothed_cutoff.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>
#include <type_traits>

namespace terrace {

template <PairPotential P> struct Smoothed {
    using Bare = P;
    static constexpr std::string_view name = P::name;
    static constexpr AttitudeUse attitude = P::attitude;
    using Orientation = typename P::Orientation;

    P bare;
    SmoothedCutoff cut = SmoothedCutoff::none();

    // Where P has one (else none): the same bare potential under the same cutoff.
    bool operator==(const Smoothed&) const = default;

    /// The distance beyond which U_s is 0 (Å; +∞ without a cutoff).
    double range() const { return cut.outer(); }

    /// The switch of the pair (si, sj): its own where the potential cuts each pair apart.
    const SmoothedCutoff& cutOfPair(const Orientation& si, const Orientation& sj) const {
        if constexpr (requires { bare.cutoffOf(si, sj); })
            if (bare.cutPerPair) return bare.cutoffOf(si, sj);
        return cut;
    }

    PairForce evaluate(const Vec3& rij, const Orientation& si, const Orientation& sj) const {
        const SmoothedCutoff& cut = cutOfPair(si, sj);
        const double r2 = rij.squaredNorm();
        if (r2 <= cut.inner() * cut.inner()) return bare.evaluate(rij, si, sj);
        if (r2 >= cut.outer() * cut.outer()) return PairForce{};
        return smoothed(bare.evaluate(rij, si, sj), rij, std::sqrt(r2), cut);
    }

    double energy(const Vec3& rij, const Orientation& si, const Orientation& sj) const {
        const SmoothedCutoff& cut = cutOfPair(si, sj);
        const double r2 = rij.squaredNorm();
        if (r2 <= cut.inner() * cut.inner()) return bare.energy(rij, si, sj);
        if (r2 >= cut.outer() * cut.outer()) return 0.0;
        return cut.switching(std::sqrt(r2)) * bare.energy(rij, si, sj);
    }

    EnergyRate energyRate(const Vec3& rij, const Vec3& vij, const Orientation& si, const Vec3& wi,
                          const Orientation& sj, const Vec3& wj) const {
        const SmoothedCutoff& cut = cutOfPair(si, sj);
        const double r2 = rij.squaredNorm();
        if (r2 <= cut.inner() * cut.inner()) return energyAndRate(bare, rij, vij, si, wi, sj, wj);
        if (r2 >= cut.outer() * cut.outer()) return {};
        const EnergyRate e = energyAndRate(bare, rij, vij, si, wi, sj, wj);
        const double r = std::sqrt(r2), g = cut.switching(r);
        return {g * e.U, g * e.dUdt + e.U * cut.switchingSlope(r) * rij.dot(vij) / r};
    }

    /// U_s = g·U over the neighbourhood: g is non-increasing in r, so over the centre distances
    /// [r − shift, r + shift] it lies between its values at the ends, and the bilinear g·U is
    /// extreme at a corner of (g range) × (U's range).
    EnergyRange energyRange(const Vec3& rij, const Orientation& si, const Orientation& sj,
                            double shift, double turnI,
                            double turnJ) const requires RangeBounded<P> {
        const SmoothedCutoff& cut = cutOfPair(si, sj);
        const double r = rij.norm();
        const double rLo = std::max(0.0, r - shift), rHi = r + shift;
        if (rLo >= cut.outer()) return {};
        const EnergyRange u = bare.energyRange(rij, si, sj, shift, turnI, turnJ);
        if (rHi <= cut.inner()) return u;
        const double gMax = cut.switching(rLo), gMin = cut.switching(rHi);
        return {std::min(gMin * u.lo, gMax * u.lo), std::isfinite(u.hi)
                                                        ? std::max(gMin * u.hi, gMax * u.hi)
                                                        : std::numeric_limits<double>::infinity()};
    }

    double minimumEnergy() const { return bare.minimumEnergy(); }

    double reachDistance(double u) const {
        if constexpr (requires { bare.pairReach(u, 0, 0); })
            if (bare.cutPerPair) {
                // The farthest of the pairs' reaches, each through its own switch.
                double r = 0.0;
                for (int a = 0; a < bare.species; ++a)
                    for (int b = a; b < bare.species; ++b)
                        r = std::max(
                            r, reachThrough(u, bare.pairReach(u, a, b), bare.cutoffOf(a, b),
                                            [&](double x) { return bare.pairEnergyAt(x, a, b); }));
                return r;
            }
        if constexpr (requires { bare.lowestEnergyAt(1.0); })
            return reachThrough(u, bare.reachDistance(u), cut,
                                [&](double x) { return bare.lowestEnergyAt(x); });
        else
            return reachThrough(u, bare.reachDistance(u), cut, nullptr);
    }

private:
    /// The reach of u under the switch c, from the bare reach and Ulow (the lowest U at a centre
    /// distance; nullptr where unknown).
    template <class Lowest>
    static double reachThrough(double u, double bareReach, const SmoothedCutoff& c,
                               const Lowest& lowestAt) {
        if (bareReach <= c.inner()) return bareReach;
        const double outer = std::min(bareReach, c.outer());
        if constexpr (!std::is_null_pointer_v<Lowest>) {
            // Ulow(r_l) ≤ u < 0 = g(r_u)·Ulow(r_u): the root lies in [r_l, outer].
            if (u < 0.0) {
                double lo = c.inner(), hi = outer;
                for (int k = 0; k < 200 && hi - lo > 1e-13 * hi; ++k) {
                    const double mid = 0.5 * (lo + hi);
                    (c.switching(mid) * lowestAt(mid) <= u ? lo : hi) = mid;
                }
                return hi; // g·Ulow(hi) > u or hi = outer: no r beyond hi reaches u
            }
        }
        return outer; // a bound: no closer estimate without Ulow
    }
};

} // namespace terrace
