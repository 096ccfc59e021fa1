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
//   3. where f_c has a minimum (maximum) within `grazeWindow` of the lower (upper) level, probes
//      the true extremum with successive Hermite cubics (Brent's minimisation as a fallback) — a
//      dip through the level there is a grazing event;
//   4. once a sign change is bracketed, refines the root by sampling at the crossing of the
//      Hermite cubic through the bracket, and returns a time just on the far side of the level.
// Both refinements stop as soon as the question is answered (the extremum clears the level by
// more than the cubics' own error, the root is pinned to the time tolerance), because each sample
// of U is the search's cost; bisection-safeguarded Newton and a full Brent minimisation take
// several times as many samples (docs/PERFORMANCE.md).
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
        const double inverse = 1.0 / h, inverse2 = inverse * inverse; // one division, not two
        alpha = (3.0 * (b.U - a.U) - (2.0 * a.dUdt + b.dUdt) * h) * inverse2;
        beta = (2.0 * (a.U - b.U) + (a.dUdt + b.dUdt) * h) * inverse2 * inverse;
    }
    double value(double s) const { return f0 + s * (d0 + s * (alpha + s * beta)); }
    double curvature(double s) const { return 2.0 * alpha + 6.0 * beta * s; }
    double slope(double s) const { return d0 + s * (2.0 * alpha + 3.0 * beta * s); }
    /// A zero of the interpolant in [0, h] when its end values differ in sign (f₀ > 0 here):
    /// Newton's method kept inside a shrinking bracket (false position, then bisection, where it
    /// steps out). A point where the cubic is exactly 0 is the answer: taken as a bracket end,
    /// it left Newton no room, and bisection then crept back to it over ~40 halvings. No sample
    /// is taken; this only places the next one.
    double crossing() const {
        double lo = 0.0, hi = h, fLo = f0, fHi = value(h);
        double x = fLo / (fLo - fHi) * h;
        for (int k = 0; k < 48; ++k) {
            const double f = value(x);
            if (f == 0.0) return x;
            if (f > 0.0)
                lo = x, fLo = f;
            else
                hi = x, fHi = f;
            const double d = slope(x);
            double next = d != 0.0 ? x - f / d : lo;
            if (!(next > lo && next < hi)) next = lo + fLo / (fLo - fHi) * (hi - lo);
            if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
            if (std::abs(next - x) <= 1e-15 * h) return next;
            x = next;
        }
        return x;
    }
    /// Roots of the derivative strictly inside (0, h), increasing; returns how many.
    int extrema(std::array<double, 2>& s) const {
        const double A = 3.0 * beta, B = 2.0 * alpha, C = d0;
        // The derivative A s² + B s + C has the same sign at both ends (checked without a
        // square root): it vanishes in between only if its vertex lies inside and crosses zero.
        const double d1 = C + h * (B + A * h);
        if ((C > 0.0 && d1 > 0.0) || (C < 0.0 && d1 < 0.0)) {
            if (A == 0.0) return 0;
            const double vertex = -B / (2.0 * A);
            if (!(vertex > 0.0 && vertex < h)) return 0;
            const double dv = C + vertex * (B + A * vertex);
            if ((C > 0.0 && dv > 0.0) || (C < 0.0 && dv < 0.0)) return 0;
        }
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

/// A sample seen through g = sign·(U − level): the extremum probe below always looks for a minimum
/// of g and for g < 0 ("past the level").
struct Signed {
    double sign, level;
    PairSample operator()(const PairSample& p) const {
        return {p.t, sign * (p.U - level), sign * p.dUdt};
    }
};

/// Brent minimisation of g on [l, r]: the fallback of probeExtremum for an indicator the cubics
/// do not describe (no extremum of the kind sought, or slow convergence).
template <class Eval>
PairSample brentMinimum(Eval& eval, const Signed& g, double l, double r, int& evaluations) {
    PairSample best;
    double bestValue = std::numeric_limits<double>::infinity();
    auto value = [&](double t) {
        const PairSample p = eval(t);
        ++evaluations;
        const double v = g(p).U;
        if (v < bestValue) bestValue = v, best = p;
        return v;
    };
    std::uintmax_t maxIterations = 60;
    boost::math::tools::brent_find_minima(value, l, r, std::numeric_limits<double>::digits / 2,
                                          maxIterations);
    return best;
}

/// Probes the minimum of g = sign·(U − level) between the samples l and r, where their cubic
/// Hermite interpolant has one: a sample is taken at the interpolant's minimum, the interpolant
/// is refitted on the half that still holds the minimum (the sign of ġ there says which), and so
/// on — the interpolant's error falls as the fourth power of the interval, so the predicted
/// minimum settles within a few samples (a cubic-interpolation line search; Nocedal & Wright,
/// "Numerical Optimization", sec. 3.5). It stops at the first sample with g < 0 (returned: the
/// level is crossed there), when the refitted minimum stays above the level by more than
/// `safety` times its change since the previous fit plus `clearance` (no crossing: the sample
/// with the least g is returned), or when the minimum is pinned down to `tolerance` in time.
/// Brent's method takes over if the interpolants lose the minimum.
template <class Eval>
PairSample probeExtremum(Eval& eval, PairSample l, PairSample r, const Signed& g, double clearance,
                         double tolerance, int& evaluations) {
    constexpr double safety = 4.0;
    constexpr int maxProbes = 10;
    PairSample best = g(l).U <= g(r).U ? l : r;
    double previous = std::numeric_limits<double>::quiet_NaN();
    for (int probe = 0; probe < maxProbes; ++probe) {
        const HermiteCubic cubic(g(l), g(r));
        std::array<double, 2> ext{};
        const int n = cubic.extrema(ext);
        int k = 0;
        while (k < n && cubic.curvature(ext[k]) <= 0.0)
            ++k;
        if (k == n) break; // no minimum left between the samples: let Brent look
        const double predicted = cubic.value(ext[k]);
        if (!std::isnan(previous) &&
            predicted > safety * std::abs(predicted - previous) + clearance)
            return best;
        previous = predicted;
        const double x = l.t + ext[k];
        if (x - l.t <= tolerance || r.t - x <= tolerance) return best; // pinned down
        const PairSample p = eval(x);
        ++evaluations;
        const PairSample gp = g(p);
        if (gp.U < g(best).U) best = p;
        if (gp.U < 0.0) return p;
        if (gp.dUdt < 0.0)
            l = p; // g still falling: the minimum lies to the right
        else
            r = p;
    }
    const PairSample b = brentMinimum(eval, g, l.t, r.t, evaluations);
    return g(b).U < g(best).U ? b : best;
}

/// Root of the indicator between a (inside, ≥ 0) and b (outside, < 0), both samples. Each step
/// samples at the crossing of the cubic Hermite interpolant through the bracket (its error falls
/// as h⁴), moved `tolerance` outwards so that the sample lands just past the root once the
/// interpolant has it to round-off, and keeps the half that holds the sign change. Stops at an
/// outside sample whose linear distance to the root, |g/ġ|, is within 2·tolerance, or when the
/// bracket is that narrow; returns the time of the outer end, so that the event finds the pair
/// past the level. `onLevel`: the distance from the level within which U counts as on it.
template <class Eval>
double refineRoot(Eval& eval, PairSample a, PairSample b, ExitSide side, double level,
                  double tolerance, int& evaluations, double onLevel = 0.0) {
    // In the signed view g, the indicator (positive inside the terrace): g(a) ≥ 0, g(b) < 0.
    Signed g{side == ExitSide::Lower ? 1.0 : -1.0, level};
    if (g(a).U <= 0.0) {
        // a sits on the level (the start of a search): the root lies beyond the maximum of the
        // indicator, i.e. the minimum of −g.
        const Signed flipped{-g.sign, level};
        const PairSample top = probeExtremum(eval, a, b, flipped, 0.0, tolerance, evaluations);
        if (g(top).U > onLevel) {
            a = top;
        } else {
            // No excursion into the terrace beyond the level's tolerance: the pair meets the level
            // at a grazing or zero rate, and whether it dips inside lies below what U resolves.
            // Returning the start, or a sample in the round-off about it, leaves a rate that may
            // still point inwards there: the collision rule then has nothing to reverse (S = 0),
            // and the unchanged pair is found leaving at that instant again, a zero-time loop. Its
            // exit is instead where it passes half the tolerance beyond the level, with its rate
            // outwards and the event finding it on the level again. a, clamped onto the level, is
            // sampled afresh: it can sit just past that mark, as after a reflection made there.
            Signed beyond{g.sign, level - g.sign * (0.5 * onLevel)};
            a = eval(a.t);
            ++evaluations;
            if (beyond(a).U <= 0.0) {
                // Back inside the mark before leaving again, or, should it never come back (it
                // was reflected at a zero rate), the same distance on from where it turns.
                const Signed inside{-beyond.sign, beyond.level};
                a = probeExtremum(eval, a, b, inside, 0.0, tolerance, evaluations);
                if (beyond(a).U <= 0.0) beyond.level = a.U - g.sign * (0.5 * onLevel);
            }
            if (!(beyond(b).U < 0.0)) return b.t; // b is no farther out: the exit is there
            g = beyond;
            // Halve the bracket until its inner end moves outwards: from a sample still moving
            // in, where the indicator rises to its hump, the cubics' crossing creeps (it steps
            // by false position a round-off at a time).
            for (int k = 0; k < 64 && g(a).dUdt > 0.0 && b.t - a.t > 2.0 * tolerance; ++k) {
                const PairSample m = eval(0.5 * (a.t + b.t));
                ++evaluations;
                (g(m).U > 0.0 ? a : b) = m;
            }
        }
    }
    PairSample lo = g(a), hi = g(b);
    double outer = b.t;
    bool pinned = false;
    for (int iteration = 0; iteration < 64 && !(pinned = hi.t - lo.t <= 2.0 * tolerance);
         ++iteration) {
        double x = lo.t + HermiteCubic(lo, hi).crossing() + tolerance;
        if (!(x > lo.t && x < hi.t)) x = 0.5 * (lo.t + hi.t);
        const PairSample p = g(eval(x));
        ++evaluations;
        if (p.U > 0.0) {
            lo = p;
            continue;
        }
        hi = p;
        outer = x;
        if ((pinned = -p.U <= 2.0 * tolerance * std::abs(p.dUdt))) break;
    }
    // Not pinned down: the cubics' crossings crept from an inner end still moving in, below a
    // hump round-off hardly resolves (a pair leaving a level at a nearly grazing rate, turning back
    // within a few 1e-10 of it). The outer end would be the window's end, long after the crossing,
    // an event missed: bisection finishes the bracket instead.
    for (int k = 0; k < 64 && !pinned; ++k) {
        const double x = 0.5 * (lo.t + hi.t);
        const PairSample p = g(eval(x));
        ++evaluations;
        (p.U > 0.0 ? lo : hi) = p;
        if (p.U <= 0.0) outer = x;
        pinned = hi.t - lo.t <= 2.0 * tolerance ||
                 (p.U <= 0.0 && -p.U <= 2.0 * tolerance * std::abs(p.dUdt));
    }
    return outer;
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
    // Samples that stay within the tolerance of that level count as on it too, until one leaves
    // it: over a window shorter than round-off can resolve (a pair leaving r_m just as it leaves
    // a level at r_m, which is where r_m lies when the lowest terrace holds the whole tail) a
    // sample beyond the level by round-off alone would put the pair back across at once, and
    // again after that, a zero-time loop.
    ExitSide onLevel = ExitSide::None;
    if (a.U <= lower + near) a.U = lower, onLevel = ExitSide::Lower;
    if (a.U >= upper - near) a.U = upper, onLevel = ExitSide::Upper;
    auto stillOnLevel = [&](PairSample& p) {
        const double level = onLevel == ExitSide::Lower ? lower : upper;
        if (onLevel == ExitSide::None || !(std::abs(p.U - level) <= near)) return false;
        p.U = level;
        return true;
    };
    const double tolerance = 1e-13 * s.maxStep;

    auto bracketed = [&](const PairSample& from, const PairSample& to, ExitSide side) {
        const double level = side == ExitSide::Lower ? lower : upper;
        result.side = side;
        result.t =
            detail::refineRoot(eval, from, to, side, level, tolerance, result.evaluations, near);
        return result;
    };

    // The cubic strays from the chord between two samples by at most (4/27)·h·(|ḟ₁ − s| +
    // |ḟ₂ − s|), s the chord's slope (its Hermite basis functions peak at 4/27).
    const auto strayOf = [](const PairSample& p, const PairSample& q) {
        const double rise = q.U - p.U, h = q.t - p.t;
        return 4.0 / 27.0 * (std::abs(h * p.dUdt - rise) + std::abs(h * q.dUdt - rise));
    };
    // A sample closer to a level than the cubic's own bend, and moving away from it, may sit
    // next to a turn of U back across that level that the cubic does not show: U rising from
    // just above the lower level can dip through it and out again within one step while the
    // cubic through the step's ends stays monotone (rods at ρ* 0.7, T* 10, ΔV = kT/8: a dip of
    // 4e-5 kJ/mol below a level 6.5e-5 below the start, 0.6 to 1.4 fs on, in a 3.2 fs step whose
    // pair turns 0.5 rad). Such a step is halved until the bend is smaller than that distance.
    // The start of a pair on its level is left to the extrema (Bannerman's rule above).
    const auto turnsNearLevel = [&](const PairSample& p, bool start, double stray) {
        if (start && onLevel != ExitSide::None) return false;
        const double aboveLower = p.U - lower, belowUpper = upper - p.U;
        return (aboveLower > 0.0 && aboveLower < stray && p.dUdt > 0.0) ||
               (belowUpper > 0.0 && belowUpper < stray && p.dUdt < 0.0);
    };
    const double shortestStep = s.maxStep / 4096.0;

    while (a.t < tEnd) {
        double h = s.maxStep;
        if (a.dUdt < 0.0 && std::isfinite(lower))
            h = std::min(h, (a.U - lower) / -a.dUdt + s.nudge);
        else if (a.dUdt > 0.0 && std::isfinite(upper))
            h = std::min(h, (upper - a.U) / a.dUdt + s.nudge);
        PairSample b;
        double stray = 0.0;
        for (;;) {
            const double tb = std::min(a.t + h, tEnd);
            if (!(tb > a.t)) break; // the window cannot be split any further
            b = eval(tb);
            ++result.evaluations;
            stray = strayOf(a, b);
            if (h <= shortestStep ||
                !(turnsNearLevel(a, true, stray) || turnsNearLevel(b, false, stray)))
                break;
            h *= 0.5;
        }
        if (!(b.t > a.t)) break;
        // An extremum between a and b comes before b: it is judged by whether a was on the level.
        const bool bOnLevel = stillOnLevel(b);

        const detail::HermiteCubic cubic(a, b);
        std::array<double, 2> ext{};
        // When even the cubic's largest stray from the chord leaves it farther than grazeWindow
        // from both levels, no extremum can matter.
        const bool clear = std::min(a.U, b.U) - stray > lower + s.grazeWindow &&
                           std::max(a.U, b.U) + stray < upper - s.grazeWindow;
        const int n = clear ? 0 : cubic.extrema(ext);
        for (int e = 0; e < n; ++e) {
            const double predicted = cubic.value(ext[e]);
            if (cubic.curvature(ext[e]) > 0.0) {
                if (std::isfinite(lower) && predicted - lower < s.grazeWindow) {
                    PairSample m = detail::probeExtremum(eval, a, b, {1.0, lower}, near, tolerance,
                                                         result.evaluations);
                    if (m.U < lower && !stillOnLevel(m)) return bracketed(a, m, ExitSide::Lower);
                }
            } else if (std::isfinite(upper) && upper - predicted < s.grazeWindow) {
                PairSample m = detail::probeExtremum(eval, a, b, {-1.0, upper}, near, tolerance,
                                                     result.evaluations);
                if (m.U > upper && !stillOnLevel(m)) return bracketed(a, m, ExitSide::Upper);
            }
        }
        if (!bOnLevel) onLevel = ExitSide::None;
        if (b.U < lower) return bracketed(a, b, ExitSide::Lower);
        if (b.U > upper) return bracketed(a, b, ExitSide::Upper);
        a = b;
    }
    result.end = a;
    return result;
}

} // namespace terrace::dmd
