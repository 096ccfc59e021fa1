#pragma once
// A stepped spherical pair potential as DynamO and the stepped-potential literature give it
// (Chapela, Scriven & Davis, J. Chem. Phys. 91, 4307 (1989); Thomson, Lue & Bannerman, J. Chem.
// Phys. 140, 034105 (2014)): steps (r_k, E_k), k = 0 … K−1, with r_0 > r_1 > … > r_{K−1} > 0,
// and a hard core r_hc < r_{K−1} (0: none). The pair energy is
//     0      for r ≥ r_0 (r_0 is the cutoff),
//     E_k    for r_{k+1} ≤ r < r_k   (r_K = r_hc),
//     +∞     for r < r_hc            (the pair reflects elastically at r_hc).
// Radii in σ, energies in ε: the table is free of units, the scene scales it (core/scene.cpp).
//
// Besides explicit tables, the ready-made ones users know: the square well and the square
// shoulder, Chapela's discretisation of Lennard-Jones as DynamO ships it, and DynamO's default
// generator for a continuous potential (steps placed at equal energy intervals of the cut-and-
// shifted U, each step's energy the volume average of U over its shell). Pure functions; every
// problem with a table is a one-line SceneError naming the key.
#include "core/scene.hpp"
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace terrace {

struct StepTable {
    std::vector<double> radii;    // r_k, σ, strictly decreasing
    std::vector<double> energies; // E_k, ε, one per radius
    double hardCore = 0.0;        // r_hc, σ (0: none)

    bool hasCore() const { return hardCore > 0.0; }
    /// The distance beyond which the energy is 0, σ: r_0, or r_hc for bare hard spheres.
    double cutoff() const { return radii.empty() ? hardCore : radii.front(); }
    /// The energy at centre distance r (σ), ε: +∞ inside the core. A pair exactly on r_k has
    /// left step k − 1 (the intervals are closed below, as in the definition above).
    double energyAt(double r) const {
        if (r < hardCore) return std::numeric_limits<double>::infinity();
        double e = 0.0;
        for (std::size_t k = 0; k < radii.size() && r < radii[k]; ++k)
            e = energies[k];
        return e;
    }
    /// The lowest energy the table takes, ε (0 at the latest beyond the cutoff).
    double minimumEnergy() const {
        double e = 0.0;
        for (double x : energies)
            e = std::min(e, x);
        return e;
    }
};

/// Refuses a table that does not define a potential, naming `key` (e.g. "potential.steps"):
/// no step and no core, radii or energies not finite, radii not > 0 or not strictly
/// decreasing, a core not inside the innermost step.
inline void validateStepTable(const StepTable& t, const std::string& key) {
    auto fail = [&](const std::string& what) { throw SceneError(key + ": " + what); };
    auto show = [](double x) {
        char text[32];
        std::snprintf(text, sizeof text, "%.6g", x);
        return std::string(text);
    };
    if (t.radii.size() != t.energies.size())
        fail("needs one energy per radius, got " + std::to_string(t.radii.size()) + " radii and " +
             std::to_string(t.energies.size()) + " energies");
    if (t.radii.empty() && !t.hasCore())
        fail("is empty and there is no hard_core: give at least one step [r, E] or a hard core");
    if (!std::isfinite(t.hardCore) || t.hardCore < 0.0)
        fail("hard_core must be a finite radius >= 0 (σ), got " + show(t.hardCore));
    for (std::size_t k = 0; k < t.radii.size(); ++k) {
        const std::string at = "step " + std::to_string(k) + " ";
        if (!std::isfinite(t.radii[k]) || !(t.radii[k] > 0.0))
            fail(at + "has radius " + show(t.radii[k]) + ": radii must be finite and > 0 (σ)");
        if (!std::isfinite(t.energies[k]))
            fail(at + "has energy " + show(t.energies[k]) +
                 ": energies must be finite (a wall is the hard_core)");
        if (k > 0 && t.radii[k] == t.radii[k - 1])
            fail(at + "repeats the radius " + show(t.radii[k]) + " of step " +
                 std::to_string(k - 1) + ": radii must be distinct");
        if (k > 0 && !(t.radii[k] < t.radii[k - 1]))
            fail(at + "has radius " + show(t.radii[k]) + " > " + show(t.radii[k - 1]) +
                 " of step " + std::to_string(k - 1) +
                 ": steps must be sorted by decreasing radius, the cutoff first");
    }
    if (t.hasCore() && !t.radii.empty() && !(t.hardCore < t.radii.back()))
        fail("hard_core " + show(t.hardCore) + " must lie inside the innermost step, at r < " +
             show(t.radii.back()));
}

namespace steps {

/// The square well of range λ and depth ε·depth (depth < 0: a square shoulder of height
/// −depth): −depth for 1 ≤ r < λ, a hard core at 1 (σ).
inline StepTable squareWell(double lambda, double depth) {
    if (!std::isfinite(lambda) || !(lambda > 1.0))
        throw SceneError("potential.lambda: the well's range must be > 1 (σ), got " +
                         std::to_string(lambda));
    return StepTable{{lambda}, {-depth}, 1.0};
}

/// The square shoulder of range λ and height ε·height over a hard core at 1 (σ).
inline StepTable squareShoulder(double lambda, double height) {
    return squareWell(lambda, -height);
}

/// Chapela, Scriven & Davis's discretisation of Lennard-Jones (J. Chem. Phys. 91, 4307 (1989)),
/// the ten steps and core at 0.75 σ that DynamO builds by default for its stepped potential
/// (dynamod --pack-mode 16, src/dynamo/dynamo/inputplugins/packer.cpp, "Chapela et al potential
/// 6"; DynamO gives the core as a step of energy 1e300).
inline StepTable chapelaLJ() {
    return StepTable{{2.30, 1.75, 1.45, 1.25, 1.05, 1.00, 0.95, 0.90, 0.85, 0.80},
                     {-0.06, -0.22, -0.55, -0.98, -0.47, 0.76, 3.81, 10.95, 27.55, 66.74},
                     0.75};
}

/// How a generated step's energy is taken from U over its shell [r_in, r_out).
enum class StepEnergyRule {
    Volume,   // the volume average of U over the shell (DynamO's default, UMode "Volume")
    Midpoint, // U at the shell's mid radius (DynamO's UMode "Midpoint")
};

/// DynamO's default stepping of a continuous potential with one minimum (dynamod --pack-mode 16
/// --i2 1, PotentialLennardJones in src/dynamo/dynamo/interactions/potentials/lennard_jones.cpp,
/// RMode "DeltaU"): with U cut and shifted to 0 at `cutoff` and ΔU = −U(r_min)/n (n, the number
/// of attractive steps, may be fractional), the radii are r_0 = cutoff, then the radii at which
/// U = −ΔU, −2ΔU, … down the attractive side while they lie above the minimum, then on the
/// repulsive side back up through the same levels and on by ΔU. DynamO goes on for ever; here the
/// first step whose energy would exceed coreEnergy (ε) becomes the hard core instead.
/// U in ε of r in σ, rMin its minimum; `volumeAverage(a, b)` the exact volume average of U over
/// the shell a < r < b (unshifted), for the Volume rule.
inline StepTable energySteps(const std::function<double(double)>& U, double rMin, double cutoff,
                             double n, StepEnergyRule rule, double coreEnergy,
                             const std::function<double(double, double)>& volumeAverage) {
    if (!(cutoff > rMin) || !std::isfinite(cutoff))
        throw SceneError("potential.range: the cutoff must lie beyond the potential's minimum "
                         "at " +
                         std::to_string(rMin) + " σ");
    if (!(n > 0.0) || !std::isfinite(n) || n > 1000.0)
        throw SceneError("potential.attractive_steps: must be in (0, 1000], got " +
                         std::to_string(n));
    const double shift = U(cutoff);
    auto Us = [&](double r) { return U(r) - shift; };
    const double dU = -Us(rMin) / n;
    // r with Us(r) = u by bisection between a (Us above u) and b (Us below u), either order.
    auto root = [&](double u, double above, double below) {
        for (int k = 0; k < 200 && above != below; ++k) {
            const double mid = 0.5 * (above + below);
            if (mid == above || mid == below) break;
            (Us(mid) > u ? above : below) = mid;
        }
        return 0.5 * (above + below);
    };
    // Levels strictly inside the well: for a whole n the n-th would sit on the minimum, where
    // the step between its two roots would have no width.
    const int bottom = static_cast<int>(std::ceil(n)) - 1;
    auto energyOf = [&](double in, double out) {
        return rule == StepEnergyRule::Volume ? volumeAverage(in, out) - shift
                                              : Us(0.5 * (in + out));
    };
    StepTable t;
    double outer = cutoff; // r_{i−1}
    for (int i = 1;; ++i) {
        double r;
        if (i <= bottom) { // down the attractive side, outwards of the minimum
            r = root(-i * dU, outer, rMin);
        } else { // back up the repulsive side and on, by ΔU
            const double u = (i - 2 * bottom - 1) * dU;
            const double below = std::min(outer, rMin);
            double above = below;
            while (Us(above) < u)
                above *= 0.5; // Us rises without bound towards r = 0
            r = root(u, above, below);
        }
        const double e = energyOf(r, outer);
        if (e > coreEnergy || t.radii.size() >= 10000) {
            t.hardCore = outer;
            break;
        }
        t.radii.push_back(outer);
        t.energies.push_back(e);
        outer = r;
    }
    return t;
}

/// The shifted Lennard-Jones potential 4(r⁻¹² − r⁻⁶) (ε, σ = 1) stepped as DynamO does by
/// default: n attractive steps (5.8), cutoff 3 σ, step energies by `rule`.
inline StepTable lennardJones(double n, double cutoff, StepEnergyRule rule, double coreEnergy) {
    const auto U = [](double r) {
        const double s6 = 1.0 / (r * r * r * r * r * r);
        return 4.0 * (s6 * s6 - s6);
    };
    // 3/(b³ − a³) ∫_a^b r² U dr = 4/(b³ − a³) [(a⁻⁹ − b⁻⁹)/3 − (a⁻³ − b⁻³)]
    const auto average = [](double a, double b) {
        const double a3 = a * a * a, b3 = b * b * b;
        return 4.0 / (b3 - a3) *
               ((1.0 / (a3 * a3 * a3) - 1.0 / (b3 * b3 * b3)) / 3.0 - (1.0 / a3 - 1.0 / b3));
    };
    return energySteps(U, std::pow(2.0, 1.0 / 6.0), cutoff, n, rule, coreEnergy, average);
}

} // namespace steps
} // namespace terrace
