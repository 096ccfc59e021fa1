// The files a run's analysis writes: names, headers, c(0) = 1, g(r) → 1, oacf.csv only for
// rotating bodies, fewer blocks for short runs, nothing written from unusable samples.
#include "analysis/csv.hpp"
#include "analysis/reference/direct_correlations.hpp"
#include "analysis/run_analysis.hpp"
#include "synthetic_samples.hpp"
#include <cmath>
#include <fstream>
#include <gtest/gtest.h>
#include <unistd.h>

namespace test_run_analysis_files {

using namespace terrace;
using namespace terrace::analysis;
namespace fs = std::filesystem;

namespace {

/// c(0) and OACF(0) are 1 by construction, to round-off.
constexpr double roundOff = 1e-12;
/// g over r ∈ [0.4, 0.5] L of randomly placed free rods: 1 within 5 of its quoted errors.
constexpr double largeRSigmas = 5.0;

/// An empty scratch directory of this process (ctest -j runs tests side by side), removed again
/// at the end of the test.
struct ScratchDirectory {
    fs::path path;
    explicit ScratchDirectory(const std::string& name)
        : path(fs::temp_directory_path() /
               ("terrace_analysis_" + name + "_" + std::to_string(::getpid()))) {
        fs::remove_all(path);
    }
    ~ScratchDirectory() { fs::remove_all(path); }
};

StreamingOptions options(int blocks = 8, double maxLagPs = 0.0, double rdfBin = 0.05) {
    StreamingOptions o;
    o.blocks = blocks, o.maxLagPs = maxLagPs, o.rdfBinAngstrom = rdfBin;
    return o; // g(r) out to L/2, every sample a frame
}

/// The files of a run that sampled `samples`, written into dir; its summary entries.
nlohmann::json written(const std::vector<Snapshot>& samples, const fs::path& dir,
                       const StreamingOptions& o = options()) {
    RunAnalysis run(samples.front().size(), samples.front().boxLength,
                    reference::sampleIntervalPs(samples), static_cast<long>(samples.size()), o);
    for (const auto& s : samples)
        run.add(s);
    return run.write(dir);
}

} // namespace

TEST(RunAnalysisFiles, FreeRodsWriteFourFilesWithUnitCurvesAtZero) {
    const auto samples = synthetic::freeRotors(64, 200, 0.1, 25.0, 4.2, 18.0, 1.154, 11);
    const ScratchDirectory scratch("rods");
    const fs::path& dir = scratch.path;
    const auto summary = written(samples, dir, options(8, 0.0, 0.1));

    const auto rdf = readCsv(dir / "rdf.csv"), vacf = readCsv(dir / "vacf.csv"),
               oacf = readCsv(dir / "oacf.csv"), msd = readCsv(dir / "msd.csv");
    EXPECT_EQ(rdf.header, (std::vector<std::string>{"r_angstrom", "g", "err"}));
    EXPECT_EQ(vacf.header, (std::vector<std::string>{"t_ps", "c", "err"}));
    EXPECT_EQ(oacf.header, (std::vector<std::string>{"t_ps", "c1", "c1_err", "c2", "c2_err"}));
    EXPECT_EQ(msd.header, (std::vector<std::string>{"t_ps", "msd_angstrom2", "err"}));

    EXPECT_EQ(rdf.rows(), 125); // L/2 = 12.5 Å in 0.1 Å bins
    // Lags up to half the 63-interval span, 31: 0 … 15, then 16, 18, … 30 (multiple-tau).
    EXPECT_EQ(vacf.rows(), 24);
    EXPECT_NEAR(vacf.columns[1][0], 1.0, roundOff);
    EXPECT_NEAR(oacf.columns[1][0], 1.0, roundOff);
    EXPECT_NEAR(oacf.columns[3][0], 1.0, roundOff);
    EXPECT_NEAR(vacf.columns[0][23], 30 * 0.01, 1e-15);
    EXPECT_EQ(msd.columns[1][0], 0.0);

    EXPECT_EQ(summary["samples"], 64);
    EXPECT_EQ(summary["bodies"], 200);
    const double gFar = summary["rdf"]["g_large_r"], gFarErr = summary["rdf"]["g_large_r_err"];
    EXPECT_GT(gFarErr, 0.0);
    EXPECT_NEAR(gFar, 1.0, largeRSigmas * gFarErr);
    EXPECT_TRUE(summary["diffusion"].contains("einstein_angstrom2_per_ps"));
}

TEST(RunAnalysisFiles, SpheresGetNoOacfAndAStaleOneIsRemoved) {
    auto samples = synthetic::ornsteinUhlenbeck(40, 20, 0.1, 20.0, 4.2, 18.0, 2.0, 12);
    const ScratchDirectory scratch("spheres");
    const fs::path& dir = scratch.path;
    fs::create_directories(dir);
    std::ofstream(dir / "oacf.csv") << "t_ps,c1,c1_err,c2,c2_err\n0,1,0,1,0\n";
    const auto summary = written(samples, dir);
    EXPECT_FALSE(fs::exists(dir / "oacf.csv"));
    EXPECT_TRUE(summary["oacf"].is_string());
    for (const char* name : {"rdf.csv", "vacf.csv", "msd.csv"})
        EXPECT_TRUE(fs::exists(dir / name));
}

TEST(RunAnalysisFiles, ShortRunsUseFewerBlocks) {
    const auto samples = synthetic::freeRotors(6, 4, 0.1, 25.0, 4.2, 18.0, 1.154, 14);
    const ScratchDirectory scratch("short");
    const fs::path& dir = scratch.path;
    const auto summary = written(samples, dir);
    EXPECT_EQ(summary["blocks"], 3);
    EXPECT_EQ(summary["blocks_requested"], 8);
    EXPECT_EQ(summary["msd_blocks_of_bodies"], 3);
    EXPECT_EQ(readCsv(dir / "vacf.csv").rows(), 3); // lags 0 … (6 − 1)/2
    EXPECT_TRUE(fs::exists(dir / "oacf.csv"));
}

TEST(RunAnalysisFiles, RejectsUnusableSamplesBeforeWritingAnything) {
    const ScratchDirectory scratch("bad");
    const fs::path& dir = scratch.path;
    auto samples = synthetic::ornsteinUhlenbeck(10, 5, 0.1, 20.0, 4.2, 18.0, 2.0, 13);
    EXPECT_THROW(written(samples, dir, options(1)), std::invalid_argument);
    EXPECT_THROW(written(samples, dir, options(2, 0.0, 0.0)), std::invalid_argument);
    EXPECT_THROW(written(samples, dir, options(2, -1.0)), std::invalid_argument);
    samples[3].time *= 1.5;
    EXPECT_THROW(written(samples, dir), std::invalid_argument);
    EXPECT_FALSE(fs::exists(dir));
}

} // namespace test_run_analysis_files
