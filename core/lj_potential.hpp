#pragma once
// Plain Lennard-Jones between spheres: U = 4ε[(σ/r)^12 - (σ/r)^6], no torques.
#include "core/pair_potential.hpp"

namespace terrace {

struct LJPotential {
    static constexpr std::string_view name = "lj";
    static constexpr AttitudeUse attitude = AttitudeUse::None;
    using Orientation = Vec3;

    double epsilon = 1.0; // kJ/mol
    double sigma = 1.0;   // Å

    // Same parameters, same pair energies: terrace designs are remembered by it
    // (dmd/terrace_design.hpp, rememberedDesign).
    bool operator==(const LJPotential&) const = default;

    /// U depends on the centre distance alone: r_e = r, whatever the axes.
    double effectiveDistance(double r, double) const { return r; }
    double alignmentLength() const { return 0.0; }
    detail::RadialRoots radialRoots(double u) const {
        return detail::lennardJonesRoots(u, epsilon, sigma);
    }

    PairForce evaluate(const Vec3& rij, const Vec3&, const Vec3&) const {
        const double r = rij.norm();
        const auto lj = detail::lennardJones(r, epsilon, sigma);
        PairForce f;
        f.U = lj.U;
        f.F = (-lj.dUdx / r) * rij;
        return f;
    }
    /// U and dU/dt = U'(r) r̂_ij·v_ij (no orientations).
    EnergyRate energyRate(const Vec3& rij, const Vec3& vij, const Vec3&, const Vec3&, const Vec3&,
                          const Vec3&) const {
        const double r = rij.norm();
        const auto lj = detail::lennardJones(r, epsilon, sigma);
        return {lj.U, lj.dUdx * rij.dot(vij) / r};
    }
    double energy(const Vec3& rij, const Vec3&, const Vec3&) const {
        return detail::lennardJones(rij.norm(), epsilon, sigma).U;
    }
    double minimumEnergy() const { return -epsilon; }
    /// U at centre distance r (no orientations to range over).
    double lowestEnergyAt(double r) const { return detail::lennardJones(r, epsilon, sigma).U; }
    double reachDistance(double u) const { return detail::lennardJonesRoot(u, epsilon, sigma); }
};

} // namespace terrace
