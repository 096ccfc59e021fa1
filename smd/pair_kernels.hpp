#pragma once
// The smoothed pair interaction (core/smoothed_potential.hpp) as the SMD pair loop evaluates it,
// from the squared separation r² (Å²) that the loop already has for its cutoff test. The general
// kernel calls the bare potential's evaluate() and smoothed() (core/smoothed_cutoff.hpp), with the
// square root only in the switch. Plain Lennard-Jones has a cheaper exact
// form with one division per pair and a square root only between r_l and r_u:
//     s6 = (σ²/r²)³,   U = 4ε(s6² - s6),   F_ij = 24ε(2 s6² - s6)/r² · r_ij,
// the formulas of core/lj_potential.hpp rearranged (test_pair_kernels.cpp checks that both agree
// to round-off), with the switch g(r) and the -U g'(r) r̂ term of smoothed().
// Units: Å, kJ/mol, kJ/mol/Å.
#include "core/lj_mixture.hpp"
#include "core/lj_potential.hpp"
#include "core/smoothed_potential.hpp"
#include <cmath>

namespace terrace::smd {

/// General kernel: any smoothed PairPotential, within r_u.
template <class S> struct PairKernel {
    static constexpr bool evaluatesBeyondCutoff = false; // the loop skips pairs beyond r_u

    static PairForce evaluate(const S& potential, const Vec3& rij, double r2,
                              const typename S::Orientation& si,
                              const typename S::Orientation& sj) {
        const PairForce f = potential.bare.evaluate(rij, si, sj);
        const SmoothedCutoff& cut = potential.cut;
        return r2 <= cut.inner() * cut.inner() ? f : smoothed(f, rij, std::sqrt(r2), cut);
    }
};

/// A central force without torques: all a sphere pair needs, and cheaper to build in the pair
/// loop than a PairForce with its zeroed torques.
struct CentralForce {
    double U;
    Vec3 F;
};

/// Lennard-Jones spheres: energy and force from r² directly; the square root only in the switch.
template <> struct PairKernel<Smoothed<LJPotential>> {
    static constexpr bool evaluatesBeyondCutoff = false;

    static CentralForce evaluate(const Smoothed<LJPotential>& model, const Vec3& rij, double r2,
                                 const Vec3&, const Vec3&) {
        const LJPotential& lj = model.bare;
        const SmoothedCutoff& cut = model.cut;
        const double inv2 = 1.0 / r2;
        const double s2 = lj.sigma * lj.sigma * inv2;
        const double s6 = s2 * s2 * s2;
        double u = 4.0 * lj.epsilon * s6 * (s6 - 1.0);
        double forceOverR = 24.0 * lj.epsilon * s6 * (2.0 * s6 - 1.0) * inv2;
        // A branch, not a clamped t in [0, 1] for every pair: the faster of the two in the scalar
        // pair loop (docs/PERFORMANCE.md).
        if (r2 > cut.inner() * cut.inner()) { // in the switch: g U, g F - U g' r̂
            const double r = std::sqrt(r2), g = cut.switching(r);
            forceOverR = g * forceOverR - u * cut.switchingSlope(r) * (r * inv2);
            u *= g;
        }
        return {u, forceOverR * rij};
    }
};

/// A Lennard-Jones mixture: the same form, with the pair's ε, σ and switch picked by the two
/// species. The caller's range test is the envelope's (Smoothed::range): a pair beyond its own r_u
/// but inside the envelope gets g = g' = 0 here.
template <> struct PairKernel<Smoothed<LJMixture>> {
    static constexpr bool evaluatesBeyondCutoff = false;

    static CentralForce evaluate(const Smoothed<LJMixture>& model, const Vec3& rij, double r2,
                                 int a, int b) {
        const LJMixture& lj = model.bare;
        const SmoothedCutoff& cut = model.cutOfPair(a, b);
        const double epsilon = lj.pairEpsilon(a, b), sigma = lj.pairSigma(a, b);
        const double inv2 = 1.0 / r2;
        const double s2 = sigma * sigma * inv2;
        const double s6 = s2 * s2 * s2;
        double u = 4.0 * epsilon * s6 * (s6 - 1.0);
        double forceOverR = 24.0 * epsilon * s6 * (2.0 * s6 - 1.0) * inv2;
        if (r2 > cut.inner() * cut.inner()) {
            const double r = std::sqrt(r2), g = cut.switching(r);
            forceOverR = g * forceOverR - u * cut.switchingSlope(r) * (r * inv2);
            u *= g;
        }
        return {u, forceOverR * rij};
    }
};

} // namespace terrace::smd
