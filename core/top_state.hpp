#pragma once
// State and the frame-independent helpers shared by the symmetric and the asymmetric top.
// A maps lab vectors to the body (principal-axis) frame; L is the lab-frame angular momentum.
#include "core/body_kind.hpp"

namespace terrace {

struct TopState {
    Vec3 r = Vec3::Zero();
    Vec3 v = Vec3::Zero();
    Mat3 A = Mat3::Identity(); // attitude: lab -> body
    Vec3 L = Vec3::Zero();     // angular momentum, lab frame, g/mol Å² per time unit
};

namespace detail {

inline Vec3 bodyOmega(const TopState& b, const BodyParams& p) {
    return (b.A * b.L).cwiseQuotient(p.inertia);
}

} // namespace detail

/// Helpers common to every top; Kind supplies name, rotationalDof and freeRotate.
struct TopCommon {
    using State = TopState;
    /// The body's third principal axis in the lab frame (the symmetry axis of a symmetric top).
    static Vec3 axis(const State& b) { return b.A.row(2).transpose(); }
    static Vec3 angularVelocity(const State& b, const BodyParams& p) {
        return b.A.transpose() * detail::bodyOmega(b, p);
    }
    static Vec3 angularMomentum(const State& b, const BodyParams&) { return b.L; }
    static double rotationalKinetic(const State& b, const BodyParams& p) {
        return 0.5 * (b.A * b.L).dot(detail::bodyOmega(b, p));
    }
    static double inverseInertia(const State& b, const BodyParams& p, const Vec3& a,
                                 const Vec3& c) {
        return (b.A * a).cwiseQuotient(p.inertia).dot(b.A * c);
    }
    static void addAngularMomentum(State& b, const BodyParams&, const Vec3& dL) { b.L += dL; }
    static void scaleAngularVelocity(State& b, const BodyParams&, double f) { b.L *= f; }
};

} // namespace terrace
