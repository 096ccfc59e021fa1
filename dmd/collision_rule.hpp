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
    c.a = 0.5 * f.F.squaredNorm() * (2.0 / p.mass) +
          0.5 * K::inverseInertia(bi, p, f.tauI, f.tauI) +
          0.5 * K::inverseInertia(bj, p, f.tauJ, f.tauJ);
    c.b = (bi.v - bj.v).dot(f.F) + f.tauI.dot(K::angularVelocity(bi, p)) +
          f.tauJ.dot(K::angularVelocity(bj, p));
    return c;
}

/// S for a pair reaching a level that would change the terraced energy by dE (< 0: the lower
/// level, > 0: the upper level). A climb with b ≥ 0 (the pair is not moving outwards, which only
/// round-off at a grazing touch produces) is a reflection with S = 0: nothing to reverse.
inline Impulse solveImpulse(const ImpulseCoefficients& c, double dE) {
    const double a = c.a, b = c.b;
    if (dE < 0.0) {
        const double root = std::sqrt(b * b - 4.0 * a * dE);
        const double S = b > 0.0 ? -2.0 * dE / (b + root) : (root - b) / (2.0 * a);
        return {Outcome::Down, S, dE};
    }
    const double D = b * b - 4.0 * a * dE;
    if (b < 0.0 && D >= 0.0) return {Outcome::Up, -2.0 * dE / (b - std::sqrt(D)), dE};
    if (b < 0.0 && a > 0.0) return {Outcome::Reflect, -b / a, 0.0};
    return {Outcome::Reflect, 0.0, 0.0};
}

/// Apply the impulse S along (F, τ_i, τ_j) to both bodies; momenta are conserved exactly.
template <BodyKind K>
void applyImpulse(typename K::State& bi, typename K::State& bj, const PairForce& f, double S,
                  const BodyParams& p) {
    const Vec3 dv = (S / p.mass) * f.F;
    bi.v += dv;
    bj.v -= dv;
    K::addAngularMomentum(bi, p, S * f.tauI);
    K::addAngularMomentum(bj, p, S * f.tauJ);
}

} // namespace terrace::dmd
