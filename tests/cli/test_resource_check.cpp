// The memory and disk estimates of a run against what real runs take and write, and the
// refusals and warnings they lead to (cli/resource_check.hpp). The tests that measure the
// process's own memory are in test_resource_memory.cpp.
#include "cli/resource_check.hpp"
#include "tests/cli/resource_scenes.hpp"
#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>

namespace test_resource_check {

using namespace terrace;
using namespace terrace::resource_tests;

TEST(ResourceCheck, TheEngineEstimateGrowsWithTheBodiesAndTheirNeighbours) {
    for (const std::string engine : {"dmd", "smd"}) {
        auto bytes = [&](int n, double density) {
            return cli::memoryEstimate(scene({"engine=" + engine, "state.n=" + std::to_string(n),
                                              "state.density=" + std::to_string(density)}))
                .engine;
        };
        // At one density every body costs the same: linear in N beyond the process's own.
        const double perBody = (bytes(8000, 0.5) - bytes(1000, 0.5)) / 7000.0;
        EXPECT_NEAR(bytes(64000, 0.5) - bytes(8000, 0.5), 56000.0 * perBody, 1e-9 * perBody * 8e4)
            << engine;
        EXPECT_GT(perBody, 200.0) << engine;
        EXPECT_LT(perBody, 4000.0) << engine;
        // Denser, more partners in each body's neighbour list.
        EXPECT_GT(bytes(8000, 0.8), bytes(8000, 0.5)) << engine;
    }
}

TEST(ResourceCheck, DmdBeyondItsBodyLimitIsRefusedBeforeItsMemory) {
    try {
        cli::checkResources(scene({"state.n=70000000"}), scratch("limit"), false);
        ADD_FAILURE() << "7e7 DMD bodies were not refused";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()), "run: state.n = 70000000: DMD runs at most 67108863 "
                                         "bodies (an agenda keeps an event's partner in 26 bits)");
    }
}

TEST(ResourceCheck, TheRefusalNamesTheLargerShare) {
    const Scene s = scene({});
    const cli::MemoryEstimate engineHeavy{30.0 * (1 << 30), 7.0 * (1 << 30)};
    EXPECT_EQ(cli::memoryRefusal(s, engineHeavy, {22.0 * (1 << 30)}),
              "state.n = 512: the run needs about 37 GiB of memory (engine 30 GiB, analysis 7 GiB) "
              "and this machine has 22 GiB available: use fewer bodies");
    const cli::MemoryEstimate analysisHeavy{1.0 * (1 << 30), 40.0 * (1 << 30)};
    EXPECT_EQ(cli::memoryRefusal(s, analysisHeavy, {22.0 * (1 << 30)}),
              "analysis.follow_bodies, analysis.lags_per_level (512 bodies followed, 16 lags a "
              "level): the run needs about 41 GiB of memory (engine 1 GiB, analysis 40 GiB) and "
              "this machine has 22 GiB available: follow fewer bodies or use fewer lags a level");
    EXPECT_EQ(cli::memoryRefusal(s, engineHeavy, {40.0 * (1 << 30)}), "");
    EXPECT_EQ(cli::memoryRefusal(s, engineHeavy, {0.0}), ""); // unknown: nothing said
    EXPECT_EQ(cli::memoryRefusal(s, engineHeavy, {3.0 * (1 << 30), "the process's cgroup leaves"}),
              "state.n = 512: the run needs about 37 GiB of memory (engine 30 GiB, analysis 7 GiB) "
              "and the process's cgroup leaves 3 GiB available: use fewer bodies");
}

TEST(ResourceCheck, AvailableMemoryIsPositiveAndAtMostTheMachines) {
    const double have = cli::availableMemory().bytes;
    EXPECT_GT(have, 0.0);
    EXPECT_LE(have, double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE)));
}

TEST(ResourceCheck, BytesAreShownWithABinaryUnit) {
    EXPECT_EQ(cli::showBytes(512), "512 B");
    EXPECT_EQ(cli::showBytes(3.4 * (1 << 20)), "3.4 MiB");
    EXPECT_EQ(cli::showBytes(38.0 * (1 << 30)), "38 GiB");
    EXPECT_EQ(cli::showBytes(1000.0 * (1 << 20)), "1000 MiB");
    EXPECT_EQ(cli::showBytes(9.1 * 1024.0 * (1 << 30)), "9.1 TiB");
}

