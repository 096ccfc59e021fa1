#pragma once
// A step table (core/step_table.hpp) as a pair potential of the DMD engine, which finds events
// where a continuous U crosses a level and exchanges terraced energies there
// (dmd/terrace_levels.hpp, dmd/collision_rule.hpp). The table is carried by a smooth, strictly
// decreasing function of the centre distance alone,
//     φ(r) = ε / (1 + r²/σ²),
// whose value at each step radius r_k is a level and at the hard core the last: φ crosses a level
// exactly when r crosses its radius, so the engine's event search, root refinement and collision
// rule serve the table unchanged. The terrace between two levels carries the table's E_k, the one
// beyond the cutoff 0 and the one inside the core +∞, which no pair can climb into: the core
// always reflects. φ's force is central, F = 2ε/(σ²(1 + r²/σ²)²) r_ij, so every impulse lies on
// the line of centres, and its size is set by energy conservation alone, whatever φ's slope.
// φ is finite at r = 0, so a table without a core lets pairs pass through each other.
//
// φ itself is no energy of the model: the engine's energies are the terraces'. SMD, which would
// integrate φ, refuses the scene (core/scene.cpp). Units: Å, kJ/mol.
#include "core/pair_potential.hpp"
#include "core/step_table.hpp"
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace terrace {

struct StepPotential {
    static constexpr std::string_view name = "steps";
    static constexpr AttitudeUse attitude = AttitudeUse::None;
    using Orientation = Vec3;

    double epsilon = 1.0; // kJ/mol: the table's energy unit and φ's scale
    double sigma = 1.0;   // Å: the table's length unit and φ's
    StepTable table;      // σ, ε

    /// φ at squared distance r2 (Å²).
    double carrierSquared(double r2) const { return epsilon / (1.0 + r2 / (sigma * sigma)); }
    double carrier(double r) const { return carrierSquared(r * r); }

    /// The levels, φ at each step radius and then at the core, increasing (kJ/mol).
    std::vector<double> levels() const {
        std::vector<double> L;
        for (double r : table.radii)
            L.push_back(carrier(r * sigma));
        if (table.hasCore()) L.push_back(carrier(table.hardCore * sigma));
        return L;
    }
    /// The terrace energies, kJ/mol: 0 beyond the cutoff, E_k on step k, +∞ inside the core.
    std::vector<double> values() const {
        std::vector<double> V{0.0};
        for (double e : table.energies)
            V.push_back(e * epsilon);
        if (table.hasCore()) V.push_back(std::numeric_limits<double>::infinity());
        return V;
    }

    /// U depends on the centre distance alone (the hold screen's bands, dmd/terrace_hold.hpp).
    double effectiveDistance(double r, double) const { return r; }
    double alignmentLength() const { return 0.0; }
    /// φ = u at r = σ √(ε/u − 1), on φ's one decreasing side (inner); there is no rising side
    /// (outer = +∞). u ≥ ε: only at r = 0 or never (0); u ≤ 0: never (+∞, φ's infimum).
    detail::RadialRoots radialRoots(double u) const {
        constexpr double inf = std::numeric_limits<double>::infinity();
        if (!(u > 0.0)) return {inf, inf};
        if (u >= epsilon) return {0.0, inf};
        return {sigma * std::sqrt(epsilon / u - 1.0), inf};
    }

    PairForce evaluate(const Vec3& rij, const Vec3&, const Vec3&) const {
        const double q = 1.0 / (1.0 + rij.squaredNorm() / (sigma * sigma));
        PairForce f;
        f.U = epsilon * q;
        f.F = (2.0 * epsilon * q * q / (sigma * sigma)) * rij;
        return f;
    }
    EnergyRate energyRate(const Vec3& rij, const Vec3& vij, const Vec3&, const Vec3&, const Vec3&,
                          const Vec3&) const {
        const double q = 1.0 / (1.0 + rij.squaredNorm() / (sigma * sigma));
        return {epsilon * q, -2.0 * epsilon * q * q / (sigma * sigma) * rij.dot(vij)};
    }
    double energy(const Vec3& rij, const Vec3&, const Vec3&) const {
        return carrierSquared(rij.squaredNorm());
    }
    /// φ's infimum (far pairs): the levels all lie above it.
    double minimumEnergy() const { return 0.0; }
    double lowestEnergyAt(double r) const { return carrier(r); }
    /// The largest r with φ(r) = u: the root on φ's one side, 0 when φ never takes u.
    double reachDistance(double u) const {
        const double r = radialRoots(u).inner;
        return std::isfinite(r) ? r : 0.0;
    }

    /// The table's energy at centre distance r (Å), kJ/mol (+∞ inside the core).
    double tableEnergy(double r) const { return epsilon * table.energyAt(r / sigma); }
};

/// The step potential of P: P itself, the table that a mixture's pairs share
/// (core/step_mixture.hpp), or either as the bare potential of a smoothed model
/// (core/smoothed_potential.hpp); nullptr for any other potential. Its levels and terrace
/// energies are every pair's.
template <class P> auto stepPotentialOf(const P& p) {
    if constexpr (std::is_same_v<P, StepPotential>)
        return &p;
    else if constexpr (requires { p.steps; })
        return stepPotentialOf(p.steps);
    else if constexpr (requires { p.bare; })
        return stepPotentialOf(p.bare);
    else
        return nullptr;
}
/// Whether P is a step table, bare or in a smoothed model.
template <class P>
inline constexpr bool isSteppedModel =
    !std::is_same_v<decltype(stepPotentialOf(std::declval<const P&>())), std::nullptr_t>;

/// The table's energy (kJ/mol) of a pair at centre distance r (Å) in the stepped model P: a
/// mixture's pair at its own σ_ab.
template <class P, class O> double stepPairEnergy(const P& p, double r, const O& oi, const O& oj) {
    if constexpr (requires { p.bare; })
        return stepPairEnergy(p.bare, r, oi, oj);
    else if constexpr (requires { p.tableEnergy(r, oi, oj); })
        return p.tableEnergy(r, oi, oj);
    else
        return p.tableEnergy(r);
}

/// Whether P scales each pair's terrace energies by its own factor (a step mixture's ε_ab/ε,
/// core/step_mixture.hpp), bare or in a smoothed model.
template <class P> inline constexpr bool scalesPairEnergies = requires(const P& p) {
    p.pairEnergyScale(0, 0);
}
|| requires(const P& p) {
    p.bare.pairEnergyScale(0, 0);
};

/// The factor of the pair (si, sj)'s terrace energies over the shared ones: 1 unless P scales
/// each pair's.
template <class P, class O> double pairEnergyScale(const P& p, const O& si, const O& sj) {
    if constexpr (requires { p.pairEnergyScale(si, sj); })
        return p.pairEnergyScale(si, sj);
    else if constexpr (requires { p.bare.pairEnergyScale(si, sj); })
        return p.bare.pairEnergyScale(si, sj);
    else
        return 1.0;
}

/// The energy a start is judged by (core/initial_state.hpp): the table's for a step table, whose
/// carrier φ is no energy, U for any other potential.
template <class P, class O>
double startEnergy(const P& p, const Vec3& rij, const O& oi, const O& oj) {
    if constexpr (isSteppedModel<P>)
        return stepPairEnergy(p, rij.norm(), oi, oj);
    else
        return p.energy(rij, oi, oj);
}

} // namespace terrace
