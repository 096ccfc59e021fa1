#pragma once
// The Gay–Berne potential between uniaxial ellipsoids (Gay & Berne, J. Chem. Phys. 74, 3316
// (1981)). With r = |r_ij|, r̂ = r_ij/r and the unit symmetry axes u_i, u_j,
//     a = r̂·u_i,   b = r̂·u_j,   c = u_i·u_j,
//     H(χ) = (χ/2) [(a + b)²/(1 + χc) + (a − b)²/(1 − χc)],
//     U = ε LJ₁(x),   LJ₁(x) = 4[(σ0/x)^12 − (σ0/x)^6],   x = r − σ + σ0,
//     σ = σ0 [1 − H(χ)]^(−1/2),   χ = (κ² − 1)/(κ² + 1),
//     ε = ε0 ε1^ν ε2^μ,   ε1 = (1 − χ²c²)^(−1/2),   ε2 = 1 − H(χ'),
//     χ' = (κ'^(1/μ) − 1)/(κ'^(1/μ) + 1).
// σ is the range of Berne & Pechukas' Gaussian overlap (J. Chem. Phys. 56, 4213 (1972)): σ0 side
// by side, κσ0 end to end, σ0/√(1 − χ) in a T. Shifting the LJ argument by σ rather than scaling
// it keeps the well σ0-wide whatever the orientation, as in Gay & Berne's form. The well depth is
// ε0 for crossed axes, ε0 (1 − χ²)^(−ν/2) side by side, and κ' times less end to end, where
// ε2 = κ'^(−1/μ).
//
// Gradient, in the scalar form of Allen & Germano, Mol. Phys. 104, 3225 (2006): with the partials
// U_q = ∂U/∂q at fixed r (q = a, b, c) and U_r = ε LJ₁'(x) at fixed a, b, c,
//     U_q = U ∂lnε/∂q − U_r ∂σ/∂q,
//     ∂σ/∂q = (σ/2) H_q(χ)/(1 − H(χ)),   ∂lnε/∂q = νχ²c/(1 − χ²c²) [q = c only] − μ H_q(χ')/ε2,
//     H_a = χ(p + m),   H_b = χ(p − m),   H_c = −(χ²/2)(p² − m²),
//     p = (a + b)/(1 + χc),   m = (a − b)/(1 − χc)   (so H = (χ/2)[(a + b)p + (a − b)m]).
// Since ∂a/∂r_ij = (u_i − a r̂)/r and ∂a/∂u_i = r̂ (likewise b), ∂c/∂u_i = u_j, ∂c/∂u_j = u_i:
//     F_ij = −∂U/∂r_ij = −[U_r − (a U_a + b U_b)/r] r̂ − (U_a u_i + U_b u_j)/r,
// and a small rotation δθ of body i moves u_i by δθ × u_i, so dU = (u_i × ∂U/∂u_i)·δθ = −τ_ij·δθ:
//     τ_ij = −u_i × (U_a r̂ + U_c u_j) = U_a r̂ × u_i − U_c u_i × u_j,
//     τ_ji = −u_j × (U_b r̂ + U_c u_i) = U_b r̂ × u_j + U_c u_i × u_j.
// The c terms cancel in τ_ij + τ_ji and the rest is −r_ij × F_ij: angular momentum is conserved.
// Units: ε0 kJ/mol, σ0 Å; κ, κ', μ, ν are pure numbers.
//
// Overlapping cores (x ≤ 0) are unphysical and outside LJ₁'s domain: there U is +∞ (force and
// torques zero). The engines never go there: SMD's repulsive wall turns bodies back long before,
// and DMD's topmost level is a hard wall.
#include "core/pair_potential.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace terrace {

struct GayBernePotential {
    static constexpr std::string_view name = "gay-berne";
    static constexpr AttitudeUse attitude = AttitudeUse::Axis;
    using Orientation = Vec3; // the unit symmetry axis u of the ellipsoid, lab frame

    double epsilon = 1.0;    // ε0, kJ/mol: the well depth with crossed axes
    double sigma = 1.0;      // σ0 = σ_s, Å: the side-by-side contact distance
    double kappa = 3.0;      // κ = σ_e/σ_s: end-to-end over side-by-side contact distance
    double kappaPrime = 5.0; // κ' = ε_s/ε_e: side-by-side over end-to-end well depth
    double mu = 2.0;         // μ: exponent of the orientation-and-direction factor ε2
    double nu = 1.0;         // ν: exponent of the orientation factor ε1

    // Same parameters, same pair energies: terrace designs are remembered by it
    // (dmd/terrace_design.hpp, rememberedDesign).
    bool operator==(const GayBernePotential&) const = default;

