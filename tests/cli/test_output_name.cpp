// Default output directories named by the command line's overrides (cli/output_dir.hpp), so
// that runs of one scene with different --set do not collide.
#include "cli/output_dir.hpp"
#include <gtest/gtest.h>

namespace test_output_name {

using namespace terrace::cli;

TEST(OutputName, OverridesAreSortedByKeyAndNamedByTheirLastComponent) {
    EXPECT_EQ(overridesName({}), "");
    EXPECT_EQ(overridesName({"smd.dt_fs=0.7"}), "dt_fs=0.7");
    // The order on the command line does not matter; the key decides.
    EXPECT_EQ(overridesName({"state.temperature=2", "smd.dt_fs=0.7"}), "dt_fs=0.7,temperature=2");
    EXPECT_EQ(overridesName({"smd.dt_fs=0.7", "state.temperature=2"}), "dt_fs=0.7,temperature=2");
    // A key given twice counts once, by its last value, as the scene takes it.
    EXPECT_EQ(overridesName({"state.n=64", "state.n=128"}), "n=128");
    // name and engine are in the directory's name already.
    EXPECT_EQ(overridesName({"engine=smd", "name=x", "seed=3"}), "seed=3");
}

TEST(OutputName, SharedLastComponentsKeepTheWholeKey) {
    EXPECT_EQ(overridesName({"dmd.terraces.levels=optimal", "dmd.levels=[-1,1]"}),
              "dmd.levels=_-1_1_,dmd.terraces.levels=optimal");
    // An object value counts as its leaves.
    EXPECT_EQ(overridesName({R"(dmd.terraces={"levels": "optimal", "n": 3})"}),
              "levels=optimal,n=3");
}

TEST(OutputName, EveryCharacterIsSafeInOneDirectoryName) {
    const std::string name = overridesName({"name=a", "smd.scheme=a/b c", "state.n=1e3"});
    EXPECT_EQ(name, "scheme=a_b_c,n=1000.0");
    EXPECT_EQ(overridesName({"smd.scheme=../x"}), "scheme=.._x");
    for (const char c : overridesName({"smd.scheme=*?<>|\\\"'`$"}))
        EXPECT_TRUE(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ||
                    c == '.' || c == ',' || c == '=')
            << c;
}

TEST(OutputName, TooLongIsCutWithAChecksum) {
    std::vector<std::string> many, others;
    for (int k = 0; k < 40; ++k) {
        many.push_back("analysis.key" + std::to_string(k) + "=" + std::to_string(k));
        others.push_back("analysis.key" + std::to_string(k) + "=" + std::to_string(k + 1));
    }
    const std::string a = overridesName(many), b = overridesName(others);
    EXPECT_EQ(a.size(), 160u);
    EXPECT_EQ(b.size(), 160u);
    EXPECT_NE(a, b); // the checksum tells them apart
    EXPECT_EQ(a, overridesName(many));
    EXPECT_EQ(a.substr(0, 20), overridesName(many, 100000).substr(0, 20));
}

TEST(OutputName, TheBaseNameComesFirst) {
    EXPECT_EQ(nameWithOverrides("lj-liquid-smd", {"smd.dt_fs=0.7"}), "lj-liquid-smd-dt_fs=0.7");
    EXPECT_EQ(nameWithOverrides("lj-liquid-smd", {"engine=smd"}), "lj-liquid-smd");
}

} // namespace test_output_name
