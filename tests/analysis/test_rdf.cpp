// Centre-of-mass g(r) as a run accumulates it: ideal gas gives 1, a simple cubic lattice gives its
// shells and their coordination numbers.
#include "analysis/rdf_accumulator.hpp"
#include "synthetic_samples.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <random>
#include <string>

namespace test_rdf {

using namespace terrace;
using namespace terrace::analysis;

namespace {

/// Pair counts of uniformly random points are Poisson-like; 5 standard deviations per bin keeps
/// a false alarm over 40 bins below 1e-4 while a 1 − 1/N normalisation slip (1 %) is caught
/// by the pooled check below.
constexpr double poissonSigmas = 5.0;
/// Pooled g over all pairs within L/2 of an ideal gas: 1 to within its Poisson error (~0.2 %
/// here); a relative tolerance of 0.5 % catches an N² instead of N(N−1) normalisation (1 %).
constexpr double pooledIdealTolerance = 0.005;
/// Block error bars must match the Poisson error to within their own scatter (8 blocks: ±25 %
/// per bin, far less averaged over 40 bins).
constexpr double errorRatioLow = 0.8, errorRatioHigh = 1.25;
/// Coordination numbers of a perfect lattice are integers, up to the round-off of the shells.
constexpr double coordinationTolerance = 1e-9;

/// g(r) out to L/2 of all the frames, in `blocks` blocks.
RadialDistribution accumulated(const std::vector<Snapshot>& frames, double bin, int blocks) {
    const double length = frames.front().boxLength;
    RdfAccumulator acc(frames.front().size(), length, bin, 0.5 * length,
                       static_cast<long>(frames.size()), blocks);
    for (const auto& f : frames)
        acc.add(f);
    return acc.result();
}

/// Mean number of neighbours within rMax of a body, 4π ρ' ∫₀^rMax g r² dr over whole bins,
/// ρ' = (N − 1)/V: what the normalisation of g must give back on a lattice.
double neighboursWithin(const RadialDistribution& rdf, double rMax, int bodies, double length) {
    const double density = (bodies - 1.0) / (length * length * length);
    double n = 0.0;
    for (std::size_t k = 0; k < rdf.r.size(); ++k) {
        const double lo = k * rdf.binWidth, hi = (k + 1) * rdf.binWidth;
        if (hi > rMax) break;
        n += density * rdf.g[k] * 4.0 / 3.0 * std::numbers::pi * (hi * hi * hi - lo * lo * lo);
    }
    return n;
}

} // namespace

TEST(RadialDistribution, IdealGasIsOneWithinNoise) {
    const int n = 100, frames = 200, blocks = 8;
    const double length = 20.0, bin = 0.25;
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> uniform(-length, 2.0 * length); // unwrapped
    auto samples = synthetic::emptySamples(frames, n, 0.1, length);
    for (auto& f : samples)
        for (auto& r : f.position)
            r = {uniform(rng), uniform(rng), uniform(rng)};
    const auto rdf = accumulated(samples, bin, blocks);
    ASSERT_EQ(rdf.r.size(), 40u);

    double counted = 0.0, expected = 0.0, ratio = 0.0;
    const double volume = length * length * length, pairs = frames * 0.5 * n * (n - 1.0);
    for (std::size_t k = 0; k < rdf.r.size(); ++k) {
        const double lo = k * bin, hi = lo + bin;
        const double ideal =
            pairs * 4.0 / 3.0 * std::numbers::pi * (hi * hi * hi - lo * lo * lo) / volume;
        const double poisson = 1.0 / std::sqrt(ideal);
        if (ideal > 100.0) { // bins with enough pairs for a Gaussian error
            EXPECT_NEAR(rdf.g[k], 1.0, poissonSigmas * poisson) << "r = " << rdf.r[k];
        }
        counted += rdf.g[k] * ideal, expected += ideal;
        ratio += rdf.err[k] / poisson / rdf.r.size();
    }
    EXPECT_NEAR(counted / expected, 1.0, pooledIdealTolerance);
    EXPECT_GT(ratio, errorRatioLow);
    EXPECT_LT(ratio, errorRatioHigh);
}

TEST(RadialDistribution, SimpleCubicLatticeHasItsShellsAndCoordinationNumbers) {
    const int m = 6, n = m * m * m;
    const double a = 3.01, length = m * a, bin = 0.05; // a off the bin edges
    std::mt19937_64 rng(7);
    std::uniform_int_distribution<int> image(-2, 2);
    auto samples = synthetic::emptySamples(2, n, 0.1, length);
    for (int f = 0; f < 2; ++f) {
        const Vec3 shift = Vec3(0.3, 1.1, 2.9) * f; // a rigid translation changes nothing
        int i = 0;
        for (int x = 0; x < m; ++x)
            for (int y = 0; y < m; ++y)
                for (int z = 0; z < m; ++z, ++i) // unwrapped: random periodic images
                    samples[f].position[i] = a * Vec3(x, y, z) + shift +
                                             length * Vec3(image(rng), image(rng), image(rng));
    }
    const auto rdf = accumulated(samples, bin, 2);

    // Shells of the simple cubic lattice inside L/2 = 3a: distance a√q and its multiplicity.
    const std::vector<std::pair<int, int>> shells{{1, 6},  {2, 12}, {3, 8}, {4, 6},
                                                  {5, 24}, {6, 24}, {8, 12}};
    for (std::size_t k = 0; k < rdf.r.size(); ++k) {
        const double lo = k * bin, hi = lo + bin;
        bool holdsShell = false;
        for (auto [q, count] : shells)
            holdsShell |= (a * std::sqrt(q) >= lo && a * std::sqrt(q) < hi);
        if (holdsShell) {
            EXPECT_GT(rdf.g[k], 0.0) << "shell missing at r = " << rdf.r[k];
        } else {
            EXPECT_EQ(rdf.g[k], 0.0) << "spurious pair at r = " << rdf.r[k];
        }
        EXPECT_EQ(rdf.err[k], 0.0); // two identical frames
    }
    int cumulative = 0;
    for (std::size_t s = 0; s < shells.size(); ++s) {
        cumulative += shells[s].second;
        const double next = s + 1 < shells.size() ? a * std::sqrt(shells[s + 1].first) : 3.0 * a;
        const double between = 0.5 * (a * std::sqrt(shells[s].first) + next);
        EXPECT_NEAR(neighboursWithin(rdf, between, n, length), cumulative, coordinationTolerance)
            << "within " << between << " Å";
    }
}

TEST(RadialDistribution, RejectsChangingBoxesAndBadBins) {
    auto samples = synthetic::emptySamples(4, 3, 0.1, 10.0);
    EXPECT_THROW(RdfAccumulator(3, 10.0, 0.0, 5.0, 4, 2), std::invalid_argument);
    EXPECT_THROW(RdfAccumulator(3, 10.0, 6.0, 5.0, 4, 2), std::invalid_argument);
    EXPECT_THROW(RdfAccumulator(3, 10.0, 0.1, 5.0, 4, 5), std::invalid_argument);
    // A damaged trajectory's box: r_max = L/2 of 3e18 Å in 0.05 Å bins is more bins than an int
    // holds (found by fuzzing `terrace analyse`). A box of 1e12 r_max across is fine: its cells
    // are capped before the count is cast.
    // The error names the bin count: a count cast to an int first came out negative in a
    // release build and was refused only by chance, as "the bin is wider than r_max".
    try {
        RdfAccumulator(3, 3e18, 0.05, 1.5e18, 4, 2);
        ADD_FAILURE() << "3e19 bins accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("asks for 3e+19 bins"), std::string::npos) << e.what();
    }
    EXPECT_NO_THROW(RdfAccumulator(3, 5e12, 0.1, 5.0, 4, 2));
    RdfAccumulator acc(3, 10.0, 0.1, 5.0, 4, 2);
    acc.add(samples[0]);
    samples[1].boxLength = 11.0;
    EXPECT_THROW(acc.add(samples[1]), std::invalid_argument);
}

} // namespace test_rdf
