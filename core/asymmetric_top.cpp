// Exact free rotation of the asymmetric top; formulas and sources in asymmetric_top.hpp.
#include "core/asymmetric_top.hpp"
#include "core/symmetric_top.hpp"
#include <boost/math/special_functions/ellint_rf.hpp>
#include <boost/math/special_functions/ellint_rj.hpp>
#include <cmath>
#include <limits>
#include <numbers>

namespace terrace {

namespace detail {

JacobiElliptic::JacobiElliptic(double m, double m1) : m_(m), m1_(m1) {
    // AGM of 1 and sqrt(m1); c_n = c_{n-1}² / (4 a_n) avoids the cancellation in (a − b) / 2.
    double a = 1.0, b = std::sqrt(m1), c = std::sqrt(m);
    a_[0] = a;
    c_[0] = c;
    while (levels_ + 1 < maxLevels && c > std::numeric_limits<double>::epsilon() * a) {
        const double aNext = 0.5 * (a + b);
        c = c * c / (4.0 * aNext);
        b = std::sqrt(a * b);
        a = aNext;
        ++levels_;
        a_[levels_] = a;
        c_[levels_] = c;
    }
    K_ = std::numbers::pi / (2.0 * a);
}

JacobiElliptic::Values JacobiElliptic::landen(double u) const {
    double phi = std::ldexp(a_[levels_] * u, levels_);
    for (int n = levels_; n >= 1; --n)
        phi = 0.5 * (phi + std::asin(c_[n] / a_[n] * std::sin(phi)));
    const double sn = std::sin(phi), cn = std::cos(phi);
    // dn² = 1 − m sn² = cn² + m1 sn²: no cancellation as m → 1.
    return {sn, cn, std::sqrt(cn * cn + m1_ * sn * sn)};
}

JacobiElliptic::Values JacobiElliptic::reduced(double u) const {
    if (std::abs(u) <= 0.5 * K_) return landen(u);
    // Near ±K, cn = cos φ would carry only an absolute error ~1 ulp while dn → sqrt(m1) can be
    // smaller still; the quarter-period shift (A&S Table 16.8) keeps both to full relative
    // precision: sn(K − v) = cn v / dn v, cn(K − v) = sqrt(m1) sn v / dn v, dn(K − v) = sqrt(m1) /
    // dn v.
    const double v = K_ - std::abs(u); // exact (Sterbenz) since |u| ∈ [K/2, K]
    const Values w = landen(v);
    const double k1 = std::sqrt(m1_);
    return {std::copysign(w.cn / w.dn, u), k1 * w.sn / w.dn, k1 / w.dn};
}

JacobiElliptic::Reduction JacobiElliptic::reduce(double u) const {
    const double j = std::nearbyint(u / (2.0 * K_));
    return {std::fma(-2.0 * K_, j, u), j};
}

JacobiElliptic::Values JacobiElliptic::operator()(double u) const {
    const Reduction red = reduce(u);
    Values v = reduced(red.r);
    if (std::fmod(red.j, 2.0) != 0.0) {
        v.sn = -v.sn;
        v.cn = -v.cn;
    }
    return v;
}

} // namespace detail

namespace {

constexpr double pi = std::numbers::pi;
// Series are summed until a term falls below this fraction of the leading one (below 1 ulp).
constexpr double seriesTolerance = 1e-17;

double sign(double x) {
    return x < 0.0 ? -1.0 : 1.0;
}

using LongVec3 = Eigen::Matrix<long double, 3, 1>;

/// Axes reordered by a proper signed permutation P (rows ±unit vectors, det +1) so that I2 is the
/// middle moment and m ∈ [0, 1): the third axis is the one L circulates about (REFERENCES.md step
/// 1; for D = E2 I2 − L² < 0 the largest moment, for D > 0 the smallest).
struct Ordering {
    Mat3 P = Mat3::Zero();
    Vec3 I, L;
    double D = 0.0;
};

Ordering orderAxes(const LongVec3& Lbody, const Vec3& I) {
    int lo = 0, hi = 0;
    for (int k = 1; k < 3; ++k) {
        if (I[k] < I[lo]) lo = k;
        if (I[k] > I[hi]) hi = k;
    }
    const int mid = 3 - lo - hi;
    // D = E2 I2 − L² (the middle axis contributes nothing). Its two terms cancel near the
    // separatrix, where 1 − m ∝ D sets the period: one ulp of a double L_body would move 1 − m by
    // ~1e-16 / (1 − m) relative, so L_body = A L and D are formed in long double.
    auto excess = [&](int k) {
        return Lbody[k] * Lbody[k] * static_cast<long double>(I[mid] - I[k]) / I[k];
    };
    Ordering o;
    o.D = static_cast<double>(excess(lo) + excess(hi));
    const int first = o.D > 0.0 ? hi : lo, third = o.D > 0.0 ? lo : hi;
    o.P(0, first) = 1.0;
    o.P(1, mid) = 1.0;
    o.P(2, third) = 1.0;
    o.P.row(1) *= o.P.determinant(); // flip the middle axis if the permutation is odd
    o.I = Vec3(I[first], I[mid], I[third]);
    o.L = o.P * Lbody.cast<double>();
    return o;
}

/// Constants of the orbit in the ordered frame (REFERENCES.md step 2, signs as derived there:
/// ω1m has the sign of ω1(0), ω2m the opposite sign, ω3m the sign of ω3, which never changes).
/// Returns false if L lies along a principal axis (also to within underflow, where the formulas
/// would divide by zero); the middle axis is D = 0 with L1 = L3 = 0, an equilibrium.
bool orbitOf(const Ordering& o, detail::TopOrbit& b) {
    const double I1 = o.I[0], I2 = o.I[1], I3 = o.I[2];
    const double L1 = o.L[0], L2 = o.L[1], L3 = o.L[2];
    const double I13 = I1 - I3, I23 = I2 - I3, I21 = I2 - I1;
    const double L12 = L1 * L1 * I13 / I1 + L2 * L2 * I23 / I2; // L² − E2 I3, like-signed terms
    const double L23 = L2 * L2 * I21 / I2 - L3 * L3 * I13 / I3; // L² − E2 I1, like-signed terms
    if (L12 == 0.0 || L23 == 0.0 || (L1 * L1 == 0.0 && L3 * L3 == 0.0)) return false;
    b.I1 = I1, b.I2 = I2, b.I3 = I3, b.L = o.L.norm();
    const double s1 = sign(L1), s3 = sign(L3);
    b.w1m = s1 * std::sqrt(L12 / (I1 * I13));
    b.w2m = -s1 * std::sqrt(L12 / (I2 * I23));
    b.w3m = s3 * std::sqrt(-L23 / (I3 * I13));
    b.wp = s3 * sign(I23) * std::sqrt(-I23 * L23 / (I1 * I2 * I3));
    b.m = I21 * L12 / (I23 * L23);
    b.m1 = (I3 - I1) * o.D / (I23 * L23); // 1 − m without cancellation
    b.n = I3 * I21 / (I1 * I23);
    return true;
}

/// The rotation M(ℓ) whose third column is ℓ = Lb/|Lb| (REFERENCES.md step 5).
Mat3 frameOf(const Vec3& Lb) {
    const double Lperp = std::hypot(Lb[0], Lb[1]), Lnorm = Lb.norm();
    const double o1 = Lb[0] / Lperp, o2 = Lb[1] / Lperp, f = Lperp / Lnorm, o3 = Lb[2] / Lnorm;
    Mat3 M;
    M << o1 * o3, -o2, o1 * f, o2 * o3, o1, o2 * f, -f, 0.0, o3;
    return M;
}

/// R_z(ψ) of REFERENCES.md step 5 (maps the rotated L-frame back by −ψ about z).
Mat3 rotationZ(double psi) {
    const double c = std::cos(psi), s = std::sin(psi);
    Mat3 R;
    R << c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0;
    return R;
}

/// ∫₀^u du' / (1 − n sn²(u'|m)) in Carlson form for u = r + 2K j, r ∈ [−K, K]: the integrand
/// has period 2K, and over one period the integral is 2 Π(n|m) = 2 [RF(0, m1, 1) + n/3 RJ(0, m1,
/// 1, 1 − n)] (DLMF §19.25(i) with φ = am u, cos φ = cn u, sqrt(1 − m sin²φ) = dn u).
double completePi(double n, double m1) {
    return boost::math::ellint_rf(0.0, m1, 1.0) +
           n / 3.0 * boost::math::ellint_rj(0.0, m1, 1.0, 1.0 - n);
}

double legendreW(const detail::JacobiElliptic::Values& v, double j, double n, double Pi) {
    const double c2 = v.cn * v.cn, d2 = v.dn * v.dn, s = v.sn;
    return s * boost::math::ellint_rf(c2, d2, 1.0) +
           n / 3.0 * s * s * s * boost::math::ellint_rj(c2, d2, 1.0, 1.0 - n * s * s) +
           2.0 * j * Pi;
}

/// Exact rotation when L is along principal axis k: dA/dt = −[ω]× A with ω = ω_k e_k constant.
Mat3 principalRotation(int k, double omega, double t) {
    return rotationMatrix(Vec3::Unit(k), -omega * t);
}

} // namespace

namespace detail {

double complementaryEllipticParameter(const Vec3& Lbody, const Vec3& I) {
    TopOrbit o;
    const Ordering ord = orderAxes(Lbody.cast<long double>(), I);
    return orbitOf(ord, o) ? o.m1 : (ord.D == 0.0 ? 0.0 : 1.0);
}

} // namespace detail

AsymmetricTop::FreeRotation::FreeRotation(const TopState& s, const BodyParams& p,
                                          AngleMethod method)
    : A0_(s.A), L_(s.L) {
    const Vec3& I = p.inertia;
    if (s.L.squaredNorm() == 0.0) return; // Kind::Still
    // Two equal moments: the symmetric (or spherical) top, unique axis the odd one out.
    if (I[0] == I[1] || I[1] == I[2] || I[0] == I[2]) {
        kind_ = Kind::Symmetric;
        axis_ = I[0] == I[1] ? 2 : (I[1] == I[2] ? 0 : 1);
        Iaxis_ = I[axis_];
        Iperp_ = I[(axis_ + 1) % 3];
        return;
    }
    const LongVec3 LbodyPrecise = s.A.cast<long double>() * s.L.cast<long double>();
    const Ordering ord = orderAxes(LbodyPrecise, I);
    if (!orbitOf(ord, o_)) {
        kind_ = Kind::PrincipalAxis;
        const Vec3 Lbody = LbodyPrecise.cast<double>();
        Lbody.cwiseAbs().maxCoeff(&axis_);
        omegaAxis_ = Lbody[axis_] / I[axis_];
        return;
    }
    P_ = ord.P;
    B0_ = frameOf(ord.L).transpose() * ord.P * s.A;
    const Vec3& L0 = ord.L;
    // sn ε = ω2/ω2m, cn ε = ω1/ω1m ≥ 0, dn ε = ω3/ω3m.
    const double snE = L0[1] / (o_.I2 * o_.w2m), cnE = L0[0] / (o_.I1 * o_.w1m);
    const double dnE = L0[2] / (o_.I3 * o_.w3m);
    if (o_.m1 == 0.0) {
        // On the separatrix sn = tanh, cn = sech: ε = asinh(sn ε / cn ε).
        kind_ = Kind::Separatrix;
        eps_ = std::asinh(snE / cnE);
        const double rnu = std::sqrt(-o_.n);
        W0_ = (eps_ + rnu * std::atan(rnu * std::tanh(eps_))) / (1.0 - o_.n);
        return;
    }
    kind_ = Kind::Elliptic;
    jac_ = detail::JacobiElliptic(o_.m, o_.m1);
    K_ = jac_.K();
    eps_ = snE * boost::math::ellint_rf(cnE * cnE, dnE * dnE, 1.0); // ε = F(am ε | m)
    if (method != AngleMethod::LegendrePi) {
        // Theta constants (REFERENCES.md step 4). η = sgn(ω3) K' − F(arcsin(I3|ω3m|/L) | 1 − m)
        // = sgn(ω3) F(χ | 1 − m) by Legendre's complement relation, with
        // tan²χ = I1 (I3 − I2) / (I3 (I2 − I1)) independent of the state.
        a_ = pi * detail::JacobiElliptic(o_.m1, o_.m).K() / K_;
        const double wA = o_.I1 * (o_.I3 - o_.I2), wB = o_.I3 * (o_.I2 - o_.I1);
        const double sin2 = wA / (wA + wB), cos2 = wB / (wA + wB);
        const double F = std::sqrt(sin2) * boost::math::ellint_rf(cos2, cos2 + o_.m * sin2, 1.0);
        b_ = sign(o_.w3m) * pi * F / K_;
        // A2's terms fall like e^{−k(2a − |b|)}: the count that reaches seriesTolerance.
        const int terms =
            static_cast<int>(std::ceil(-std::log(seriesTolerance) / (2.0 * a_ - std::abs(b_))));
        theta_ = method == AngleMethod::ThetaSeries || terms <= maxThetaTerms;
        if (theta_) {
            double sum = 0.0;
            for (int k = 1; k <= terms; ++k)
                sum += (std::exp(k * (b_ - 2.0 * a_)) - std::exp(-k * (b_ + 2.0 * a_))) /
                       -std::expm1(-2.0 * k * a_);
            A2_ = o_.L / o_.I1 + pi * o_.wp / (2.0 * K_) / std::tanh(0.5 * b_) -
                  pi * o_.wp / K_ * sum;
            arg0_ = thetaArg(eps_, 0.0);
            return;
        }
    }
    Pi_ = completePi(o_.n, o_.m1);
    W0_ = legendreW({snE, cnE, dnE}, 0.0, o_.n, Pi_);
}

/// Continuous arg of the theta function at u = r + 2K j. For b > 0 the series (scaled by ξ^{−1/2})
/// stays in the lower half plane on r ∈ [−K, K] and turns by +π per period 2K; b < 0 is its
/// complex conjugate.
double AsymmetricTop::FreeRotation::thetaArg(double r, double j) const {
    const double x = pi * r / (2.0 * K_), B = std::abs(b_);
    double re = 0.0, im = 0.0;
    for (int k = 0;; ++k) {
        const double base = -a_ * k * (k + 1.0), alt = (k % 2 == 0) ? 1.0 : -1.0;
        const double ep = std::exp(base + k * B), em = std::exp(base - (k + 1.0) * B);
        re += alt * (ep + em) * std::sin((2 * k + 1) * x);
        im -= alt * (ep - em) * std::cos((2 * k + 1) * x);
        if (ep < seriesTolerance) break;
    }
    return sign(b_) * (std::atan2(re, -im) - 0.5 * pi + j * pi);
}

Mat3 AsymmetricTop::FreeRotation::attitude(double t) const {
    Mat3 A;
    switch (kind_) {
    case Kind::Still:
        return A0_;
    case Kind::Symmetric:
        A = A0_;
        detail::rotateSymmetricTop(A, L_, Iperp_, Iaxis_, axis_, t);
        return A;
    case Kind::PrincipalAxis:
        A = principalRotation(axis_, omegaAxis_, t) * A0_;
        break;
    case Kind::Separatrix: {
        const double u = o_.wp * t + eps_, rnu = std::sqrt(-o_.n);
        const double W = (u + rnu * std::atan(rnu * std::tanh(u))) / (1.0 - o_.n);
        const double psi = o_.L * t / o_.I3 + (o_.L / o_.I1 - o_.L / o_.I3) * (W - W0_) / o_.wp;
        const double sech = 1.0 / std::cosh(u);
        const Vec3 Lt(o_.I1 * o_.w1m * sech, o_.I2 * o_.w2m * std::tanh(u), o_.I3 * o_.w3m * sech);
        A = P_.transpose() * frameOf(Lt) * rotationZ(psi) * B0_;
        break;
    }
    case Kind::Elliptic: {
        const auto red = jac_.reduce(o_.wp * t + eps_);
        detail::JacobiElliptic::Values v = jac_.reduced(red.r);
        const double psi = theta_ ? A2_ * t - (thetaArg(red.r, red.j) - arg0_)
                                  : o_.L * t / o_.I3 + (o_.L / o_.I1 - o_.L / o_.I3) *
                                                           (legendreW(v, red.j, o_.n, Pi_) - W0_) /
                                                           o_.wp;
        if (std::fmod(red.j, 2.0) != 0.0) {
            v.sn = -v.sn;
            v.cn = -v.cn;
        }
        const Vec3 Lt(o_.I1 * o_.w1m * v.cn, o_.I2 * o_.w2m * v.sn, o_.I3 * o_.w3m * v.dn);
        A = P_.transpose() * frameOf(Lt) * rotationZ(psi) * B0_;
        break;
    }
    }
    detail::reorthonormalise(A);
    return A;
}

void AsymmetricTop::freeRotate(State& b, const BodyParams& p, double t) {
    freeRotate(b, p, t, AngleMethod::Automatic);
}

void AsymmetricTop::freeRotate(State& b, const BodyParams& p, double t, AngleMethod method) {
    if (t == 0.0) return;
    b.A = FreeRotation(b, p, method).attitude(t);
}

} // namespace terrace
