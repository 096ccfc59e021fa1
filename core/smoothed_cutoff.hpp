#pragma once
// Smoothed cutoff of a pair potential (paper eqs. 22-23, "Comparison between standard molecular
// dynamics and event-driven simulations"): U_smooth = g(r) U(r_ij, s_i, s_j) with r = |r_ij| and
//     g(r) = 1                                          r < r_l
//          = (r_u - r)² (r_u - 3 r_l + 2r) / (r_u - r_l)³   r_l <= r <= r_u
//          = 0                                          r > r_u
//     g'(r) = -6 (r_u - r)(r - r_l) / (r_u - r_l)³      on [r_l, r_u], 0 elsewhere.
// g and g' are continuous at both ends, so force and torque are continuous everywhere. Because g
// depends on the centre distance only, the torques are g τ and the force gains one term:
//     F_smooth = g F - U g'(r) r̂_ij,   τ_smooth = g τ   (force on i, r̂_ij = r_ij / r).
// r_l = r_u = +∞ is no cutoff at all (g = 1 everywhere): the bare potential, which the paper's DMD
// terraces out to r_m (core/smoothed_potential.hpp).
// Units: distances Å, energies kJ/mol (those of the wrapped potential).
#include "core/pair_potential.hpp"
#include <cmath>
#include <limits>

namespace terrace {

class SmoothedCutoff {
public:
    SmoothedCutoff() = default;
    SmoothedCutoff(double rl, double ru)
        : rl_(rl), ru_(ru),
          invWidthCubed_(std::isfinite(rl) ? 1.0 / ((ru - rl) * (ru - rl) * (ru - rl)) : 0.0) {}
    /// No cutoff: g = 1 at every distance.
    static SmoothedCutoff none() {
        return {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    }
    bool isFinite() const { return std::isfinite(ru_); }
    bool operator==(const SmoothedCutoff&) const = default;

    double inner() const { return rl_; } // r_l, Å: the potential is untouched inside
    double outer() const { return ru_; } // r_u, Å: zero beyond

    /// g(r): 1 inside r_l, the cubic switch on [r_l, r_u], 0 beyond r_u.
    double switching(double r) const {
        if (r <= rl_) return 1.0;
        if (r >= ru_) return 0.0;
        const double a = ru_ - r;
        return a * a * (ru_ - 3.0 * rl_ + 2.0 * r) * invWidthCubed_;
    }
    /// g'(r) = dg/dr.
    double switchingSlope(double r) const {
        if (r <= rl_ || r >= ru_) return 0.0;
        return -6.0 * (ru_ - r) * (r - rl_) * invWidthCubed_;
    }

private:
    // 1/(r_u - r_l)³, computed once: the pair loop would otherwise divide twice per pair in the
    // switch (a division inside a branch is not hoisted out of the loop).
    double rl_ = 0.0, ru_ = 0.0, invWidthCubed_ = 0.0;
};

/// The smoothed pair interaction from the raw one at separation rij (r = |rij| > 0, Å).
/// Valid for r < r_u; callers skip pairs beyond r_u, where every term is zero.
inline PairForce smoothed(PairForce f, const Vec3& rij, double r, const SmoothedCutoff& cut) {
    if (r <= cut.inner()) return f; // the common case in a dense liquid: nothing to do
    // Scaled in place: a fresh PairForce would zero three vectors first (out-of-line at -O2).
    const double g = cut.switching(r);
    f.F = g * f.F - (f.U * cut.switchingSlope(r) / r) * rij;
    f.tauI *= g;
    f.tauJ *= g;
    f.U *= g;
    return f;
}

} // namespace terrace
