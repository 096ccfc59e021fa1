// The analysis' state as a restart file keeps it (analysis/state_bytes.hpp): an analysis restored
// from it after any sample goes on to write the same bytes as one that never stopped, its size is
// fixed by the settings whatever the samples taken, and a state that does not fit is refused.
#include "analysis/run_analysis.hpp"
#include "core/output_file.hpp"
#include "synthetic_samples.hpp"
#include <filesystem>
#include <gtest/gtest.h>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <unistd.h>

namespace test_analysis_state {

using namespace terrace;
using namespace terrace::analysis;
namespace fs = std::filesystem;

namespace {

constexpr double intervalPs = 0.01;

/// Several levels of lags (p = 4), followed bodies fewer than the bodies, g(r) every third sample
/// with a terracing profile: every accumulator has state to keep.
StreamingOptions settings(int blocks = 4) {
    StreamingOptions o;
    o.blocks = blocks;
    o.lagsPerLevel = 4;
    o.followBodies = 16;
    o.rdfEvery = 3;
    o.rdfBinAngstrom = 0.25;
    o.beta = 0.4;
    return o;
}

std::vector<Snapshot> samples() {
    return synthetic::freeRotors(150, 40, units::fromPs(intervalPs), 25.0, 4.2, 18.0, 1.154, 7);
}

std::unique_ptr<RunAnalysis> fresh(const std::vector<Snapshot>& s,
                                   const StreamingOptions& o = settings()) {
    return std::make_unique<RunAnalysis>(s.front().size(), s.front().boxLength, intervalPs,
                                         long(s.size()), o);
}

/// Sample k into the analysis, with the pair weights an engine would put into its terracing
/// profile on a g(r) frame.
void add(RunAnalysis& a, const Snapshot& sample, long k) {
    if (a.wantsPositions())
        for (int p = 0; p < 20; ++p)
            a.terracing()->add(0.37 * double(p) + 0.01 * double(k % 7), 0.05 * double(p - k % 5));
    a.add(sample);
}

struct Written {
    std::map<std::string, std::string> files;
    std::string summary;
};

Written writtenBy(const RunAnalysis& a, const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("terrace_state_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    Written w;
    w.summary = a.write(dir).dump();
    for (const char* f : {"rdf.csv", "vacf.csv", "oacf.csv", "msd.csv"})
        w.files[f] = readWholeFile(dir / f);
    fs::remove_all(dir);
    return w;
}

} // namespace

// Cut after samples at and around the FFT's block edges (W = 4), the coarser levels' strides and
// g(r)'s frames, restored into a new analysis (its state through bytes alone) and continued: the
// same files and summary, byte for byte, as the analysis that took every sample in one go.
TEST(AnalysisState, ARestoredAnalysisWritesTheSameBytesAsOneThatNeverStopped) {
    const auto s = samples();
    auto whole = fresh(s);
    for (long k = 0; k < long(s.size()); ++k)
        add(*whole, s[k], k);
    const Written expected = writtenBy(*whole, "whole");
    for (const long cut : {1L, 3L, 4L, 5L, 8L, 9L, 37L, 64L, 100L, 149L}) {
        auto before = fresh(s);
        for (long k = 0; k < cut; ++k)
            add(*before, s[k], k);
        const std::vector<std::uint8_t> state = before->state();
        before.reset();
        auto after = fresh(s);
        after->restore(state);
        ASSERT_EQ(after->samples(), cut);
        for (long k = cut; k < long(s.size()); ++k)
            add(*after, s[k], k);
        const Written got = writtenBy(*after, "cut");
        EXPECT_EQ(got.summary, expected.summary) << "cut after " << cut;
        for (const auto& [name, bytes] : expected.files)
            EXPECT_EQ(got.files.at(name), bytes) << name << ", cut after " << cut;
    }
}

// The state holds the accumulators, not the samples: the same number of bytes after one sample
// as after all of them (a history of the followed bodies alone would add 16 × 16 doubles a
// sample).
TEST(AnalysisState, ItsSizeIsFixedByTheSettings) {
    const auto s = samples();
    auto a = fresh(s);
    const std::size_t empty = a->state().size();
    for (long k = 0; k < long(s.size()); ++k) {
        add(*a, s[k], k);
        if (k == 0 || k == 9 || k == 149) {
            EXPECT_EQ(a->state().size(), empty) << "sample " << k;
        }
    }
}

// A state cut short anywhere, lengthened, or written by an analysis of other settings is refused
// with std::invalid_argument, never misread.
TEST(AnalysisState, AStateThatDoesNotFitIsRefused) {
    const auto s = samples();
    auto a = fresh(s);
    for (long k = 0; k < 10; ++k)
        add(*a, s[k], k);
    const std::vector<std::uint8_t> state = a->state();
    for (std::size_t size = 0; size < state.size(); size += 1 + size / 64) {
        auto b = fresh(s);
        EXPECT_THROW(b->restore(std::span(state).first(size)), std::invalid_argument)
            << size << " of " << state.size() << " bytes";
    }
    std::vector<std::uint8_t> longer = state;
    longer.push_back(0);
    EXPECT_THROW(fresh(s)->restore(longer), std::invalid_argument);
    EXPECT_THROW(fresh(s, settings(5))->restore(state), std::invalid_argument);
    StreamingOptions other = settings();
    other.lagsPerLevel = 6;
    EXPECT_THROW(fresh(s, other)->restore(state), std::invalid_argument);
    other = settings();
    other.beta = 0.0; // no terracing profile
    EXPECT_THROW(fresh(s, other)->restore(state), std::invalid_argument);
    try {
        fresh(s, settings(5))->restore(state);
    } catch (const std::invalid_argument& e) {
        EXPECT_EQ(std::string(e.what()).rfind("analysis state: ", 0), 0u) << e.what();
    }
}

} // namespace test_analysis_state
