#pragma once
// Rods among spheres: the paper's rod potential (core/rod_potential.hpp) for every pair of a
// mixture whose species are rods (linear rotors) or spheres. A pair of species a, b takes
//     r_e = r + ζ_ab(1/2 − c²),   U = 4ε_ab[(σ_ab/r_e)^12 − (σ_ab/r_e)^6],   c = s_i·s_j,
// with ζ_ab = ζ where both are rods and ζ_ab = 0 otherwise: a sphere meets a rod, or another
// sphere, through Lennard-Jones on the centre distance, and its axis is never read (with ζ = 0 the
// torque 2ζcU'(s_i × s_j) is exactly zero, so neither body of such a pair turns). A rod's solvent
// shell is thereby round: the anisotropy lives in the rod–rod pairs alone, as in the paper's
// model. The pairs' ε_ab, σ_ab are set by the scene: Lorentz–Berthelot from the species' own
// unless a pair is given (as for core/lj_mixture.hpp). Units: kJ/mol, Å.
#include "core/body_kind.hpp"
#include "core/pair_potential.hpp"
#include "core/rod_potential.hpp"
#include "core/species_pairs.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace terrace {

struct RodMixture {
    static constexpr std::string_view name = "rod-lj";
    static constexpr AttitudeUse attitude = AttitudeUse::SpeciesAxis;
    using Orientation = SpeciesAxis;
    static constexpr int maxSpecies = terrace::maxSpecies;
    static constexpr double minimumOverSigma = 1.122462048309373; // 2^(1/6): where LJ is least

    int species = 1;
    std::array<bool, maxSpecies> rod{}; // species a's bodies are rods; the others are spheres
    SpeciesPairTable<RodPotential> pair;

    /// Sets the pair (a, b) and its mirror: ε (kJ/mol), σ (Å), and the rods' ζ (Å), which the
    /// pair feels only where both species are rods. Set `rod` first.
    void setPair(int a, int b, double eps, double sig, double zeta) {
        pair.set(a, b, RodPotential{eps, sig, rod[a] && rod[b] ? zeta : 0.0});
    }
    const RodPotential& of(const SpeciesAxis& i, const SpeciesAxis& j) const {
        return pair(i.species, j.species);
    }

    PairForce evaluate(const Vec3& rij, const SpeciesAxis& i, const SpeciesAxis& j) const {
        return of(i, j).evaluate(rij, i.axis, j.axis);
    }
    EnergyRate energyRate(const Vec3& rij, const Vec3& vij, const SpeciesAxis& i, const Vec3& wi,
                          const SpeciesAxis& j, const Vec3& wj) const {
        return of(i, j).energyRate(rij, vij, i.axis, wi, j.axis, wj);
    }
    double energy(const Vec3& rij, const SpeciesAxis& i, const SpeciesAxis& j) const {
        return of(i, j).energy(rij, i.axis, j.axis);
    }

    /// U over every configuration whose centre distance lies within `shift` of |rij| and whose
    /// axes are turned by at most turnI, turnJ (rad): the angle between the axes then moves by
    /// at most turnI + turnJ, which bounds c² and so r_e; the LJ curve of r_e falls to its
    /// minimum at 2^(1/6)σ and rises after it, so it is least at the point of the r_e interval
    /// nearest that minimum and greatest at one of the interval's ends.
    EnergyRange energyRange(const Vec3& rij, const SpeciesAxis& i, const SpeciesAxis& j,
                            double shift, double turnI, double turnJ) const {
        const RodPotential& p = of(i, j);
        const double r = rij.norm();
        double c2Lo = 0.0, c2Hi = 1.0;
        if (p.zeta != 0.0) {
            const double angle = std::acos(std::clamp(i.axis.dot(j.axis), -1.0, 1.0));
            const double turn = turnI + turnJ;
            const double lo = std::max(0.0, angle - turn);
            const double hi = std::min(std::numbers::pi, angle + turn);
            const double c2a = std::cos(lo) * std::cos(lo), c2b = std::cos(hi) * std::cos(hi);
            c2Hi = (lo == 0.0 || hi == std::numbers::pi) ? 1.0 : std::max(c2a, c2b);
            c2Lo = (lo <= 0.5 * std::numbers::pi && hi >= 0.5 * std::numbers::pi)
                       ? 0.0
                       : std::min(c2a, c2b);
        }
        const double xLo = std::max(0.0, r - shift) + p.zeta * (0.5 - c2Hi);
        const double xHi = r + shift + p.zeta * (0.5 - c2Lo);
        const auto at = [&](double x) {
            return x > 0.0 ? detail::lennardJones(x, p.epsilon, p.sigma).U
                           : std::numeric_limits<double>::infinity();
        };
        return {at(std::clamp(p.sigma * minimumOverSigma, xLo, xHi)), std::max(at(xLo), at(xHi))};
    }

    /// The deepest well of all pairs.
    double minimumEnergy() const {
        double u = 0.0;
        for (int a = 0; a < species; ++a)
            for (int b = a; b < species; ++b)
                u = std::min(u, pair(a, b).minimumEnergy());
        return u;
    }
    /// The lowest U of any pair, over all alignments, at centre distance r.
    double lowestEnergyAt(double r) const {
        double u = std::numeric_limits<double>::infinity();
        for (int a = 0; a < species; ++a)
            for (int b = a; b < species; ++b)
                u = std::min(u, pair(a, b).lowestEnergyAt(r));
        return u;
    }
    /// The farthest centre distance at which any pair's U equals u.
    double reachDistance(double u) const {
        double r = 0.0;
        for (int a = 0; a < species; ++a)
            for (int b = a; b < species; ++b)
                r = std::max(r, pair(a, b).reachDistance(u));
        return r;
    }
};

} // namespace terrace
