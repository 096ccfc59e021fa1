// The FFT windows of the linear lags against the direct sums over every origin (the reference),
// fine block by fine block and group by group, whatever the run's length does to the last
// blocks; and the block-error arithmetic.
#include "analysis/block_average.hpp"
#include "analysis/curves.hpp"
#include "analysis/windowed_correlation.hpp"
#include "synthetic_samples.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <random>

namespace test_windowed_correlation {

using namespace terrace;
using namespace terrace::analysis;

namespace {

/// FFT and direct sums differ by round-off only: O(ε log W) relative to the sum of the terms'
/// magnitudes (a few hundred terms of size ~1 here).
constexpr double fftRelativeTolerance = 1e-12;

/// Rotors whose velocities are white noise and whose centres random-walk, so that no lag's sum
/// is trivially alike another's; unwrapped positions start anywhere in a 25-Å box.
std::vector<Snapshot> noisySamples(int samples, int bodies, std::uint64_t seed) {
    auto s = synthetic::freeRotors(samples, bodies, 0.05, 25.0, 4.2, 18.0, 1.154, seed);
    std::mt19937_64 rng(seed + 1);
    for (int k = 0; k < samples; ++k)
        for (int i = 0; i < bodies; ++i) {
            s[k].velocity[i] = synthetic::gaussianVector(rng, 1.0);
            if (k > 0)
                s[k].position[i] = s[k - 1].position[i] + synthetic::gaussianVector(rng, 0.3);
        }
    return s;
}

/// The direct sums of the first `seen` samples that WindowedCorrelation keeps, lags < lags.
LagSums directSums(const std::vector<Snapshot>& s, long seen, int lags, long planned, int fine,
                   int groups) {
    const int m = s.front().size();
    LagSums d;
    d.vv.assign(fine, std::vector<double>(lags, 0.0));
    d.ss = d.s2 = d.origins = d.vv;
    d.msd.assign(groups, std::vector<double>(lags, 0.0));
    d.msdOrigins.assign(lags, 0.0);
    for (long t0 = 0; t0 < seen; ++t0) {
        const int f = fineBlockOfSample(t0, planned, fine);
        for (int k = 0; k < lags && t0 + k < seen; ++k) {
            const Snapshot &a = s[t0], &b = s[t0 + k];
            for (int i = 0; i < m; ++i) {
                const double c = a.axis[i].dot(b.axis[i]);
                d.vv[f][k] += a.velocity[i].dot(b.velocity[i]);
                d.ss[f][k] += c, d.s2[f][k] += c * c;
                const int g = static_cast<int>((long(i) * groups + groups - 1) / m);
                d.msd[g][k] += (b.position[i] - a.position[i]).squaredNorm();
            }
            d.origins[f][k] += 1.0, d.msdOrigins[k] += 1.0;
        }
    }
    return d;
}

void expectNear(const std::vector<std::vector<double>>& x,
                const std::vector<std::vector<double>>& y, double scale, const char* what) {
    ASSERT_EQ(x.size(), y.size()) << what;
    for (std::size_t b = 0; b < x.size(); ++b)
        for (std::size_t k = 0; k < x[b].size(); ++k)
            EXPECT_NEAR(x[b][k], y[b][k], fftRelativeTolerance * scale)
                << what << " block " << b << " lag " << k;
}

/// Feeds samples and compares with the direct sums after each of `checks` samples.
void compare(const std::vector<Snapshot>& s, int window, int lags, long planned, int fine,
             int groups, const std::vector<long>& checks) {
    WindowedCorrelation w(s.front().size(), window, lags, planned, fine, groups);
    long fed = 0;
    for (const long upTo : checks) {
        while (fed < upTo)
            w.add(s[fed++], nullptr);
        const LagSums fft = w.sums(), direct = directSums(s, upTo, lags, planned, fine, groups);
        const double scale = double(s.front().size()) * double(upTo) * 10.0; // Σ |terms|
        SCOPED_TRACE("W " + std::to_string(window) + ", " + std::to_string(upTo) + " samples");
        expectNear(fft.vv, direct.vv, scale, "vv");
        expectNear(fft.ss, direct.ss, scale, "ss");
        expectNear(fft.s2, direct.s2, scale, "s2");
        expectNear(fft.msd, direct.msd, scale, "msd");
        EXPECT_EQ(fft.origins, direct.origins);
        EXPECT_EQ(fft.msdOrigins, direct.msdOrigins);
    }
}

} // namespace

TEST(WindowedCorrelation, LinearLagsEqualTheDirectSumsOverEveryOrigin) {
    const auto s = noisySamples(150, 23, 3);
    // Runs ending mid-block, on a block's end, before the first window is whole and before the
    // first block is: each a last partial block handled exactly. Read, then fed on.
    compare(s, 16, 16, 150, 32, 8, {5, 16, 20, 32, 47, 150});
    compare(s, 8, 6, 150, 12, 3, {3, 9, 64, 149});
    compare(s, 4, 4, 150, 32, 1, {150});
}

TEST(WindowedCorrelation, FineBlocksThatCutAWindowGetTheirOwnOrigins) {
    // 7 fine blocks over 100 planned samples cut most windows of 16; a run stopped at 61 samples
    // leaves the later fine blocks empty.
    const auto s = noisySamples(100, 9, 5);
    compare(s, 16, 16, 100, 7, 2, {61});
    compare(s, 16, 16, 100, 7, 2, {100});
    compare(s, 16, 16, 40, 7, 2, {100}); // samples beyond the plan join the last fine block
}

TEST(WindowedCorrelation, RefusesLagsBeyondTheWindow) {
    EXPECT_THROW(WindowedCorrelation(10, 8, 9, 100, 4, 2), std::invalid_argument);
    EXPECT_THROW(WindowedCorrelation(10, 8, 8, 100, 4, 11), std::invalid_argument);
    EXPECT_THROW(WindowedCorrelation(0, 8, 8, 100, 4, 1), std::invalid_argument);
}

TEST(BlockAverage, EqualWeightsGiveTheStandardErrorOfTheMean) {
    const std::vector<double> v{1.0, 2.0, 3.0, 6.0}, w(4, 1.0);
    // mean 3, Σ(v − 3)² = 14, err² = 14 / (4·3)
    EXPECT_DOUBLE_EQ(blockError(v, w, 3.0), std::sqrt(14.0 / 12.0));
    const std::vector<double> sums{2.0, 4.0, 6.0, 12.0}, weights(4, 2.0);
    const Estimate e = blockRatio(sums, weights);
    EXPECT_DOUBLE_EQ(e.mean, 3.0);
    EXPECT_DOUBLE_EQ(e.err, std::sqrt(14.0 / 12.0));
}

TEST(BlockAverage, EmptyBlocksDoNotCountAndOneBlockGivesNoError) {
    const std::vector<double> v{1.0, 3.0, 100.0}, w{1.0, 1.0, 0.0};
    EXPECT_DOUBLE_EQ(blockError(v, w, 2.0), 1.0); // (1 + 1)/4 · 2/1 = 1
    const std::vector<double> one{1.0, 0.0};
    EXPECT_TRUE(std::isnan(blockError(std::vector<double>{5.0, 7.0}, one, 5.0)));
}

TEST(BlockAverage, ATimeSeriesIsCutIntoContiguousBlocks) {
    // 8 samples in 4 blocks of 2: block means 1.5, 3.5, 5.5, 7.5; mean 4.5, err² = 20 / (4·3)
    const std::vector<double> x{1, 2, 3, 4, 5, 6, 7, 8};
    const Estimate e = blockMean(x, 4);
    EXPECT_DOUBLE_EQ(e.mean, 4.5);
    EXPECT_DOUBLE_EQ(e.err, std::sqrt(20.0 / 12.0));
    // 3 samples in 8 blocks: 5 blocks empty, each sample its own block.
    const Estimate few = blockMean(std::vector<double>{1.0, 2.0, 6.0}, 8);
    EXPECT_DOUBLE_EQ(few.mean, 3.0);
    EXPECT_DOUBLE_EQ(few.err, std::sqrt(14.0 / 6.0)); // Σ(x − 3)² / (3·2)
    EXPECT_TRUE(std::isnan(blockMean(std::vector<double>{2.0}, 8).err));
    EXPECT_THROW(blockMean(std::vector<double>{}, 8), std::invalid_argument);
}

} // namespace test_windowed_correlation
