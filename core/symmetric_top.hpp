#pragma once
// Symmetric top (I1 = I2 ≠ I3, unique axis 3). In the lab frame ω = L/I1 + (1/I3 − 1/I1) L3 n,
// with n the symmetry axis and L3 = L·n constant, so the free motion is a uniform precession about
// the fixed L at rate |L|/I1 composed with a spin about n at rate ωp = (1 − I3/I1) ω3:
//     Q(t) = R_L(|L| t / I1) R_{n(0)}(ωp t) Q(0),   Q = Aᵀ (body -> lab)
// (REFERENCES.md "Exact free rigid-body motion"; van Zon & Schofield, J. Comput. Phys. 225,
// 145 (2007)).
#include "core/top_state.hpp"
#include <cmath>

namespace terrace {

struct SymmetricTop : TopCommon {
    static constexpr std::string_view name = "symmetric";
    static constexpr int rotationalDof = 3;

    static void freeRotate(State& b, const BodyParams& p, double t) {
        const double Lnorm = b.L.norm();
        if (Lnorm == 0.0) return;
        const double I1 = p.inertia[0], I3 = p.inertia[2];
        const Vec3 n = b.A.row(2).transpose();
        const double omega3 = b.L.dot(n) / I3;
        const Mat3 spin = rotationMatrix(n, (1.0 - I3 / I1) * omega3 * t);
        const Mat3 precession = rotationMatrix(b.L / Lnorm, Lnorm * t / I1);
        b.A = b.A * spin.transpose() * precession.transpose();
    }
};

} // namespace terrace
