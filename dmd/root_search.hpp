#pragma once
// Adaptive search for the first time a pair leaves its terrace (paper sec. 3, "Finding Interaction
// Event Times"; DESIGN.md "Finding event times").
//
// The pair is on the terrace (lower, upper); the indicators are f = U(τ) − lower and upper − U(τ),
// with f and its rate ḟ = ±dU/dt (paper eq. 13) available at every grid point. Starting from a
// known sample the search
//   1. places the next grid point at the linear prediction of the level that dU/dt heads to, plus
//      a nudge δt (never beyond the largest step Δt, nor the end of the window);
//   2. fits the cubic Hermite interpolant f_c(τ) = f₁ + ḟ₁τ + ατ² + βτ³ (paper eq. 14) through the
//      two latest samples and counts its extrema in between (roots of ḟ_c);
//   3. where f_c has a minimum (maximum) within `grazeWindow` of the lower (upper) level, finds the
//      true extremum by Brent minimisation — a dip through the level there is a grazing event;
//   4. once a sign change is bracketed, refines the root by safeguarded Newton (bisection when the
//      Newton step leaves the bracket) and returns the time on the far side of the level.
// Extrema are examined in time order, before the end point, so the earliest crossing wins.
//
// Right after an event the pair sits on a level (within round-off of U). The Bannerman rule
// (Bannerman, Lue & Woodcock, "Stable algorithm for event detection in event-driven particle
// dynamics", 2013) decides: on or past a level and moving outwards → the event is now; moving
// inwards → no event at that level now (the start is clamped onto the level, and a later crossing
// of the same level is bracketed only after the maximum of f in between, so τ = 0 is never returned
// again). Times are relative to the caller's reference (time unit 100 fs); energies kJ/mol.
#include <algorithm>
#include <array>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <cstdint>
#include <limits>