    /// "" when the parameters are usable, else what is wrong, naming the parameter: the scene
    /// layer reports it (an aggregate has no constructor to check them in).
    std::string problem() const {
        const auto bad = [](const char* key, const char* rule, double v) {
            std::ostringstream out;
            out << key << " must be " << rule << ", got " << v;
            return out.str();
        };
        // Written as !(v > 0) so that NaN is rejected too.
        if (!(std::isfinite(epsilon) && epsilon > 0.0)) return bad("epsilon", "> 0", epsilon);
        if (!(std::isfinite(sigma) && sigma > 0.0)) return bad("sigma", "> 0", sigma);
        if (!(std::isfinite(kappa) && kappa > 0.0)) return bad("kappa", "> 0", kappa);
        if (!(std::isfinite(kappaPrime) && kappaPrime > 0.0))
            return bad("kappaPrime", "> 0", kappaPrime);
        if (!(std::isfinite(mu) && mu >= 0.0)) return bad("mu", ">= 0", mu);
        if (!(std::isfinite(nu) && nu >= 0.0)) return bad("nu", ">= 0", nu);
        // |χ| = 1 would put poles 1 ∓ χc = 0 inside the domain: extreme κ, or κ'^(1/μ) with μ → 0.
        if (!(std::abs(chi()) < 1.0)) return bad("kappa", "within the range where |χ| < 1", kappa);
        if (!(std::abs(chiPrime()) < 1.0))
            return bad("mu", "large enough for κ' that |χ'| < 1", mu);
        return "";
    }

    /// χ = (κ² − 1)/(κ² + 1): the shape anisotropy of the overlap range.
    double chi() const {
        const double k2 = kappa * kappa;
        return (k2 - 1.0) / (k2 + 1.0);
    }
    /// χ' = (k − 1)/(k + 1) with k = κ'^(1/μ), written tanh(ln k / 2) in general so that k may
    /// overflow; μ = 1 and 2 (the usual choices) skip the transcendental functions. With μ = 0
    /// the factor ε2^μ is 1 whatever χ', which is then taken as 0.
    double chiPrime() const {
        if (mu == 0.0) return 0.0;
        if (mu == 1.0) return (kappaPrime - 1.0) / (kappaPrime + 1.0);
        if (mu == 2.0) {
            const double k = std::sqrt(kappaPrime);
            return (k - 1.0) / (k + 1.0);
        }
        return std::tanh(std::log(kappaPrime) / (2.0 * mu));
    }

    /// σ(u_i, u_j, r̂), Å: the centre distance along the unit vector rHat at which U = 0.
    double contactDistance(const Vec3& rHat, const Vec3& ui, const Vec3& uj) const {
        const double a = rHat.dot(ui), b = rHat.dot(uj), c = ui.dot(uj);
        return sigma / std::sqrt(1.0 - overlap(chi(), a, b, c).H);
    }
    /// ε(u_i, u_j, r̂), kJ/mol: the well depth along the unit vector rHat.
    double wellDepth(const Vec3& rHat, const Vec3& ui, const Vec3& uj) const {
        const double a = rHat.dot(ui), b = rHat.dot(uj), c = ui.dot(uj);
        const double chiS = chi(), cc = chiS * c;
        return epsilon * power(1.0 - cc * cc, -0.5 * nu) *
               power(1.0 - overlap(chiPrime(), a, b, c).H, mu);
    }

    // Ranges of σ and ε over all configurations. σ: H(χ) runs from 0 (side by side) to 2χ/(1 + χ)
    // (end to end) for χ ≥ 0, the reverse for χ < 0, so σ runs between σ0 and κσ0. ε1 runs from 1
    // (c = 0) to (1 − χ²)^(−1/2) = (κ + 1/κ)/2 (c² = 1); ε2 between 1 (a = b = 0) and κ'^(−1/μ)
    // (a = b = c = 1), so ε2^μ between 1 and 1/κ'.
    double sigmaMin() const { return sigma * std::min(1.0, kappa); }
    double sigmaMax() const { return sigma * std::max(1.0, kappa); }
    /// Half the longest contact distance, Å: how far the ellipsoid's ends lie from its centre,
    /// by which the DMD search bounds their motion as it turns (dmd/pair_prediction.hpp).
    double extent() const { return 0.5 * sigmaMax(); }
    /// The deepest well: parallel axes (c² = 1) side by side when κ' ≥ 1, end to end when κ' < 1,
    /// where ε1 and ε2 are largest together, so this is attained.
    double epsilonMax() const {
        return epsilon * power(0.5 * (kappa + 1.0 / kappa), nu) *
               (mu > 0.0 ? std::max(1.0, 1.0 / kappaPrime) : 1.0);
    }
    /// A lower bound of the well depth (the smallest ε1 and ε2 need not occur together).
    double epsilonMin() const {
        return epsilon * (mu > 0.0 ? std::min(1.0, 1.0 / kappaPrime) : 1.0);
    }

