// dmd/well_coverage.hpp: which pair orientations' wells a terracing swallows whole.
#include "core/gay_berne_potential.hpp"
#include "core/lj_potential.hpp"
#include "dmd/well_coverage.hpp"
#include <gtest/gtest.h>

namespace test_well_coverage {

using namespace terrace;

namespace {

// The Gay–Berne scene's model (experiments/scenes/gay-berne-liquid.json): ε0 = 2 kJ/mol,
// σ0 = 3 Å, κ 3, κ' 5, μ 2, ν 1; kT = 4 kJ/mol (T* = 2).
const GayBernePotential gb{.epsilon = 2.0, .sigma = 3.0};
constexpr double kT = 4.0;

dmd::WellCoverage coverage(double dV) {
    return dmd::wellCoverage(gb, dmd::TerraceLevels::uniform(dV * kT), 0.1 * kT, 20.0 * kT);
}

} // namespace

TEST(WellCoverage, HalfKTSwallowsTheShallowGayBerneWellsAndAFifthResolvesThem) {
    const auto coarse = coverage(0.5);
    EXPECT_EQ(coarse.orientations, 256);
    EXPECT_GT(coarse.withWell, 128); // most relative orientations have a well deeper than kT/10
    EXPECT_GT(coarse.swallowed, 0);
    // Swallowed: its lowest U lies above the first level, −ΔV/2 = −kT/4.
    EXPECT_GT(coarse.deepestSwallowed, -0.25 * kT);
    EXPECT_LT(coarse.deepestSwallowed, -0.1 * kT);
    // A level at −kT/10 lies inside every well deeper than kT/10.
    const auto fine = coverage(0.2);
    EXPECT_EQ(fine.withWell, coarse.withWell);
    EXPECT_EQ(fine.swallowed, 0);
    EXPECT_EQ(fine.deepestSwallowed, 0.0);
}

TEST(WellCoverage, ASphereHasOneProfileSwallowedOnlyWhenTheFirstLevelIsBelowItsMinimum) {
    const LJPotential lj{.epsilon = 1.0, .sigma = 3.4};
    const auto kept = dmd::wellCoverage(lj, dmd::TerraceLevels::uniform(1.0), 0.1, 20.0);
    EXPECT_EQ(kept.orientations, 1);
    EXPECT_EQ(kept.withWell, 1);
    EXPECT_EQ(kept.swallowed, 0);
    // ΔV = 2.5 ε: the first level at −1.25 ε, below U_min = −ε.
    const auto lost = dmd::wellCoverage(lj, dmd::TerraceLevels::uniform(2.5), 0.1, 20.0);
    EXPECT_EQ(lost.swallowed, 1);
    EXPECT_NEAR(lost.deepestSwallowed, -1.0, 1e-3); // the grid's minimum, within its spacing
}

} // namespace test_well_coverage
