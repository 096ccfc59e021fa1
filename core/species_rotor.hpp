#pragma once
// A body of a mixture of rods and spheres (core/rod_mixture.hpp): a linear rotor (the paper's rod)
// whose species gives its mass and its moment of inertia (BodyParams::speciesMass,
// speciesInertia). A species of inertia 0 is a sphere: it has no rotational degrees of freedom
// (ω = 0 always, its axis never turns and never matters), an impulse's torque on it is dropped
// (infinite inertia, inverseInertia = 0) and the bath gives it no spin. RodMixture gives such a
// body no torque, so dropping one loses nothing. The species of a body never changes.
//
// Why one kind and not a rotor and a sphere side by side: both engines are compiled for one body
// kind (core/body_kind.hpp), and a pair loop that asked each pair which kinds it joins would be a
// branch or a virtual call per pair. A sphere here costs a rotor's 128-B state and a sincos of
// angle 0 per search sample; it buys the mixture without a second engine.
#include "core/body_kind.hpp"
#include "core/linear_rotor.hpp"
#include <cstdint>

namespace terrace {

struct SpeciesRotor {
    static constexpr std::string_view name = "linear-species";
    /// The most a body has (a rod's); a sphere's bodies have none (rotationalDofOf).
    static constexpr int rotationalDof = 2;

    struct alignas(32) State : LinearRotor::State {
        std::int32_t species = 0; // index into Scene::species
    };

    /// I of the body's species, g/mol Å²: 0 for a sphere.
    static double inertia(const State& b, const BodyParams& p) {
        return p.speciesInertia[b.species];
    }
    static double mass(const State& b, const BodyParams& p) { return p.speciesMass[b.species]; }
    static int rotationalDofOf(const State& b, const BodyParams& p) {
        return inertia(b, p) > 0.0 ? 2 : 0;
    }

    // The rotor's motion as LinearRotor's (a sphere's ω = 0 leaves its axis where it is).
    static void freeRotate(State& b, const BodyParams& p, double t) {
        LinearRotor::freeRotate(b, p, t);
    }
    static Vec3 axis(const State& b) { return b.s; }
    static Vec3 angularVelocity(const State& b, const BodyParams&) { return b.w; }
    static Vec3 angularMomentum(const State& b, const BodyParams& p) { return inertia(b, p) * b.w; }
    static double rotationalKinetic(const State& b, const BodyParams& p) {
        return 0.5 * inertia(b, p) * b.w.squaredNorm();
    }
    static double inverseInertia(const State& b, const BodyParams& p, const Vec3& a,
                                 const Vec3& c) {
        const double I = inertia(b, p);
        if (I == 0.0) return 0.0;
        return (a - a.dot(b.s) * b.s).dot(c - c.dot(b.s) * b.s) / I;
    }
    static void addAngularMomentum(State& b, const BodyParams& p, const Vec3& dL) {
        const double I = inertia(b, p);
        if (I == 0.0) return;
        b.w += (dL - dL.dot(b.s) * b.s) / I;
        b.w -= b.w.dot(b.s) * b.s; // keep ω ⟂ s against round-off
    }
    static void scaleAngularVelocity(State& b, const BodyParams&, double f) { b.w *= f; }
};

/// A kind whose bodies are linear rotors (ω ⟂ s, constant in free flight): the paper's rods, alone
/// or with spheres of a mixture. The DMD engine's rotor paths (a rotor's orbit turned in place,
/// its |ω| kept) serve both.
template <class K>
inline constexpr bool isLinearRotorKind =
    std::is_same_v<K, LinearRotor> || std::is_same_v<K, SpeciesRotor>;

} // namespace terrace