    PairForce evaluate(const Vec3& rij, const Vec3& ui, const Vec3& uj) const {
        const Terms t = terms<true>(rij, ui, uj);
        PairForce f;
        f.U = t.U;
        if (!t.finite) return f;
        const Vec3 rHat = rij * (1.0 / t.r);
        const double inverseR = 1.0 / t.r;
        f.F = (-(t.Ur - (t.a * t.Ua + t.b * t.Ub) * inverseR)) * rHat - (t.Ua * inverseR) * ui -
              (t.Ub * inverseR) * uj;
        const Vec3 cij = ui.cross(uj);
        f.tauI = t.Ua * rHat.cross(ui) - t.Uc * cij;
        f.tauJ = t.Ub * rHat.cross(uj) + t.Uc * cij;
        return f;
    }
    /// U and dU/dt along free motion by the chain rule through (r, a, b, c), with
    ///     ṙ = r̂·v_ij,   ȧ = (u_i·v_ij − a ṙ)/r + ω_i·(u_i × r̂),   ḃ likewise with u_j, ω_j,
    ///     ċ = (ω_i − ω_j)·(u_i × u_j):
    /// the value of eq. (13) with evaluate()'s force and torques, without building them.
    EnergyRate energyRate(const Vec3& rij, const Vec3& vij, const Vec3& ui, const Vec3& wi,
                          const Vec3& uj, const Vec3& wj) const {
        const Terms t = terms<true>(rij, ui, uj);
        if (!t.finite) return {t.U, 0.0};
        const double inverseR = 1.0 / t.r;
        const double rDot = rij.dot(vij) * inverseR;
        const double aDot =
            (ui.dot(vij) - t.a * rDot) * inverseR + wi.dot(ui.cross(rij)) * inverseR;
        const double bDot =
            (uj.dot(vij) - t.b * rDot) * inverseR + wj.dot(uj.cross(rij)) * inverseR;
        const double cDot = (wi - wj).dot(ui.cross(uj));
        return {t.U, t.Ur * rDot + t.Ua * aDot + t.Ub * bDot + t.Uc * cDot};
    }
    double energy(const Vec3& rij, const Vec3& ui, const Vec3& uj) const {
        return terms<false>(rij, ui, uj).U;
    }

    /// −ε_max, the bottom of the deepest well (see epsilonMax()): exact.
    double minimumEnergy() const { return -epsilonMax(); }
    /// A lower bound of U over all orientations at centre distance r: x lies in
    /// [r − (σ_max − σ0), r − (σ_min − σ0)], where LJ₁ is lowest at its minimum 2^(1/6)σ0 or else
    /// at the end nearer to it; below zero the deepest ε scales it, above zero the shallowest.
    /// Beyond the well (x's lower end past 2^(1/6)σ0) it rises with r, as the reach bisection
    /// needs.
    double lowestEnergyAt(double r) const {
        const double bottom = sigma * std::pow(2.0, 1.0 / 6.0);
        const double x = std::clamp(bottom, r - (sigmaMax() - sigma), r - (sigmaMin() - sigma));
        if (!(x > 0.0)) return std::numeric_limits<double>::infinity(); // cores overlap at any u
        // LJ₁(x) < 0 beyond σ0: there the deepest well bounds U from below, inside the shallowest.
        return detail::lennardJones(x, x > sigma ? epsilonMax() : epsilonMin(), sigma).U;
    }
    /// An upper bound of the centre distance at which U = u for some orientation, 0 if U never
    /// reaches u. U = ε LJ₁(x) with ε ≤ ε_max: for u < 0 that needs LJ₁(x) ≤ u/ε_max, so x is at
    /// most the outer root of LJ₁ = u/ε_max; for u ≥ 0 it needs LJ₁(x) ≥ u/ε_max, so x is at most
    /// the wall's root (σ0 for u = 0). Then r = x + σ − σ0 ≤ x + σ_max − σ0. At u = −ε_max the
    /// bottom of the deepest well is still touched (at x = 2^(1/6)σ0), so the answer is not 0 there
    /// (unlike LJPotential's). For u < 0 and κ' ≥ 1, parallel axes side by side reach to within
    /// σ_max − σ0 of the bound (their σ is σ0); u = 0 is reached exactly at σ_max.
    double reachDistance(double u) const {
        const double deepest = epsilonMax();
        if (u < -deepest) return 0.0;
        const detail::RadialRoots x = detail::lennardJonesRoots(u / deepest, 1.0, sigma);
        return (u < 0.0 ? x.outer : x.inner) + (sigmaMax() - sigma);
    }

