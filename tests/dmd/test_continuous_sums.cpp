// The configurational estimators of a DMD run (core/continuous_sums.hpp): the continuous model's U
// and virial W on DMD's configuration are those of the O(N²) reference on the same bodies; each
// pair's U − V is bounded by the terrace it sits on (|U − V| ≤ ΔV/2 for the paper's midpoints),
// so the back-conversion weight e^{−β(U−V)} of g_c(r) tends to 1 as ΔV → 0, and g_c to g_d.
#include "core/continuous_sums.hpp"
#include "core/smoothed_potential.hpp"
#include "dmd/testing.hpp"
#include "smd/pair_forces.hpp"
#include "test_systems.hpp"
#include <cmath>
#include <gtest/gtest.h>

namespace test_continuous_sums {

using namespace terrace;
using namespace terrace::dmdtest;

TEST(ContinuousSums, DmdConfigurationGivesTheReferenceUAndVirial) {
    const Scene s = rodScene(216, 0.5, 1.4, 0.5);
    SmoothedRodEngine e(buildInitialState<LinearRotor>(s, smoothedRods(s)), s);
    e.advanceTo(units::fromPs(0.3)); // a liquid configuration, not the lattice
    const smd::Forces all = smd::allPairsForces(e.system());
    const ContinuousSums c = e.continuousSums();
    EXPECT_NEAR(c.potential, all.potential, 1e-10 * std::abs(all.potential));
    EXPECT_NEAR(c.virial, all.virial, 1e-10 * std::abs(all.virial) + 1e-10);
    EXPECT_GT(all.evaluations, 216 * 10); // pairs out to r_u = 3σ, not just the terraced range
    // The terraced U differs from the continuous one by at most ΔV/2 per pair within r_u
    // (beyond r_m, V = 0 and |U| < ΔV/2), and does differ.
    const double dV = 0.5 * s.kT();
    const double gap = std::abs(c.potential - e.potentialEnergy());
    EXPECT_LE(gap, 0.5 * dV * double(all.evaluations));
    EXPECT_GT(gap, 0.0);
}

TEST(ContinuousSums, BackConversionWeightsTendToOneAsTheTerracesShrink) {
    // Per pair |U − V| ≤ ΔV/2 on uniform midpoint terraces, so every pair's weight lies within
    // e^{±βΔV/2}, and the profile's mean weights with it: ΔV = kT/2, kT/8, kT/32.
    double previous = std::numeric_limits<double>::infinity();
    for (const double dVkT : {0.5, 0.125, 0.03125}) {
        const Scene s = rodScene(216, 0.5, 1.4, dVkT);
        SmoothedRodEngine e(buildInitialState<LinearRotor>(s, smoothedRods(s)), s);
        e.advanceTo(units::fromPs(0.2));
        const double beta = 1.0 / s.kT();
        TerracingProfile profile(200, 0.05, beta);
        e.continuousSums(&profile);
        ASSERT_FALSE(profile.empty());
        double largest = 0.0;
        for (int k = 0; k < profile.bins(); ++k) {
            if (profile.counts()[std::size_t(k)] == 0.0) continue;
            const double lnW = std::log(profile.meanWeight(std::size_t(k)));
            EXPECT_LE(std::abs(lnW), 0.5 * dVkT + 1e-12) << "bin " << k << ", dV " << dVkT;
            largest = std::max(largest, std::abs(lnW));
        }
        EXPECT_LT(largest, previous); // the back-conversion vanishes with ΔV
        previous = largest;
    }
}

TEST(ContinuousSums, ProfileAveragesTheWeightsOfEachBin) {
    TerracingProfile profile(10, 0.1, 1.0);
    profile.add(0.55, 0.0); // U = V: weight 1
    EXPECT_DOUBLE_EQ(profile.meanWeight(5), 1.0);
    profile.add(0.55, std::log(2.0)); // U − V = kT ln 2: weight ½
    EXPECT_DOUBLE_EQ(profile.meanWeight(5), 0.75);
    EXPECT_DOUBLE_EQ(profile.meanWeight(0), 1.0); // no pair seen: U = V = 0
    profile.add(5.0, 1.0);                        // beyond the bins: not counted
    EXPECT_DOUBLE_EQ(profile.counts()[5], 2.0);
    EXPECT_THROW(profile.restore({1.0}, {1.0}), std::invalid_argument);
}

} // namespace test_continuous_sums
