#pragma once
// The contract every body kind fulfils. A body kind is a compile-time parameter of both engines
// (DESIGN.md "Rigid bodies and free motion"): the pair loop never makes a virtual call, and a rod
// scene never touches the asymmetric-top machinery.
//
// Conventions (van Zon & Schofield, J. Comput. Phys. 225, 145 (2007)): the attitude matrix A maps
// lab-frame vectors to the body frame; body-frame quantities carry no suffix in the formulas of the
// top headers. All vectors in a State are in the lab frame unless named otherwise.
#include "core/vec.hpp"
#include <array>
#include <concepts>
#include <string_view>

namespace terrace {

/// The most species a mixture may have (Scene::species).
inline constexpr int maxSpecies = 4;

/// Mass (g/mol) and principal moments of inertia (g/mol Å²) shared by every body of a scene; in a
/// mixture, each species' own mass (and, of rods among spheres, its own moment of inertia), which
/// its kind reads by the body's species (bodyMass).
struct BodyParams {
    double mass = 0.0;
    Vec3 inertia = Vec3::Zero(); // I1, I2, I3 in the body frame; unused entries are ignored
    std::array<double, maxSpecies> speciesMass{}; // g/mol, by species; unused without species
    // g/mol Å², by species: a rod's I, 0 for a sphere (core/species_rotor.hpp); unused elsewhere
    std::array<double, maxSpecies> speciesInertia{};
};

template <class K>
concept BodyKind = requires(typename K::State s, const typename K::State cs, const BodyParams p,
                            double t, Vec3 a) {
    { K::name } -> std::convertible_to<std::string_view>;
    { K::rotationalDof } -> std::convertible_to<int>;
    { cs.r } -> std::convertible_to<Vec3>;        // centre of mass, Å (unwrapped)
    { cs.v } -> std::convertible_to<Vec3>;        // centre-of-mass velocity, Å per time unit
    K::freeRotate(s, p, t);                       // exact torque-free rotation over time t
    { K::axis(cs) } -> std::convertible_to<Vec3>; // unit long (symmetry) axis
    { K::angularVelocity(cs, p) } -> std::convertible_to<Vec3>; // lab ω, rad per time unit
    { K::angularMomentum(cs, p) } -> std::convertible_to<Vec3>; // lab L about the centre
    { K::rotationalKinetic(cs, p) } -> std::convertible_to<double>;
    { K::inverseInertia(cs, p, a, a) } -> std::convertible_to<double>; // a·I⁻¹·b, lab frame
    K::addAngularMomentum(s, p, a);   // L += a (an impulsive or a kick torque)
    K::scaleAngularVelocity(s, p, t); // ω *= factor (thermostat)
};

/// A kind whose bodies have masses of their own (a mixture's species), where every other kind's
/// bodies share the scene's one mass.
template <class K>
concept MassPerBody = requires(const typename K::State s, const BodyParams p) {
    { K::mass(s, p) } -> std::convertible_to<double>;
};

/// A kind whose bodies differ in their rotational degrees of freedom (rods and spheres of one
/// mixture), where every other kind's bodies have K::rotationalDof each.
template <class K>
concept DofPerBody = requires(const typename K::State s, const BodyParams p) {
    { K::rotationalDofOf(s, p) } -> std::convertible_to<int>;
};

/// The rotational degrees of freedom of one body: 0, 2 or 3.
template <BodyKind K> int bodyRotationalDof(const typename K::State& s, const BodyParams& p) {
    if constexpr (DofPerBody<K>)
        return K::rotationalDofOf(s, p);
    else
        return K::rotationalDof;
}

/// The mass of one body, g/mol. Kinds without masses of their own read the scene's, so that their
/// sums keep the operations, and so the round-off, of a scene where mass was one number.
template <BodyKind K> double bodyMass(const typename K::State& s, const BodyParams& p) {
    if constexpr (MassPerBody<K>)
        return K::mass(s, p);
    else
        return p.mass;
}

/// Exact free motion over time t: straight-line translation and the kind's exact rotation.
template <BodyKind K> void freeMove(typename K::State& s, const BodyParams& p, double t) {
    s.r += s.v * t;
    K::freeRotate(s, p, t);
}

template <BodyKind K> double kineticEnergy(const typename K::State& s, const BodyParams& p) {
    return 0.5 * bodyMass<K>(s, p) * s.v.squaredNorm() + K::rotationalKinetic(s, p);
}

/// Rodrigues' rotation matrix: rotates vectors by angle theta (rad) about the unit axis u.
inline Mat3 rotationMatrix(const Vec3& u, double theta) {
    const double c = std::cos(theta), s = std::sin(theta);
    Mat3 cross;
    cross << 0, -u.z(), u.y(), u.z(), 0, -u.x(), -u.y(), u.x(), 0;
    return c * Mat3::Identity() + s * cross + (1.0 - c) * u * u.transpose();
}

} // namespace terrace