namespace terrace::dmd {

struct PairSample {
    double t = 0.0;
    double U = 0.0;
    double dUdt = 0.0;
};

struct SearchSettings {
    double maxStep = 0.04;    // Δt, the largest grid step (time units; paper: 4 fs)
    double nudge = 0.00125;   // δt added to a linear prediction
    double grazeWindow = 0.5; // kJ/mol: extrema of f_c closer than this to a level are examined
    double levelTolerance = 1e-12; // kJ/mol: |U − level| below this counts as on the level
};

enum class ExitSide : std::int8_t { None = 0, Lower = -1, Upper = +1 };

struct SearchResult {
    ExitSide side = ExitSide::None;
    double t = 0.0; // the event time when side != None
    PairSample end; // the last sample when side == None (the window was exhausted)
    int evaluations = 0;
};

namespace detail {

/// The cubic Hermite interpolant between two samples (paper eq. 14).
struct HermiteCubic {
    double t0, h, f0, d0, alpha, beta;
    HermiteCubic(const PairSample& a, const PairSample& b)
        : t0(a.t), h(b.t - a.t), f0(a.U), d0(a.dUdt) {
        alpha = (3.0 * (b.U - a.U) - (2.0 * a.dUdt + b.dUdt) * h) / (h * h);
        beta = (2.0 * (a.U - b.U) + (a.dUdt + b.dUdt) * h) / (h * h * h);
    }
    double value(double s) const { return f0 + s * (d0 + s * (alpha + s * beta)); }
    double curvature(double s) const { return 2.0 * alpha + 6.0 * beta * s; }
    /// Roots of the derivative strictly inside (0, h), increasing; returns how many.
    int extrema(std::array<double, 2>& s) const {
        const double A = 3.0 * beta, B = 2.0 * alpha, C = d0;
        int n = 0;
        auto keep = [&](double x) {
            if (x > 0.0 && x < h) s[n++] = x;
        };
        if (A == 0.0) {
            if (B != 0.0) keep(-C / B);
        } else {
            const double disc = B * B - 4.0 * A * C;
            if (disc < 0.0) return 0;
            const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
            if (q != 0.0) keep(C / q);
            keep(q / A);
            if (n == 2 && s[0] > s[1]) std::swap(s[0], s[1]);
        }
        return n;
    }
};

/// Indicator for one side: positive inside the terrace.
inline double inside(const PairSample& p, ExitSide side, double level) {
    return side == ExitSide::Lower ? p.U - level : level - p.U;
}
inline double insideRate(const PairSample& p, ExitSide side) {
    return side == ExitSide::Lower ? p.dUdt : -p.dUdt;
}

/// Brent minimisation of ±U on [l, r]; returns the sample at the extremum found.
template <class Eval>
PairSample extremum(Eval& eval, double l, double r, bool minimum, int& evaluations) {
    PairSample best;
    double bestValue = std::numeric_limits<double>::infinity();
    auto g = [&](double t) {
        const PairSample p = eval(t);
        ++evaluations;
        const double v = minimum ? p.U : -p.U;
        if (v < bestValue) bestValue = v, best = p;
        return v;
    };
    std::uintmax_t maxIterations = 60;
    boost::math::tools::brent_find_minima(g, l, r, std::numeric_limits<double>::digits / 2,
                                          maxIterations);
    return best;
}

/// Root of the indicator between a (inside, ≥ 0) and b (outside, < 0): safeguarded Newton.
/// Returns the time on the outside of the level, so that the event finds the pair past it.
template <class Eval>
double refineRoot(Eval& eval, PairSample a, PairSample b, ExitSide side, double level,
                  double tolerance, int& evaluations) {
    if (inside(a, side, level) <= 0.0) {
        // a sits on the level (the start of a search): the root lies beyond the maximum of f.
        const PairSample top = extremum(eval, a.t, b.t, side == ExitSide::Upper, evaluations);
        if (inside(top, side, level) <= 0.0) return top.t;
        a = top;
    }
    double fa = inside(a, side, level), fb = inside(b, side, level);
    double lo = a.t, hi = b.t;
    double x = lo + fa / (fa - fb) * (hi - lo); // regula falsi start
    double step = hi - lo, previousStep = step;
    for (int iteration = 0; iteration < 100; ++iteration) {
        const PairSample p = eval(x);
        ++evaluations;
        const double f = inside(p, side, level);
        if (f > 0.0) {
            lo = x;
        } else {
            hi = x;
            if (f == 0.0) break;
        }
        if (hi - lo <= 2.0 * tolerance) break;
        const double rate = insideRate(p, side);
        const double newton = rate != 0.0 ? x - f / rate : lo - 1.0;
        if (!(newton > lo && newton < hi) || std::abs(2.0 * f) > std::abs(previousStep * rate)) {
            previousStep = step;
            step = 0.5 * (hi - lo);
            x = lo + step;
        } else {
            previousStep = step;
            step = f / rate;
            // Newton converges from one side; step just past the root to close the bracket.
            x = std::abs(step) < tolerance ? std::min(newton + tolerance, 0.5 * (newton + hi))
                                           : newton;
        }
        if (!(x > lo && x < hi)) break; // the bracket cannot be split any further
    }
    return hi;
}

} // namespace detail

/// First time in (start.t, tEnd] at which U leaves (lower, upper); eval(τ) → PairSample.
/// lower may be −∞ and upper +∞ (outermost explicit terraces). afterEvent: the pair's event was
/// just resolved at the start, and the collision rule has set it moving into this terrace; the
/// sign of dU/dt recomputed here may disagree by round-off when it is ~0, so no event is taken
/// at the start (a stuck loop of zero-time events otherwise).
template <class Eval>
SearchResult findTerraceExit(Eval&& eval, PairSample a, double lower, double upper, double tEnd,
                             const SearchSettings& s, bool afterEvent = false) {
    SearchResult result;
    // Bannerman rule at the start point; "on" a level means within the round-off of U.
    const double near = s.levelTolerance;
    if (!afterEvent) {
        if (a.U <= lower + near && a.dUdt < 0.0) return {ExitSide::Lower, a.t, a, 0};
        if (a.U >= upper - near && a.dUdt > 0.0) return {ExitSide::Upper, a.t, a, 0};
    }
    // On a level and moving inwards (or just resolved there): exactly on it, so that the root
    // refinement looks for the excursion into the terrace first and never returns the start.
    if (a.U <= lower + near) a.U = lower;
    if (a.U >= upper - near) a.U = upper;
    const double tolerance = 1e-13 * s.maxStep;

    auto bracketed = [&](const PairSample& from, const PairSample& to, ExitSide side) {
        const double level = side == ExitSide::Lower ? lower : upper;
        result.side = side;
        result.t = detail::refineRoot(eval, from, to, side, level, tolerance, result.evaluations);
        return result;
    };

    while (a.t < tEnd) {
        double h = s.maxStep;
        if (a.dUdt < 0.0 && std::isfinite(lower))
            h = std::min(h, (a.U - lower) / -a.dUdt + s.nudge);
        else if (a.dUdt > 0.0 && std::isfinite(upper))
            h = std::min(h, (upper - a.U) / a.dUdt + s.nudge);
        const double tb = std::min(a.t + h, tEnd);
        if (!(tb > a.t)) break; // the window cannot be split any further
        const PairSample b = eval(tb);
        ++result.evaluations;

        const detail::HermiteCubic cubic(a, b);
        std::array<double, 2> ext{};
        const int n = cubic.extrema(ext);
        for (int e = 0; e < n; ++e) {
            const double l = a.t + (e == 0 ? 0.0 : ext[0]);
            const double r = a.t + (e + 1 < n ? ext[1] : cubic.h);
            const double predicted = cubic.value(ext[e]);
            if (cubic.curvature(ext[e]) > 0.0) {
                if (std::isfinite(lower) && predicted - lower < s.grazeWindow) {
                    const PairSample m = detail::extremum(eval, l, r, true, result.evaluations);
                    if (m.U < lower) return bracketed(a, m, ExitSide::Lower);
                }
            } else if (std::isfinite(upper) && upper - predicted < s.grazeWindow) {
                const PairSample m = detail::extremum(eval, l, r, false, result.evaluations);
                if (m.U > upper) return bracketed(a, m, ExitSide::Upper);
            }
        }
        if (b.U < lower) return bracketed(a, b, ExitSide::Lower);
        if (b.U > upper) return bracketed(a, b, ExitSide::Upper);
        a = b;
    }
    result.end = a;
    return result;
}

} // namespace terrace::dmd
