#pragma once
// Symmetric top: two equal moments I⊥ about the body axes other than the unique axis n (moment
// In; SymmetricTop takes I1 = I2 = I⊥, n = third axis). In the lab frame
//     ω = L/I⊥ + (1/In − 1/I⊥) Ln n,    Ln = L·n constant,
// so with Q = Aᵀ (body -> lab) the free motion is a precession of the whole body about the fixed
// L at rate |L|/I⊥ composed with a spin about the unique axis at ωp = (1 − In/I⊥) ωn, ωn = Ln/In:
//     Q(t) = R_L(|L| t / I⊥) R_{n(0)}(ωp t) Q(0),   i.e.   A(t) = A(0) R_{n(0)}ᵀ R_Lᵀ.
// Why: writing Q = R_L(|L|t/I⊥) Q1 leaves dQ1/dt = [(1/In − 1/I⊥) Ln n1]× Q1 with n1 = Q1 e_n,
// whose axis n1 is therefore constant. The spherical top is In = I⊥ (no spin).
// (REFERENCES.md "Exact free rigid-body motion"; van Zon & Schofield, J. Comput. Phys. 225, 145
// (2007).)
#include "core/top_state.hpp"
#include <cassert>
#include <cmath>

namespace terrace {

namespace detail {

/// Exact free rotation over time t (any sign) of a top with moment Iaxis about body axis
/// `uniqueAxis` (0, 1 or 2) and Iperp about the other two.
inline void rotateSymmetricTop(Mat3& A, const Vec3& L, double Iperp, double Iaxis, int uniqueAxis,
                               double t) {
    const double Lnorm = L.norm();
    if (Lnorm == 0.0 || t == 0.0) return;
    const Vec3 n = A.row(uniqueAxis).transpose();
    const double omegaAxis = L.dot(n) / Iaxis;
    const Mat3 spin = rotationMatrix(n, (1.0 - Iaxis / Iperp) * omegaAxis * t);
    const Mat3 precession = rotationMatrix(L / Lnorm, Lnorm * t / Iperp);
    A = A * spin.transpose() * precession.transpose();
    reorthonormalise(A);
}

} // namespace detail

struct SymmetricTop : TopCommon {
    static constexpr std::string_view name = "symmetric";
    static constexpr int rotationalDof = 3;

    /// Exact torque-free rotation over time t (any sign); requires inertia[0] == inertia[1]
    /// (the scene reader enforces it; AsymmetricTop handles any pair of equal moments).
    static void freeRotate(State& b, const BodyParams& p, double t) {
        assert(p.inertia[0] == p.inertia[1] && "SymmetricTop needs I1 == I2");
        detail::rotateSymmetricTop(b.A, b.L, p.inertia[0], p.inertia[2], 2, t);
    }
};

} // namespace terrace
