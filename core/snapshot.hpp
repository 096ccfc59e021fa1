#pragma once
// An immutable picture of all bodies at one instant, the only thing analysis and trajectory
// output see. Both engines produce the same Snapshot, so g(r) and the correlation functions
// cannot treat DMD and SMD differently.
#include "core/system.hpp"
#include <cstdint>
#include <vector>

namespace terrace {

struct Snapshot {
    double time = 0.0;                 // internal time units (100 fs)
    double boxLength = 0.0;            // Å
    std::vector<Vec3> position;        // unwrapped centres of mass, Å
    std::vector<Vec3> velocity;        // Å per time unit
    std::vector<Vec3> axis;            // unit long axes (body axis 3)
    std::vector<Vec3> omega;           // lab angular velocities, rad per time unit
    std::vector<Quat> orientation;     // body -> lab rotation; filled for tops only
    std::vector<std::int32_t> species; // index into Scene::species; filled for mixtures only

    int size() const { return static_cast<int>(position.size()); }
};

/// An empty snapshot at time t with room for n bodies of kind K.
template <BodyKind K> Snapshot emptySnapshot(double t, double boxLength, std::size_t n) {
    constexpr bool withOrientation = requires(const typename K::State& b) {
        b.A;
    };
    Snapshot s;
    s.time = t;
    s.boxLength = boxLength;
    s.position.reserve(n);
    s.velocity.reserve(n);
    s.axis.reserve(n);
    s.omega.reserve(n);
    if (withOrientation) s.orientation.reserve(n);
    if constexpr (requires(const typename K::State& b) { b.species; }) s.species.reserve(n);
    return s;
}

/// Appends body b (params: the body's mass and inertia) to s.
template <BodyKind K>
void appendBody(Snapshot& s, const typename K::State& b, const BodyParams& params) {
    s.position.push_back(b.r);
    s.velocity.push_back(b.v);
    s.axis.push_back(K::axis(b));
    s.omega.push_back(K::angularVelocity(b, params));
    if constexpr (requires { b.A; }) s.orientation.emplace_back(Mat3(b.A.transpose()));
    if constexpr (requires { b.species; }) s.species.push_back(b.species);
}

/// Only the positions of every body (the other fields empty): what a g(r) frame needs.
inline Snapshot positionsOnly(double t, double boxLength, std::size_t n) {
    Snapshot s;
    s.time = t;
    s.boxLength = boxLength;
    s.position.reserve(n);
    return s;
}

template <BodyKind K, PairPotential P> Snapshot makeSnapshot(const System<K, P>& sys, double t) {
    Snapshot s = emptySnapshot<K>(t, sys.box.length, sys.bodies.size());
    for (const auto& b : sys.bodies)
        appendBody<K>(s, b, sys.body);
    return s;
}

} // namespace terrace
