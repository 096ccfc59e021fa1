#pragma once
// Collision rule for terraced potentials (paper sec. 4, eq. 22; DESIGN.md "Collision rule").
//
// At the event time the pair receives impulses along the continuous force and torques,
//     p_i += S F,  p_j −= S F,  L_i += S τ_i,  L_j += S τ_j     (F = F_ij, τ_i = τ_ij, τ_j = τ_ji),
// which conserve linear and angular momentum for any S. Energy fixes S:
//     a S² + b S + ΔE = 0,
//     a = F·F (1/m_i + 1/m_j)/2 + τ_i·I_i⁻¹τ_i/2 + τ_j·I_j⁻¹τ_j/2,
//     b = v_ij·F + τ_i·ω_i + τ_j·ω_j = −dU/dt,
// with ΔE the change of terraced energy. Along the impulse, dU/dt becomes −(b + 2aS).
//   Down (the lower level, ΔE < 0): always possible; S = (−b + √(b² − 4aΔE))/2a, the root nearest
//       zero when the pair is descending (b > 0); afterwards dU/dt = −√(b² − 4aΔE) < 0.
//   Up (the upper level, ΔE > 0) when b² ≥ 4aΔE: S = (−b − √(b² − 4aΔE))/2a, the root nearest
//       zero for a climbing pair (b < 0); afterwards dU/dt = +√(b² − 4aΔE) > 0.
//   Reflect otherwise: S = −b/a (ΔE = 0), dU/dt changes sign, terrace unchanged.
// Terraces that do not rise with U (a step table) take the same roots by the side of the level
// instead of the sign of ΔE (solveCrossing).
// The roots are evaluated in the cancellation-free form S = −2ΔE/(b ± √D).
// Units: kJ/mol, g/mol, Å, time unit 100 fs; S in time units.
#include "core/body_kind.hpp"
#include "core/pair_potential.hpp"
#include <cmath>

namespace terrace::dmd {

enum class Outcome { Up, Down, Reflect };

struct ImpulseCoefficients {
    double a = 0.0; // kJ/mol per (time unit)²: the kinetic energy quadratic in S
    double b = 0.0; // = −dU/dt, kJ/mol per time unit
};

struct Impulse {
    Outcome outcome = Outcome::Reflect;
    double S = 0.0;
    double dE = 0.0; // change of terraced energy actually made (0 for a reflection)
};

template <BodyKind K>
ImpulseCoefficients impulseCoefficients(const PairForce& f, const typename K::State& bi,
                                        const typename K::State& bj, const BodyParams& p) {
    ImpulseCoefficients c;
    double inverseMasses = 2.0 / p.mass; // 1/m_i + 1/m_j
    if constexpr (MassPerBody<K>) inverseMasses = 1.0 / K::mass(bi, p) + 1.0 / K::mass(bj, p);
    c.a = 0.5 * f.F.squaredNorm() * inverseMasses + 0.5 * K::inverseInertia(bi, p, f.tauI, f.tauI) +
          0.5 * K::inverseInertia(bj, p, f.tauJ, f.tauJ);
    c.b = (bi.v - bj.v).dot(f.F) + f.tauI.dot(K::angularVelocity(bi, p)) +
          f.tauJ.dot(K::angularVelocity(bj, p));
    return c;
}

/// S for a pair reaching the upper level of its terrace (upward) or the lower one, where the
/// crossing would change the terraced energy by dE. Terraces of a continuous U rise with U, so
/// there dE > 0 upward and < 0 downward; a step table's do not (core/step_potential.hpp: leaving
/// a square well outwards is a descent of its carrier that costs the well's depth), so both signs
/// are taken either way. The pair crosses when the energy allows it, D = b² − 4a·dE ≥ 0, and it
/// is moving towards the level (b < 0 upward, b > 0 downward) or gains energy; S is then the root
/// that leaves it moving on through the level, dU/dt = ±√D. Otherwise it reflects, S = −b/a,
/// or with S = 0 when it is not moving towards the level at all (round-off at a grazing touch).
/// A hard core is a climb of dE = +∞: never afforded, always a reflection.
inline Impulse solveCrossing(const ImpulseCoefficients& c, double dE, bool upward) {
    const double a = c.a, b = c.b;
    const double towards = upward ? -b : b; // > 0: approaching the level
    const double D = b * b - 4.0 * a * dE;
    if (D >= 0.0 && (dE < 0.0 || towards > 0.0)) {
        const double root = std::sqrt(D);
        // The cancellation-free form where b and the root's term have the same sign.
        if (upward)
            return {Outcome::Up, b < 0.0 ? -2.0 * dE / (b - root) : (-b - root) / (2.0 * a), dE};
        return {Outcome::Down, b > 0.0 ? -2.0 * dE / (b + root) : (root - b) / (2.0 * a), dE};
    }
    if (towards > 0.0 && a > 0.0) return {Outcome::Reflect, -b / a, 0.0};
    return {Outcome::Reflect, 0.0, 0.0};
}

/// solveCrossing for terraces that rise with U: dE < 0 is the lower level, dE ≥ 0 the upper one.
inline Impulse solveImpulse(const ImpulseCoefficients& c, double dE) {
    return solveCrossing(c, dE, dE >= 0.0);
}

/// Apply the impulse S along (F, τ_i, τ_j) to both bodies; momenta are conserved exactly.
template <BodyKind K>
void applyImpulse(typename K::State& bi, typename K::State& bj, const PairForce& f, double S,
                  const BodyParams& p) {
    if constexpr (MassPerBody<K>) {
        bi.v += (S / K::mass(bi, p)) * f.F;
        bj.v -= (S / K::mass(bj, p)) * f.F;
    } else {
        const Vec3 dv = (S / p.mass) * f.F;
        bi.v += dv;
        bj.v -= dv;
    }
    K::addAngularMomentum(bi, p, S * f.tauI);
    K::addAngularMomentum(bj, p, S * f.tauJ);
}

} // namespace terrace::dmd
