#pragma once
// Asymmetric top (I1, I2, I3 distinct): exact free motion (van Zon & Schofield, J. Comput. Phys.
// 225, 145 (2007); REFERENCES.md "Exact free rigid-body motion", steps 1-5). With the axes
// reordered (a proper signed permutation) so that I2 is the middle moment and m ∈ [0, 1),
//     ω1 = ω1m cn(u|m),  ω2 = ω2m sn(u|m),  ω3 = ω3m dn(u|m),  u = ωp t + ε,
//     A(t) = M(ℓ(t)) R_z(ψ(t)) M(ℓ(0))ᵀ A(0),   ℓ = L_body / |L|,
// where ψ is the angle about the fixed L, ψ̇ = |L| (L1 ω1 + L2 ω2) / (L1² + L2²) (Landau &
// Lifshitz, Mechanics §37, their φ). ψ comes from the two real theta series of van Zon &
// Schofield, or, where their nome q → 1 makes them slow (near the separatrix m → 1), from the
// equivalent Legendre form (with dn² = 1 − m sn² and ω3 = ω3m dn in the formula above)
//     ψ̇ = |L|/I3 + (|L|/I1 − |L|/I3) / (1 − n sn²u),   n = I3 (I2 − I1) / (I1 (I2 − I3)) < 0,
//     ψ(t) = |L| t / I3 + (|L|/I1 − |L|/I3) [Π(n; am u | m) − Π(n; am ε | m)] / ωp,
// evaluated with Carlson's RF and RJ (DLMF §19.25(i)). On the separatrix m = 1 itself
// sn = tanh, cn = dn = sech and the integral is elementary.
// Two equal moments dispatch to the symmetric-top formula; ω along a principal axis is a rotation
// about that fixed axis. Verified in tests/core/test_free_motion.cpp against a converged RK4
// integration of Euler's equations and dA/dt = −[ω]× A.
#include "core/top_state.hpp"
#include <array>

namespace terrace {

struct AsymmetricTop : TopCommon {
    static constexpr std::string_view name = "asymmetric";
    static constexpr int rotationalDof = 3;

    /// How the angle ψ about L is evaluated; both are exact. Automatic takes the theta series
    /// unless it would need more than maxThetaTerms terms, then the Legendre form.
    enum class AngleMethod { Automatic, ThetaSeries, LegendrePi };
    static constexpr int maxThetaTerms = 64;

    /// Exact torque-free rotation over time t (any sign). Implemented in asymmetric_top.cpp.
    static void freeRotate(State& b, const BodyParams& p, double t);
    static void freeRotate(State& b, const BodyParams& p, double t, AngleMethod method);

    /// The free rotation from one state, prepared once (ordering, K, K', ε, theta constants), for
    /// evaluating the attitude at many times, e.g. in an event search. freeRotate(b, p, t) is
    /// b.A = FreeRotation(b, p).attitude(t).
    class FreeRotation;
};

namespace detail {

/// Jacobi elliptic functions sn, cn, dn of parameter m by the descending Landen transformation
/// (arithmetic-geometric mean; Abramowitz & Stegun §16.4 and §17.6). Built from m and its
/// complement m1 = 1 − m, each given to full relative precision, so that K and dn stay accurate as
/// m → 1. The table depends on m only: build it once per orbit.
class JacobiElliptic {
public:
    JacobiElliptic() : JacobiElliptic(0.0, 1.0) {}
    JacobiElliptic(double m, double m1);
    double K() const { return K_; } // complete elliptic integral of the first kind K(m)
    double m() const { return m_; }
    double m1() const { return m1_; }
    struct Values {
        double sn, cn, dn;
    };
    /// sn, cn, dn at u ∈ [−K, K] (no reduction; use reduce() first for larger u).
    Values reduced(double u) const;
    /// Splits u = r + 2K j with r ∈ [−K, K]; sn(u) = (−1)^j sn(r), cn likewise, dn(u) = dn(r).
    struct Reduction {
        double r;
        double j;
    };
    Reduction reduce(double u) const;
    Values operator()(double u) const;

private:
    Values landen(double u) const; // descending Landen recursion, accurate for |u| <= K/2
    static constexpr int maxLevels = 32;
    double m_, m1_, K_;
    int levels_ = 0;
    std::array<double, maxLevels> a_{}, c_{};
};

/// Constants of the free orbit in the reordered principal frame (see asymmetric_top.cpp).
struct TopOrbit {
    double I1 = 0, I2 = 0, I3 = 0, L = 0;     // ordered moments, |L|
    double w1m = 0, w2m = 0, w3m = 0, wp = 0; // amplitudes of ω1, ω2, ω3 and the rate of u
    double m = 0, m1 = 1;                     // elliptic parameter and 1 − m
    double n = 0;                             // characteristic of the Legendre form of ψ
};

/// The complementary elliptic parameter 1 − m of the free orbit of body angular momentum Lbody
/// for principal moments I (distinct), after the reordering of the axes that makes m < 1.
/// Zero on the separatrix (rotation about the middle axis and its homoclinic orbits).
double complementaryEllipticParameter(const Vec3& Lbody, const Vec3& I);

} // namespace detail

class AsymmetricTop::FreeRotation {
public:
    FreeRotation(const TopState& s, const BodyParams& p,
                 AngleMethod method = AngleMethod::Automatic);
    /// The attitude A(t) (lab -> body) after free rotation over time t (any sign).
    Mat3 attitude(double t) const;
    /// Whether ψ is taken from the theta series (else the Legendre form or a closed form).
    bool usesThetaSeries() const { return kind_ == Kind::Elliptic && theta_; }

private:
    enum class Kind { Still, Symmetric, PrincipalAxis, Separatrix, Elliptic };
    Kind kind_ = Kind::Still;
    Mat3 A0_; // initial attitude
    Vec3 L_;  // lab angular momentum
    double Iperp_ = 0, Iaxis_ = 0, omegaAxis_ = 0;
    int axis_ = 2; // symmetric top's unique axis, or the principal axis of rotation
    Mat3 P_, B0_;  // reordering, and M(ℓ(0))ᵀ P A(0)
    detail::TopOrbit o_;
    detail::JacobiElliptic jac_;
    double eps_ = 0; // initial elliptic argument
    bool theta_ = false;
    double K_ = 0, a_ = 0, b_ = 0, A2_ = 0, arg0_ = 0; // theta series: q = e^−a, ξ = e^b
    double Pi_ = 0, W0_ = 0;                           // Legendre form: Π(n|m) and W(ε)

    double thetaArg(double r, double j) const;
};

} // namespace terrace
