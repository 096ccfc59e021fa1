#pragma once
// Linear rotor: the paper's rods. The pair torque is perpendicular to the long axis s, so the spin
// about s is conserved and decoupled ("Model System"); only ω ⟂ s is kept, and the free motion is
//     s(t) = s cos(|ω|t) + (ω̂ × s) sin(|ω|t),   ω constant
// (REFERENCES.md, "Exact free rigid-body motion"). Moment of inertia I = inertia[0] = inertia[1].
#include "core/body_kind.hpp"
#include <cmath>

namespace terrace {

struct LinearRotor {
    static constexpr std::string_view name = "linear";
    static constexpr int rotationalDof = 2;

    // 96 B aligned to 32: every state then covers exactly two cache lines (at the 16-B offset a
    // large heap block starts on, every other state covered three), so a partner costs a line less.
    struct alignas(32) State {
        Vec3 r = Vec3::Zero();
        Vec3 v = Vec3::Zero();
        Vec3 s = Vec3::UnitZ(); // unit long axis
        Vec3 w = Vec3::Zero();  // angular velocity, perpendicular to s
    };

    static void freeRotate(State& b, const BodyParams&, double t) {
        const double speed = b.w.norm();
        if (speed == 0.0) return;
        const double angle = speed * t;
        const Vec3 sNew = b.s * std::cos(angle) + (b.w / speed).cross(b.s) * std::sin(angle);
        b.s = sNew / sNew.norm(); // the norm drifts by round-off only; keep it exactly 1
    }
    static Vec3 axis(const State& b) { return b.s; }
    static Vec3 angularVelocity(const State& b, const BodyParams&) { return b.w; }
    static Vec3 angularMomentum(const State& b, const BodyParams& p) { return p.inertia[0] * b.w; }
    static double rotationalKinetic(const State& b, const BodyParams& p) {
        return 0.5 * p.inertia[0] * b.w.squaredNorm();
    }
    static double inverseInertia(const State& b, const BodyParams& p, const Vec3& a,
                                 const Vec3& c) {
        // Only the components perpendicular to s couple to the rotor's motion.
        return (a - a.dot(b.s) * b.s).dot(c - c.dot(b.s) * b.s) / p.inertia[0];
    }
    static void addAngularMomentum(State& b, const BodyParams& p, const Vec3& dL) {
        b.w += (dL - dL.dot(b.s) * b.s) / p.inertia[0];
        b.w -= b.w.dot(b.s) * b.s; // keep ω ⟂ s against round-off
    }
    static void scaleAngularVelocity(State& b, const BodyParams&, double f) { b.w *= f; }
};

} // namespace terrace