    /// The range of U over every configuration whose centre separation differs from rij by at
    /// most `shift` (Å) and whose axes are turned by at most turnI, turnJ (rad) from ui, uj
    /// (core/pair_potential.hpp RangeBounded; the DMD hold screen's bound). r lies within shift
    /// of r0; r̂ turns by at most asin(shift/r0), so a = r̂·u_i moves by at most that plus turnI
    /// (|Δ(r̂·u)| ≤ |Δr̂| + |Δu|, a chord no longer than its arc), b likewise, c by turnI + turnJ.
    /// Over that box of (r, a, b, c) interval arithmetic bounds H(χ), H(χ'), c² and so σ, ε1,
    /// ε2 (each monotone in its argument), each clipped to its range over all configurations;
    /// then x = r − σ + σ0 and U = ε LJ₁(x) take their extremes at the ends (LJ₁'s least at its
    /// minimum when inside). +∞ above when the cores could overlap.
    EnergyRange energyRange(const Vec3& rij, const Vec3& ui, const Vec3& uj, double shift,
                            double turnI, double turnJ) const {
        constexpr double inf = std::numeric_limits<double>::infinity();
        const double r0 = rij.norm();
        if (!(shift < r0)) return {minimumEnergy(), inf};
        const Vec3 rHat = rij / r0;
        const double tilt = std::asin(shift / r0);
        const auto around = [](double v, double d) {
            return Interval{std::max(-1.0, v - d), std::min(1.0, v + d)};
        };
        const Interval a = around(rHat.dot(ui), tilt + turnI);
        const Interval b = around(rHat.dot(uj), tilt + turnJ);
        const Interval c = around(ui.dot(uj), turnI + turnJ);
        const Interval hs = overlapRange(chi(), a, b, c);
        const Interval he = overlapRange(chiPrime(), a, b, c);
        // σ = σ0 (1 − H)^(−1/2), rising with H
        const auto range = [&](double h) { return h < 1.0 ? sigma / std::sqrt(1.0 - h) : inf; };
        const double sigmaLo = std::clamp(range(hs.lo), sigmaMin(), sigmaMax());
        const double sigmaHi = std::clamp(range(hs.hi), sigmaMin(), sigmaMax());
        // ε1 = (1 − χ²c²)^(−ν/2), rising with c²; ε2 = 1 − H(χ'), falling with it
        const double chiS = chi();
        const Interval c2 = c.squared();
        const double e1Lo = power(1.0 - chiS * chiS * c2.lo, -0.5 * nu);
        const double e1Hi = power(1.0 - chiS * chiS * c2.hi, -0.5 * nu);
        const double e2Floor = std::min(1.0, 1.0 / kappaPrime),
                     e2Ceiling = std::max(1.0, 1.0 / kappaPrime);
        const double e2Lo = std::clamp(power(std::max(0.0, 1.0 - he.hi), mu), e2Floor, e2Ceiling);
        const double e2Hi = std::clamp(power(std::max(0.0, 1.0 - he.lo), mu), e2Floor, e2Ceiling);
        const double depthLo = std::max(epsilonMin(), epsilon * e1Lo * e2Lo);
        const double depthHi = std::min(epsilonMax(), epsilon * e1Hi * e2Hi);
        const double xLo = r0 - shift - sigmaHi + sigma, xHi = r0 + shift - sigmaLo + sigma;
        const auto lj1 = [&](double x) { return detail::lennardJones(x, 1.0, sigma).U; };
        constexpr double twoToTheSixth = 1.122462048309373; // 2^(1/6): no pow() per bound
        const double bottom = sigma * twoToTheSixth;
        const double least = xLo > 0.0 ? lj1(std::clamp(bottom, xLo, xHi)) : -1.0;
        const double most = xLo > 0.0 ? std::max(lj1(xLo), lj1(xHi)) : inf;
        return {least < 0.0 ? depthHi * least : depthLo * least,
                most > 0.0 ? (std::isfinite(most) ? depthHi * most : inf) : depthLo * most};
    }

private:
    /// A closed interval of reals, with the few operations energyRange() needs.
    struct Interval {
        double lo, hi;
        Interval operator+(const Interval& o) const { return {lo + o.lo, hi + o.hi}; }
        Interval operator-(const Interval& o) const { return {lo - o.hi, hi - o.lo}; }
        Interval squared() const {
            const double m = std::max(lo * lo, hi * hi);
            return {lo <= 0.0 && hi >= 0.0 ? 0.0 : std::min(lo * lo, hi * hi), m};
        }
        /// this / o for a positive o
        Interval over(const Interval& o) const {
            const double a = lo / o.lo, b = lo / o.hi, c = hi / o.lo, d = hi / o.hi;
            return {std::min({a, b, c, d}), std::max({a, b, c, d})};
        }
        Interval scaled(double k) const {
            return k >= 0.0 ? Interval{k * lo, k * hi} : Interval{k * hi, k * lo};
        }
    };
    /// H(χ; a, b, c) over a box of (a, b, c): (χ/2)[(a+b)²/(1+χc) + (a−b)²/(1−χc)], where both
    /// denominators are positive (|χ| < 1, |c| ≤ 1).
    static Interval overlapRange(double chi, const Interval& a, const Interval& b,
                                 const Interval& c) {
        const Interval plus = Interval{1.0, 1.0} + c.scaled(chi);
        const Interval minus = Interval{1.0, 1.0} - c.scaled(chi);
        const Interval sum = (a + b).squared().over(plus), diff = (a - b).squared().over(minus);
        return (sum + diff).scaled(0.5 * chi);
    }

