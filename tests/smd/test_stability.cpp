// An SMD time step far too long for the state point must stop with a clear error naming
// smd.dt_fs, not run on into NaN (or crash in the neighbour-list build).
#include "smd/scene_engine.hpp"
#include "systems.hpp"
#include <gtest/gtest.h>

namespace test_stability {

using namespace terrace;

TEST(Stability, TooLongTimeStepIsAClearError) {
    // Dense rods at T* = 10 with a 6 fs step: bodies run deep into the repulsive wall, the next
    // kick flings them across the box within a few steps.
    auto sys = smd::fixtures::rods(6, 0.5, 10.0, 7);
    smd::SceneEngine<LinearRotor, smd::fixtures::RodModel> engine(
        std::move(sys), smd::fixtures::smdScene(3.035, 6.0));
    try {
        engine.advanceTo(units::fromPs(5.0));
        FAIL() << "a 6 fs step at T* = 10 ran 5 ps without an error";
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("unstable"), std::string::npos) << what;
        EXPECT_NE(what.find("smd.dt_fs"), std::string::npos) << what;
    }
}

TEST(Stability, PaperTimeStepAtThePaperStatePointRunsQuietly) {
    auto sys = smd::fixtures::rods(6, 0.5, 1.4, 7);
    smd::SceneEngine<LinearRotor, smd::fixtures::RodModel> engine(
        std::move(sys), smd::fixtures::smdScene(3.035, 1.8));
    EXPECT_NO_THROW(engine.advanceTo(units::fromPs(1.0)));
}

} // namespace test_stability
