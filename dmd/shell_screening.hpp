#pragma once
// Screening of a pair search with the interaction range (paper, "Implementation of the
// event-driven simulation"; Hernández de la Peña et al., J. Chem. Phys. 126, 074105 (2007)).
// Centres of mass fly on straight lines, r_ij(τ) = r0 + w τ with w = v_i − v_j, so the times at
// which |r_ij(τ)| = r_m are the roots of the quadratic
//     (w·w) τ² + 2 (r0·w) τ + (r0·r0 − r_m²) = 0.
// A pair can change terrace only while |r_ij| ≤ r_m, i.e. inside [enter, exit]. Roots are taken
// in cancellation-free form. Units: Å, time unit 100 fs.
#include "core/vec.hpp"
#include <cmath>
#include <limits>

namespace terrace::dmd {

struct ShellWindow {
    double enter = std::numeric_limits<double>::infinity(); // ≥ 0
    double exit = std::numeric_limits<double>::infinity();  // may be +∞ (no relative motion)
    bool empty() const { return !(enter < std::numeric_limits<double>::infinity()); }
};

/// The part of τ ≥ 0 during which |r0 + wτ| ≤ rm.
inline ShellWindow shellWindow(const Vec3& r0, const Vec3& w, double rm) {
    const double a = w.squaredNorm();
    const double b = r0.dot(w);
    const double c = r0.squaredNorm() - rm * rm;
    ShellWindow win;
    if (c <= 0.0) { // inside now
        win.enter = 0.0;
        if (a == 0.0) return win;
        const double root = std::sqrt(b * b - a * c);
        win.exit = b >= 0.0 ? (root > 0.0 || c < 0.0 ? -c / (b + root) : 0.0) : (root - b) / a;
        return win;
    }
    if (b >= 0.0 || a == 0.0) return win; // outside and not approaching
    const double disc = b * b - a * c;
    if (disc < 0.0) return win; // the line passes outside the shell
    const double root = std::sqrt(disc);
    win.enter = c / (root - b);
    win.exit = (root - b) / a;
    return win;
}

} // namespace terrace::dmd