    /// x^e, with the usual exponents 0, 1, 2 and −1/2 spared the call to pow.
    static double power(double x, double e) {
        if (e == 1.0) return x;
        if (e == 2.0) return x * x;
        if (e == 0.0) return 1.0;
        if (e == -0.5) return 1.0 / std::sqrt(x);
        return std::pow(x, e);
    }

    /// H(χ; a, b, c) and its partials H_a, H_b, H_c (header formulas).
    struct Overlap {
        double H, Ha, Hb, Hc;
    };
    static Overlap overlap(double chi, double a, double b, double c) {
        const double sum = a + b, diff = a - b;
        const double p = sum / (1.0 + chi * c), m = diff / (1.0 - chi * c);
        return {0.5 * chi * (sum * p + diff * m), chi * (p + m), chi * (p - m),
                -0.5 * chi * chi * (p * p - m * m)};
    }

    /// What evaluate(), energyRate() and energy() share: U through the same operations in all
    /// three (so that they agree bit for bit) and, if asked, the partials U_r, U_a, U_b, U_c.
    struct Terms {
        double r, a, b, c, U;
        bool finite;
        double Ur = 0.0, Ua = 0.0, Ub = 0.0, Uc = 0.0;
    };
    template <bool partials> Terms terms(const Vec3& rij, const Vec3& ui, const Vec3& uj) const {
        const double r = rij.norm(), inverseR = 1.0 / r;
        const double a = rij.dot(ui) * inverseR, b = rij.dot(uj) * inverseR, c = ui.dot(uj);
        const double chiS = chi(), chiE = chiPrime();
        const Overlap s = overlap(chiS, a, b, c), e = overlap(chiE, a, b, c);
        const double g = 1.0 / (1.0 - s.H); // (σ/σ0)²
        const double range = sigma * std::sqrt(g);
        const double cc = chiS * c, w = 1.0 - cc * cc; // ε1 = w^(−1/2)
        const double e2 = 1.0 - e.H;
        const double depth = epsilon * power(w, -0.5 * nu) * power(e2, mu);
        // r − (σ − σ0), not r − σ + σ0: where σ = σ0 (spheres, κ = 1) x is r to the bit.
        const double x = r - (range - sigma);
        if (!(x > 0.0)) // overlapping cores, or r = 0 (NaN): see the header
            return {r, a, b, c, std::numeric_limits<double>::infinity(), false};
        const detail::Radial lj = detail::lennardJones(x, depth, sigma); // U and U_r = ε LJ₁'
        Terms t{r, a, b, c, lj.U, true};
        if constexpr (partials) {
            const double halfRangeG = 0.5 * range * g;         // ∂σ/∂q = (σ/2) g H_q
            const double muOverE2 = mu == 0.0 ? 0.0 : mu / e2; // μ = 0: no ε2 dependence at all
            t.Ur = lj.dUdx;
            t.Ua = -lj.U * muOverE2 * e.Ha - lj.dUdx * halfRangeG * s.Ha;
            t.Ub = -lj.U * muOverE2 * e.Hb - lj.dUdx * halfRangeG * s.Hb;
            t.Uc = lj.U * (nu * chiS * cc / w - muOverE2 * e.Hc) - lj.dUdx * halfRangeG * s.Hc;
        }
        return t;
    }
};

} // namespace terrace
