#pragma once
// One step table (core/step_table.hpp) between spheres of several species, as DynamO's mixtures
// of hard spheres and square wells have it: the pair (a, b) takes the table with its radii in its
// own σ_ab and its energies in its own ε_ab. Like species take their own σ and ε, unlike ones
// Lorentz–Berthelot's σ_ab = (σ_a + σ_b)/2 (an additive mixture) and ε_ab = √(ε_a ε_b) unless the
// scene gives the pair's own (a non-additive one), as for the Lennard-Jones mixture
// (core/lj_mixture.hpp).
//
// The carrier of pair (a, b) (core/step_potential.hpp says what a carrier is),
//     φ_ab(r) = ε / (1 + r²/σ_ab²),   with the table's one ε,
// takes at r_k σ_ab the value ε/(1 + r_k²) whatever the pair: every pair crosses the same levels,
// each at its own radii. The terrace between carries E_k ε_ab: the engine's one set of terrace
// energies E_k ε (dmd/terrace_levels.hpp) times the pair's scale ε_ab/ε (pairEnergyScale; the
// DMD engine applies it at each crossing and in its energy sums). Units: Å, kJ/mol.
#include "core/body_kind.hpp"
#include "core/pair_potential.hpp"
#include "core/species_pairs.hpp"
#include "core/step_potential.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace terrace {

struct StepMixture {
    static constexpr std::string_view name = "steps";
    static constexpr AttitudeUse attitude = AttitudeUse::Species;
    using Orientation = int;
    static constexpr int maxSpecies = terrace::maxSpecies;

    StepPotential steps; // the table, ε, and the levels and terrace energies all pairs share
    int species = 1;
    SpeciesPairTable<double> sigma;       // σ_ab, Å
    SpeciesPairTable<double> energyScale; // ε_ab/ε

    double pairSigma(int a, int b) const { return sigma(a, b); }
    /// ε_ab/ε: the factor of the pair's terrace energies over the shared ones.
    double pairEnergyScale(int a, int b) const { return energyScale(a, b); }
    /// Sets the pair (a, b)'s ε (kJ/mol) and σ (Å), and its mirror's.
    void setPair(int a, int b, double eps, double sig) {
        sigma.set(a, b, sig);
        energyScale.set(a, b, eps / steps.epsilon);
    }

    /// φ_ab at squared distance r2 (Å²).
    double carrierSquared(double r2, int a, int b) const {
        const double s = pairSigma(a, b);
        return steps.epsilon / (1.0 + r2 / (s * s));
    }
    /// The table's energy of the pair at centre distance r (Å), kJ/mol (+∞ inside its core).
    double tableEnergy(double r, int a, int b) const {
        return steps.epsilon * pairEnergyScale(a, b) * steps.table.energyAt(r / pairSigma(a, b));
    }

    PairForce evaluate(const Vec3& rij, int a, int b) const {
        const double s2 = pairSigma(a, b) * pairSigma(a, b);
        const double q = 1.0 / (1.0 + rij.squaredNorm() / s2);
        PairForce f;
        f.U = steps.epsilon * q;
        f.F = (2.0 * steps.epsilon * q * q / s2) * rij;
        return f;
    }
    EnergyRate energyRate(const Vec3& rij, const Vec3& vij, int a, const Vec3&, int b,
                          const Vec3&) const {
        const double s2 = pairSigma(a, b) * pairSigma(a, b);
        const double q = 1.0 / (1.0 + rij.squaredNorm() / s2);
        return {steps.epsilon * q, -2.0 * steps.epsilon * q * q / s2 * rij.dot(vij)};
    }
    double energy(const Vec3& rij, int a, int b) const {
        return carrierSquared(rij.squaredNorm(), a, b);
    }

    /// φ_ab over the centre distances [r − shift, r + shift]: it falls with r.
    EnergyRange energyRange(const Vec3& rij, int a, int b, double shift, double, double) const {
        const double r = rij.norm();
        const double lo = std::max(0.0, r - shift), hi = r + shift;
        return {carrierSquared(hi * hi, a, b), carrierSquared(lo * lo, a, b)};
    }

    /// φ's infimum (far pairs): the levels all lie above it.
    double minimumEnergy() const { return 0.0; }
    /// The lowest φ of any pair at centre distance r: the pair of least σ_ab's.
    double lowestEnergyAt(double r) const {
        double u = std::numeric_limits<double>::infinity();
        for (int a = 0; a < species; ++a)
            for (int b = a; b < species; ++b)
                u = std::min(u, carrierSquared(r * r, a, b));
        return u;
    }
    /// The farthest distance at which any pair's φ equals u: σ_ab √(ε/u − 1) of the largest σ_ab
    /// (0 where φ never takes u).
    double reachDistance(double u) const {
        if (!(u > 0.0) || u >= steps.epsilon) return 0.0;
        double s = 0.0;
        for (int a = 0; a < species; ++a)
            for (int b = a; b < species; ++b)
                s = std::max(s, pairSigma(a, b));
        return s * std::sqrt(steps.epsilon / u - 1.0);
    }
};

} // namespace terrace
