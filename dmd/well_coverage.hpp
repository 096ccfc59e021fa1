#pragma once
// Whether a terracing keeps the wells of an orientational potential. A pair of bodies at fixed
// relative orientation has a radial profile U(r); where that profile's whole well lies on
// terrace 0 (V = 0, the terrace holding U = 0) the terraced pair feels no attraction at all in
// that orientation. The global minimum can sit well inside the levels while a shallower well (the
// end-to-end one of a Gay–Berne pair, which is κ'^{1/μ} times shallower than the side-by-side
// one) is swallowed whole: DMD then samples a different fluid, with no error bar that shows it.
//
// The check runs over a fixed set of random relative orientations (one for spheres, each species
// pair for a mixture of spheres, species pairs in turn for one with rods), the same
// kind of sample a terrace design weighs (dmd/pair_energy_density.hpp), each profile scanned on
// a radial grid from inside the wall out to the model's range. Wells shallower than
// `significant` are not counted: a well of a few hundredths of kT moves nothing measurable.
#include "core/body_orientation.hpp"
#include "core/initial_state.hpp"
#include "core/pair_potential.hpp"
#include "dmd/orientation_samples.hpp"
#include "dmd/terrace_levels.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

namespace terrace::dmd {

struct WellCoverage {
    int orientations = 0;          // relative orientations sampled
    int withWell = 0;              // whose profile dips below −significant
    int swallowed = 0;             // of those, whose whole well lies on terrace 0
    double deepestSwallowed = 0.0; // the lowest U of a swallowed well, kJ/mol
};

/// The wells of p that `levels` swallow. `wall` (kJ/mol) sets where each scan starts: at half
/// the largest distance at which U reaches it.
template <PairPotential P>
WellCoverage wellCoverage(const P& p, const TerraceLevels& levels, double significant, double wall,
                          int radii = 2000, int orientations = 256) {
    double rOut = p.reachDistance(-significant);
    if constexpr (requires { p.range(); })
        if (std::isfinite(p.range())) rOut = std::min(rOut, p.range());
    const double rIn = 0.5 * p.reachDistance(wall);
    WellCoverage c;
    // A mixture of spheres' "orientations" are its species pairs, each checked once (a mixture
    // with rods takes its pairs in turn with random axes: dmd/orientation_samples.hpp).
    std::vector<std::pair<int, int>> speciesPairs;
    if constexpr (P::attitude == AttitudeUse::Species) {
        speciesPairs = speciesPairsOf(p);
        orientations = static_cast<int>(speciesPairs.size());
    }
    c.orientations = readsBodies<P> ? orientations : 1;
    if (!(rOut > rIn)) return c;     // no well deeper than `significant` anywhere
    std::mt19937_64 rng(0x3e11c0de); // fixed: the check is a pure function of its inputs
    const int zero = levels.terraceOf(0.0);
    for (int k = 0; k < c.orientations; ++k) {
        auto si = unusedOrientation<P>(), sj = unusedOrientation<P>();
        if constexpr (P::attitude == AttitudeUse::Species) std::tie(si, sj) = speciesPairs[k];
        if constexpr (isOrientational<P>) std::tie(si, sj) = sampledOrientations(p, k, rng);
        double uMin = std::numeric_limits<double>::infinity();
        for (int i = 0; i <= radii; ++i) {
            const double r = rIn + (rOut - rIn) * i / radii;
            const double u = p.energy(Vec3(r, 0.0, 0.0), si, sj);
            if (std::isfinite(u)) uMin = std::min(uMin, u);
        }
        if (!(uMin < -significant)) continue;
        ++c.withWell;
        if (levels.terraceOf(uMin) == zero) {
            ++c.swallowed;
            c.deepestSwallowed = std::min(c.deepestSwallowed, uMin);
        }
    }
    return c;
}

} // namespace terrace::dmd
