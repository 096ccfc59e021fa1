// Keys the running engine does not read (cli/engine_keys.hpp): which keys belong to an engine,
// and the warnings and --strict refusals for the command line's --set.
#include "cli/engine_keys.hpp"
#include "core/scene.hpp"
#include <gtest/gtest.h>

namespace test_engine_keys {

using namespace terrace;
using namespace terrace::cli;

TEST(EngineKeys, AKeyBelongsToTheEngineWhoseSectionHoldsIt) {
    EXPECT_EQ(engineOfKey("smd.dt_fs"), "smd");
    EXPECT_EQ(engineOfKey("dmd.terraces.n"), "dmd");
    EXPECT_EQ(engineOfKey("dmd"), "dmd"); // the whole section, --set dmd={...}
    EXPECT_EQ(engineOfKey("engine"), "");
    EXPECT_EQ(engineOfKey("state.temperature"), "");
    EXPECT_EQ(engineOfKey("smdx.dt_fs"), ""); // not a section of either (refused as unknown)
    EXPECT_EQ(overrideKey("smd.dt_fs=0.7"), "smd.dt_fs");
    EXPECT_EQ(overrideKey("a.b=c=d"), "a.b");
}

TEST(EngineKeys, TheOtherEnginesKeysAreWarnings) {
    const std::vector<std::string> sets = {"smd.dt_fs=0.7", "state.temperature=2", "dmd.dV=0.25",
                                           "engine=dmd"};
    const auto dmd = judgeOverrides(sets, "dmd", "the run's engine, dmd,", false);
    ASSERT_EQ(dmd.size(), 1u);
    EXPECT_EQ(dmd[0], "--set smd.dt_fs=0.7: the run's engine, dmd, does not read the smd section, "
                      "so the setting has no effect (--strict refuses it)");
    const auto smd = judgeOverrides(sets, "smd", "the run's engine, smd,", false);
    ASSERT_EQ(smd.size(), 1u);
    EXPECT_NE(smd[0].find("--set dmd.dV=0.25: the run's engine, smd, does not read the dmd"),
              std::string::npos);
    EXPECT_TRUE(judgeOverrides({"state.n=64", "run.time_ps=1"}, "dmd", "x", true).empty());
}

TEST(EngineKeys, StrictRefusesTheFirst) {
    try {
        judgeOverrides({"state.n=64", "smd.skin=0.4", "smd.dt_fs=1"}, "dmd",
                       "the run's engine, dmd,", true);
        ADD_FAILURE() << "--strict accepted a key the engine does not read";
    } catch (const SceneError& e) {
        EXPECT_STREQ(e.what(), "--set smd.skin=0.4: the run's engine, dmd, does not read the smd "
                               "section, so the setting has no effect (refused under --strict)");
    }
}

} // namespace test_engine_keys
