#pragma once
// Lennard-Jones between spheres of several species: U_ab = 4ε_ab[(σ_ab/r)^12 − (σ_ab/r)^6] for a
// body of species a and one of species b, no torques. The pair's parameters come from the
// species that each body carries (AttitudeUse::Species, core/species_sphere.hpp): like species
// take their own ε and σ, unlike ones Lorentz–Berthelot's (σ_ab = (σ_a + σ_b)/2,
// ε_ab = √(ε_a ε_b)) unless the scene gives the pair's own, as the Kob–Andersen mixture does
// (W. Kob and H. C. Andersen, Phys. Rev. E 51, 4626 (1995)). Units: kJ/mol, Å.
//
// The smoothed cutoff (core/smoothed_potential.hpp) is the scene's one [r_l, r_u] for every pair,
// unless the scene scales it by each pair's σ_ab (potential.cutoff_per_pair), as Kob and Andersen
// cut each pair at 2.5 σ_ab: then the pairs' own switches sit here beside their ε and σ, and the
// smoothed model reads them through cutoffOf.
#include "core/body_kind.hpp"
#include "core/pair_potential.hpp"
#include "core/smoothed_cutoff.hpp"
#include "core/species_pairs.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace terrace {

struct LJMixture {
    static constexpr std::string_view name = "lj";
    static constexpr AttitudeUse attitude = AttitudeUse::Species;
    using Orientation = int;
    static constexpr int maxSpecies = terrace::maxSpecies;
    static constexpr double minimumOverSigma = 1.122462048309373; // 2^(1/6): where U is least

    int species = 1;
    SpeciesPairTable<double> epsilon; // ε_ab, kJ/mol
    SpeciesPairTable<double> sigma;   // σ_ab, Å

    // Each pair's own smoothed cutoff (Å), read only where cutPerPair is set.
    bool cutPerPair = false;
    SpeciesPairTable<SmoothedCutoff> pairCut;

    double pairEpsilon(int a, int b) const { return epsilon(a, b); }
    double pairSigma(int a, int b) const { return sigma(a, b); }
    /// Sets the pair (a, b) and its mirror.
    void setPair(int a, int b, double eps, double sig) {
        epsilon.set(a, b, eps);
        sigma.set(a, b, sig);
    }

    /// Sets the pair (a, b)'s own cutoff and its mirror's, and turns per-pair cutoffs on.
    void setPairCutoff(int a, int b, const SmoothedCutoff& cut) {
        pairCut.set(a, b, cut);
        cutPerPair = true;
    }
    /// The pair's own cutoff (meaningful where cutPerPair is set).
    const SmoothedCutoff& cutoffOf(int a, int b) const { return pairCut(a, b); }

    /// The pair (a, b)'s U at centre distance r, and the distance at which it equals u (the
    /// largest root; 0 where U never reaches u).
    double pairEnergyAt(double r, int a, int b) const {
        return detail::lennardJones(r, pairEpsilon(a, b), pairSigma(a, b)).U;
    }
    double pairReach(double u, int a, int b) const {
        return detail::lennardJonesRoot(u, pairEpsilon(a, b), pairSigma(a, b));
    }

    PairForce evaluate(const Vec3& rij, int a, int b) const {
        const double r = rij.norm();
        const auto lj = detail::lennardJones(r, pairEpsilon(a, b), pairSigma(a, b));
        PairForce f;
        f.U = lj.U;
        f.F = (-lj.dUdx / r) * rij;
        return f;
    }
    EnergyRate energyRate(const Vec3& rij, const Vec3& vij, int a, const Vec3&, int b,
                          const Vec3&) const {
        const double r = rij.norm();
        const auto lj = detail::lennardJones(r, pairEpsilon(a, b), pairSigma(a, b));
        return {lj.U, lj.dUdx * rij.dot(vij) / r};
    }
    double energy(const Vec3& rij, int a, int b) const {
        return detail::lennardJones(rij.norm(), pairEpsilon(a, b), pairSigma(a, b)).U;
    }

    /// U over the centre distances [r − shift, r + shift] (no attitude turns): each LJ curve
    /// falls to its minimum at 2^(1/6)σ_ab and rises after it.
    EnergyRange energyRange(const Vec3& rij, int a, int b, double shift, double, double) const {
        const double eps = pairEpsilon(a, b), sig = pairSigma(a, b);
        const double r = rij.norm();
        const double lo = std::max(0.0, r - shift), hi = r + shift;
        const double bottom = sig * minimumOverSigma;
        const auto at = [&](double x) {
            return x > 0.0 ? detail::lennardJones(x, eps, sig).U
                           : std::numeric_limits<double>::infinity();
        };
        return {at(std::clamp(bottom, lo, hi)), std::max(at(lo), at(hi))};
    }

    /// The deepest well of all pairs.
    double minimumEnergy() const {
        double u = 0.0;
        for (int a = 0; a < species; ++a)
            for (int b = a; b < species; ++b)
                u = std::min(u, -pairEpsilon(a, b));
        return u;
    }
    /// The lowest U of any pair at centre distance r.
    double lowestEnergyAt(double r) const {
        double u = std::numeric_limits<double>::infinity();
        for (int a = 0; a < species; ++a)
            for (int b = a; b < species; ++b)
                u = std::min(u, detail::lennardJones(r, pairEpsilon(a, b), pairSigma(a, b)).U);
        return u;
    }
    /// The farthest distance at which any pair's U equals u.
    double reachDistance(double u) const {
        double r = 0.0;
        for (int a = 0; a < species; ++a)
            for (int b = a; b < species; ++b)
                r = std::max(r, detail::lennardJonesRoot(u, pairEpsilon(a, b), pairSigma(a, b)));
        return r;
    }
};

} // namespace terrace