TEST(ResourceCheck, TheTrajectoryEstimateIsNearTheFileWritten) {
    for (const std::string kind : {"linear", "asymmetric"}) {
        std::vector<std::string> sets = {"body.kind=" + kind,
                                         "state.n=216",
                                         "run.equilibrate_ps=0.018",
                                         "run.time_ps=0.09",
                                         "output.trajectory_every_fs=9",
                                         "output.thermo_every_fs=9"};
        if (kind == "asymmetric") sets.push_back("body.inertia=[0.8,1.154,0.5]");
        const Scene s = scene(sets);
        const cli::DiskEstimate d = cli::diskEstimate(s);
        const auto dir = scratch("trajectory");
        std::filesystem::remove_all(dir);
        cli::runScene(s, {dir, cli::OutputMode::Fresh, true, nullptr});
        const double written = double(std::filesystem::file_size(dir / "trajectory.xyz"));
        const double thermo = double(std::filesystem::file_size(dir / "thermo.csv"));
        std::filesystem::remove_all(dir);
        std::printf("%s: trajectory estimate %.0f B, written %.0f B; thermo %.0f, %.0f\n",
                    kind.c_str(), d.trajectory, written, d.thermo, thermo);
        // Numbers at 17 significant digits take 18-24 characters: the estimate errs high.
        EXPECT_GT(d.trajectory, written) << kind;
        EXPECT_LT(d.trajectory, 1.25 * written) << kind;
        EXPECT_GT(d.thermo, thermo) << kind;
        EXPECT_LT(d.thermo, 2.0 * thermo) << kind;
    }
}

TEST(ResourceCheck, DiskBeyondTheFreeSpaceIsRefusedAndBeyondHalfWarned) {
    const Scene s = scene({"output.trajectory_every_fs=9"});
    cli::DiskEstimate d;
    d.trajectory = 6.0 * (1 << 30);
    d.results = 1 << 20;
    const auto fits = cli::diskVerdict(s, d, 0.0, 100.0 * (1 << 30), "out/x");
    EXPECT_EQ(fits.kind, cli::DiskVerdict::Kind::Fits);
    EXPECT_EQ(fits.message, "");
    const auto warn = cli::diskVerdict(s, d, 0.0, 10.0 * (1 << 30), "out/x");
    EXPECT_EQ(warn.kind, cli::DiskVerdict::Kind::Warn);
    EXPECT_EQ(warn.message, "the run will write about 6 GiB into out/x (trajectory.xyz 6 GiB), "
                            "more than half of the 10 GiB free on its file system");
    const auto refuse = cli::diskVerdict(s, d, 0.0, 4.0 * (1 << 30), "out/x");
    EXPECT_EQ(refuse.kind, cli::DiskVerdict::Kind::Refuse);
    EXPECT_EQ(refuse.message,
              "output.trajectory_every_fs: the run will write about 6 GiB into out/x "
              "(trajectory.xyz 6 GiB) and its file system has 4 GiB free: write less often, or "
              "choose another --out");
    // A continued run counts what its files already hold.
    EXPECT_EQ(cli::diskVerdict(s, d, 3.0 * (1 << 30), 4.0 * (1 << 30), "out/x").kind,
              cli::DiskVerdict::Kind::Warn);
    EXPECT_EQ(cli::diskVerdict(s, d, 5.0 * (1 << 30), 4.0 * (1 << 30), "out/x").kind,
              cli::DiskVerdict::Kind::Fits);
    // Free space unknown: nothing said.
    EXPECT_EQ(cli::diskVerdict(s, d, 0.0, -1.0, "out/x").kind, cli::DiskVerdict::Kind::Fits);
    // The restart file the largest: named with its key.
    cli::DiskEstimate r;
    r.restart = 90.0 * (1 << 30);
    const auto restart = cli::diskVerdict(s, r, 0.0, 50.0 * (1 << 30), "out/x");
    EXPECT_EQ(restart.kind, cli::DiskVerdict::Kind::Refuse);
    EXPECT_EQ(restart.message.rfind("output.restart_every_ps: ", 0), 0u) << restart.message;
    EXPECT_NE(restart.message.find("restart.bin 90 GiB"), std::string::npos) << restart.message;
    // A GSD trajectory is named as such.
    cli::DiskEstimate g;
    g.trajectory = 6.0 * (1 << 30);
    g.trajectoryName = "trajectory.gsd";
    EXPECT_NE(cli::diskVerdict(s, g, 0.0, 4.0 * (1 << 30), "out/x")
                  .message.find("(trajectory.gsd 6 GiB)"),
              std::string::npos);
}

TEST(ResourceCheck, FreeDiskIsFoundFromTheNearestExistingDirectory) {
    const double tmp = cli::freeDiskBytes(std::filesystem::temp_directory_path());
    EXPECT_GT(tmp, 0.0);
    const double below = cli::freeDiskBytes(std::filesystem::temp_directory_path() / "not" / "yet");
    EXPECT_GT(below, 0.0);
    EXPECT_NEAR(below, tmp, 0.01 * tmp); // the same file system, give or take other writers
}

} // namespace test_resource_check
