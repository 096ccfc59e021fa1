#pragma once
// State and the frame-independent helpers shared by the symmetric and the asymmetric top.
// A maps lab vectors to the body (principal-axis) frame; L is the lab-frame angular momentum.
// Free motion leaves L unchanged and moves A along dA/dt = −[ω]× A (ω in the body frame), which
// follows from Q = Aᵀ (body -> lab) obeying dQ/dt = Q [ω]×, i.e. (dA/dt)ᵀ A = [ω_lab]× (paper,
// "Rigid Systems Interacting Via Stepped-Potentials"; van Zon & Schofield, J. Comput. Phys. 225,
// 145 (2007)).
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

/// One Newton step towards the nearest rotation, A <- A (3 − AᵀA) / 2. The free-motion formulas
/// produce products of rotations that are orthonormal to a few ulp; without this the error would
/// random-walk over millions of calls. One step squares the deviation, so it stays at round-off.
inline void reorthonormalise(Mat3& A) {
    const Mat3 gram = A.transpose() * A;
    A = A * (1.5 * Mat3::Identity() - 0.5 * gram);
}

} // namespace detail

/// Helpers common to every top; Kind supplies name, rotationalDof and freeRotate.
struct TopCommon {
    using State = TopState;
    /// The body's third principal axis in the lab frame (the symmetry axis of a symmetric top).
    static Vec3 axis(const State& b) { return b.A.row(2).transpose(); }
    /// The rotation body -> lab, Q = Aᵀ: its columns are the principal axes in the lab frame.
    static Mat3 frame(const State& b) { return b.A.transpose(); }
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
