#pragma once
// What a pair potential gives the engines (paper eqs. 4-5 and 13): the energy U, the force on i,
// the torques on i and j, and -- from those and the velocities -- the rate dU/dt along free motion.
// Potentials are compile-time types; both engines are templates over them.
//
// A potential sees each body through its Orientation, the part of the attitude it reads, declared
// at compile time (AttitudeUse): nothing (spheres), the unit symmetry axis (the paper's rods,
// Gay–Berne ellipsoids, linear molecules), or the whole body frame (a molecule with sites off its
// axis). An axis potential is handed the lab axis and pays for nothing more; a frame potential is
// handed the rotation body -> lab (core/body_orientation.hpp builds either from a body's state).
#include "core/vec.hpp"
#include <cmath>
#include <concepts>
#include <limits>
#include <string_view>
#include <type_traits>

namespace terrace {

/// How much of a body's attitude a potential reads.
enum class AttitudeUse {
    None,  // central forces: the attitude is never read
    Axis,  // the unit symmetry axis s (lab frame)
    Frame, // the rotation Q = Aᵀ, body -> lab: its columns are the body's principal axes
    // central forces between spheres of several species (core/lj_mixture.hpp): the body's
    // species index, which picks the pair's parameters; no attitude, no torque
    Species,
    // bodies of several species, some of them rods (core/rod_mixture.hpp): the unit axis s with
    // the species index (SpeciesAxis), which picks the pair's parameters
    SpeciesAxis,
};

/// The orientation of a body of a mixture with rods in it (AttitudeUse::SpeciesAxis): its unit
/// long axis (lab frame; a sphere's is never read) and its species.
struct SpeciesAxis {
    Vec3 axis = Vec3::UnitZ();
    int species = 0;
};

/// What a potential with the given use is handed of each body.
template <AttitudeUse use>
using OrientationFor = std::conditional_t<
    use == AttitudeUse::Frame, Mat3,
    std::conditional_t<use == AttitudeUse::Species, int,
                       std::conditional_t<use == AttitudeUse::SpeciesAxis, SpeciesAxis, Vec3>>>;

/// Everything a pair evaluation returns (kJ/mol, kJ/mol/Å, kJ/mol per radian).
struct PairForce {
    double U = 0.0;
    Vec3 F = Vec3::Zero();    // force on i due to j; the force on j is -F
    Vec3 tauI = Vec3::Zero(); // torque on i due to j
    Vec3 tauJ = Vec3::Zero(); // torque on j due to i
};

template <class P>
concept PairPotential = requires(const P p, Vec3 r, typename P::Orientation o, double u) {
    { P::name } -> std::convertible_to<std::string_view>;
    { P::attitude } -> std::convertible_to<AttitudeUse>;
    requires std::same_as<typename P::Orientation, OrientationFor<P::attitude>>;
    // rij = ri - rj (minimum image), oi, oj the bodies' orientations (ignored under None)
    { p.evaluate(r, o, o) } -> std::same_as<PairForce>;
    { p.energy(r, o, o) } -> std::convertible_to<double>;
    // lowest value U can take over all configurations (a level there makes a zero-width terrace)
    { p.minimumEnergy() } -> std::convertible_to<double>;
    // largest centre distance at which U can equal u (0 if U never reaches u)
    { p.reachDistance(u) } -> std::convertible_to<double>;
};

/// Bounds of U over a set of configurations, kJ/mol (hi may be +∞).
struct EnergyRange {
    double lo = 0.0, hi = 0.0;
};

/// A potential that bounds its own values near a configuration: energyRange(rij, oi, oj, shift,
/// turnI, turnJ) holds U over every configuration whose centre separation differs from rij by at
/// most `shift` (Å) and whose bodies are turned by at most turnI, turnJ (rad) from oi, oj. The
/// DMD engine's hold screen for potentials without an effective-distance form
/// (dmd/pair_prediction.hpp).
template <class P>
concept RangeBounded = requires(const P p, Vec3 r, typename P::Orientation o, double x) {
    { p.energyRange(r, o, o, x, x, x) } -> std::same_as<EnergyRange>;
};

/// Whether P reads the attitude at all (torques, rotation in the search).
template <class P>
inline constexpr bool isOrientational =
    P::attitude == AttitudeUse::Axis || P::attitude == AttitudeUse::Frame ||
    P::attitude == AttitudeUse::SpeciesAxis;

/// Whether P is handed anything of each body (an attitude, or a species): whether the engines
/// keep each body's Orientation beside its position.
template <class P> inline constexpr bool readsBodies = P::attitude != AttitudeUse::None;

/// dU/dt along free motion, paper eq. (13): -F_ij·v_ij - τ_ij·ω_i - τ_ji·ω_j, with v_ij = v_i -
/// v_j.
inline double dUdt(const PairForce& f, const Vec3& vij, const Vec3& wi, const Vec3& wj) {
    return -f.F.dot(vij) - f.tauI.dot(wi) - f.tauJ.dot(wj);
}

/// U and dU/dt together: all that the DMD search asks of a pair at each of its samples.
struct EnergyRate {
    double U = 0.0;    // kJ/mol
    double dUdt = 0.0; // kJ/mol per time unit of the velocities
};

/// U and dU/dt (paper eq. 13) of the pair (rij, si, sj) moving with v_ij = v_i - v_j and angular
/// velocities wi, wj; si, sj the bodies' orientations. A potential may provide energyRate() with
/// the same arguments, which skips the force and torque vectors (a potential's rate is a scalar
/// chain rule); otherwise the rate comes from evaluate() and dUdt().
template <PairPotential P>
EnergyRate energyAndRate(const P& p, const Vec3& rij, const Vec3& vij,
                         const typename P::Orientation& si, const Vec3& wi,
                         const typename P::Orientation& sj, const Vec3& wj) {
    if constexpr (requires { p.energyRate(rij, vij, si, wi, sj, wj); }) {
        return p.energyRate(rij, vij, si, wi, sj, wj);
    } else {
        const PairForce f = p.evaluate(rij, si, sj);
        return {f.U, dUdt(f, vij, wi, wj)};
    }
}

namespace detail {

struct Radial {
    double U;    // 4ε[(σ/x)^12 - (σ/x)^6]
    double dUdx; // -(24ε/x)[2(σ/x)^12 - (σ/x)^6]
};

inline Radial lennardJones(double x, double epsilon, double sigma) {
    const double inverse = 1.0 / x; // the one division
    const double s = sigma * inverse;
    const double s2 = s * s;
    const double s6 = s2 * s2 * s2;
    const double s12 = s6 * s6;
    return {4.0 * epsilon * (s12 - s6), -24.0 * epsilon * inverse * (2.0 * s12 - s6)};
}

/// Both distances x at which the Lennard-Jones curve equals u: `inner` on the repulsive wall
/// (x ≤ 2^(1/6)σ, for u > −ε), `outer` on the attractive side (for −ε < u < 0; +∞ for u ≥ 0, which
/// the tail never reaches). For u ≤ −ε both are 2^(1/6)σ, the minimum, where the curve only
/// touches u = −ε. Solves 4ε(y² − y) = u for y = (σ/x)^6.
struct RadialRoots {
    double inner, outer;
};
inline RadialRoots lennardJonesRoots(double u, double epsilon, double sigma) {
    const double bottom = sigma * std::pow(2.0, 1.0 / 6.0);
    if (u <= -epsilon) return {bottom, bottom};
    const double disc = std::sqrt(1.0 + u / epsilon);
    const double inner = sigma / std::pow(0.5 * (1.0 + disc), 1.0 / 6.0);
    const double outer = u < 0.0 ? sigma / std::pow(0.5 * (1.0 - disc), 1.0 / 6.0)
                                 : std::numeric_limits<double>::infinity();
    return {inner, outer};
}

/// Distance x at which the Lennard-Jones curve equals u: for -ε < u < 0 the outer (attractive)
/// root, for u >= 0 the root on the repulsive wall; 0 for u <= -ε, where it is never reached.
inline double lennardJonesRoot(double u, double epsilon, double sigma) {
    if (u <= -epsilon) return 0.0;
    const RadialRoots x = lennardJonesRoots(u, epsilon, sigma);
    return u < 0.0 ? x.outer : x.inner;
}

} // namespace detail
} // namespace terrace
