// Terrace levels, indices and energies, r_m, and rejection of a level on the potential minimum.
#include "core/lj_potential.hpp"
#include "core/rod_potential.hpp"
#include "dmd/terrace_levels.hpp"
#include <gtest/gtest.h>
#include <string>

namespace test_terrace_levels {

using namespace terrace;
using namespace terrace::dmd;

TEST(TerraceLevels, UniformLevelsRoundUToTheNearestMultiple) {
    const TerraceLevels t = TerraceLevels::uniform(2.0);
    EXPECT_EQ(t.terraceOf(0.3), 0);
    EXPECT_EQ(t.terraceOf(-0.99), 0);
    EXPECT_EQ(t.terraceOf(-1.01), -1);
    EXPECT_EQ(t.terraceOf(5.2), 3);
    EXPECT_DOUBLE_EQ(t.energy(-2), -4.0);
    EXPECT_DOUBLE_EQ(t.lower(1), 1.0);
    EXPECT_DOUBLE_EQ(t.upper(1), 3.0);
    // Exactly on a level: the terrace the pair is heading into.
    EXPECT_EQ(t.terraceOf(1.0, +1.0), 1);
    EXPECT_EQ(t.terraceOf(1.0, -1.0), 0);
}

TEST(TerraceLevels, ExplicitLevelsPutTheZeroTerraceAroundZero) {
    const TerraceLevels t = TerraceLevels::explicitLevels({-2.5, -1.0, 0.5, 3.0});
    EXPECT_EQ(t.terraceOf(0.0), 0);
    EXPECT_DOUBLE_EQ(t.energy(0), 0.0);
    EXPECT_DOUBLE_EQ(t.lower(0), -1.0);
    EXPECT_DOUBLE_EQ(t.upper(0), 0.5);
    EXPECT_DOUBLE_EQ(t.energy(-1) - t.energy(0), -1.75 - (-0.25)); // midpoints −1.75, −0.25
    EXPECT_TRUE(std::isinf(t.lower(-2)));
    EXPECT_TRUE(std::isinf(t.upper(2)));
    EXPECT_EQ(t.terraceOf(10.0), 2);
    EXPECT_EQ(t.terraceOf(-10.0), -2);
}

// r_m against the paper's formula as tabulated in /work/shared/testdata/rod_reference.json
// (`interaction_range`, "computed directly from the paper's formulas") at T* = 1.4.
TEST(TerraceLevels, InteractionRangeMatchesThePaper) {
    const RodPotential rod;
    const double kT = 4.199999999999999;
    const double dVInKT[] = {0.25, 0.5, 1.0, 2.0};
    const double rm[] = {5.573000938573839, 4.978312130461398, 4.388327827082952,
                         3.414718151364337};
    for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(interactionRange(TerraceLevels::uniform(dVInKT[k] * kT), rod), rm[k], 1e-12);
}

TEST(TerraceLevels, ALevelOnTheMinimumIsRejected) {
    EXPECT_THROW(TerraceLevels::uniform(6.0).checkMinimum(-3.0, "dmd.dV"), SceneError);
    EXPECT_NO_THROW(TerraceLevels::uniform(5.9).checkMinimum(-3.0, "dmd.dV"));
    try {
        TerraceLevels::explicitLevels({-3.0, 1.0}).checkMinimum(-3.0, "dmd.levels");
        ADD_FAILURE();
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("dmd.levels"), std::string::npos);
    }
    EXPECT_THROW(TerraceLevels::uniform(0.0), SceneError);
    EXPECT_THROW(TerraceLevels::explicitLevels({-1.0, 0.0, 1.0}), SceneError);
}

namespace {

/// The refusal's text for uniform levels of `step` against a minimum `uMin`, at `kT`.
std::string minimumRefusal(double step, double uMin, double kT) {
    try {
        TerraceLevels::uniform(step).checkMinimum(uMin, "dmd.dV", kT);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

} // namespace

// The refusal names the dV nearest the refused one that put the minimum midway between two
// levels, each of which is then accepted.
TEST(TerraceLevels, ALevelOnTheMinimumNamesTheNearestValidDv) {
    // LJ at T* 2 (the case): dV = 1 puts the first level on U_min = -eps.
    EXPECT_EQ(minimumRefusal(2.0, -1.0, 2.0),
              "dmd.dV: a level falls on the potential minimum U = -1.000000 kJ/mol (a terrace of "
              "zero width); dmd.dV = 0.5 puts it midway between two levels (a dmd.dV above 1 "
              "leaves no level in the well)");
    EXPECT_EQ(minimumRefusal(0.5, -1.0, 2.0), "");
    // The minimum on the second level, -(2 - 1/2) dV kT: one level more or one fewer.
    EXPECT_EQ(minimumRefusal(2.0, -3.0, 1.0),
              "dmd.dV: a level falls on the potential minimum U = -3.000000 kJ/mol (a terrace of "
              "zero width); dmd.dV = 1.5 or 3 put it midway between two levels");
    EXPECT_EQ(minimumRefusal(1.5, -3.0, 1.0), "");
    EXPECT_EQ(minimumRefusal(3.0, -3.0, 1.0), "");
    // Without kT, as before, no dV is named.
    EXPECT_EQ(minimumRefusal(6.0, -3.0, 0.0),
              "dmd.dV: a level falls on the potential minimum U = -3.000000 kJ/mol (a terrace of "
              "zero width)");
    EXPECT_THROW(TerraceLevels::explicitLevels({1.0, -1.0}), SceneError);
}

} // namespace test_terrace_levels
