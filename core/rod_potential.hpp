#pragma once
// The paper's rod potential ("Model System", eq. 24 ff.), r = |r_ij|, c = s_i·s_j:
//     r_e = r + ζ(1/2 - c²),   U = 4ε[(σ/r_e)^12 - (σ/r_e)^6]
//     F_ij = -U'(r_e) r̂_ij,    τ_ij = 2ζ c U'(r_e) (s_i × s_j),   τ_ji = -τ_ij
// Units: ε kJ/mol, σ and ζ Å. r_e runs from r + ζ/2 (perpendicular rods) to r - ζ/2 (parallel):
// at close contact, on the repulsive wall, perpendicular neighbours have the lower energy (the
// paper's remark); in the attractive tail parallel ones do.
#include "core/pair_potential.hpp"
#include <algorithm>
#include <cmath>

namespace terrace {

struct RodPotential {
    static constexpr std::string_view name = "rod-lj";
    static constexpr AttitudeUse attitude = AttitudeUse::Axis;
    using Orientation = Vec3;

    double epsilon = 3.0; // kJ/mol
    double sigma = 3.035; // Å
    double zeta = 1.0;    // Å

    // Same parameters, same pair energies: terrace designs are remembered by it
    // (dmd/terrace_design.hpp, rememberedDesign).
    bool operator==(const RodPotential&) const = default;

    double effectiveDistance(double r, double c) const { return r + zeta * (0.5 - c * c); }
    /// How far r_e moves as c² runs from 0 to 1 (r_e = r + ζ/2 − ζc²), Å.
    double alignmentLength() const { return zeta; }
    /// The effective distances at which U = u: on the repulsive wall and in the attractive tail.
    detail::RadialRoots radialRoots(double u) const {
        return detail::lennardJonesRoots(u, epsilon, sigma);
    }

    PairForce evaluate(const Vec3& rij, const Vec3& si, const Vec3& sj) const {
        const double r = rij.norm();
        const double c = si.dot(sj);
        const auto lj = detail::lennardJones(effectiveDistance(r, c), epsilon, sigma);
        PairForce f;
        f.U = lj.U;
        f.F = (-lj.dUdx / r) * rij;
        f.tauI = (2.0 * zeta * c * lj.dUdx) * si.cross(sj);
        f.tauJ = -f.tauI;
        return f;
    }
    /// U and dU/dt along free motion by the chain rule through r_e:
    ///     dU/dt = U'(r_e) [ r̂_ij·v_ij − 2ζc (ω_i − ω_j)·(s_i × s_j) ],
    /// since ṙ = r̂·v_ij and ċ = (ω_i × s_i)·s_j + s_i·(ω_j × s_j) = (ω_i − ω_j)·(s_i × s_j);
    /// the same value as eq. (13) with evaluate()'s force and torques, at about half the cost.
    EnergyRate energyRate(const Vec3& rij, const Vec3& vij, const Vec3& si, const Vec3& wi,
                          const Vec3& sj, const Vec3& wj) const {
        const double r = rij.norm();
        const double c = si.dot(sj);
        const auto lj = detail::lennardJones(effectiveDistance(r, c), epsilon, sigma);
        const double cDot = (wi - wj).dot(si.cross(sj));
        return {lj.U, lj.dUdx * (rij.dot(vij) / r - 2.0 * zeta * c * cDot)};
    }
    double energy(const Vec3& rij, const Vec3& si, const Vec3& sj) const {
        const double c = si.dot(sj);
        return detail::lennardJones(effectiveDistance(rij.norm(), c), epsilon, sigma).U;
    }
    double minimumEnergy() const { return -epsilon; }
    /// The lowest U over all alignments at centre distance r: r_e runs over [r − ζ/2, r + ζ/2], and
    /// the LJ curve of r_e is lowest at its minimum 2^(1/6)σ, else at the end nearer to it.
    double lowestEnergyAt(double r) const {
        const double bottom = sigma * std::pow(2.0, 1.0 / 6.0);
        const double x = std::clamp(bottom, r - 0.5 * zeta, r + 0.5 * zeta);
        return detail::lennardJones(x, epsilon, sigma).U;
    }
    /// r_e ≥ r - ζ/2, so U can equal u only while r ≤ x(u) + ζ/2 (paper's r_m formula).
    double reachDistance(double u) const {
        const double x = detail::lennardJonesRoot(u, epsilon, sigma);
        return x > 0.0 ? x + 0.5 * zeta : 0.0;
    }
};

} // namespace terrace
