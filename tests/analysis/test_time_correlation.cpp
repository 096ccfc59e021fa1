// FFT correlation sums against the direct O(T²) sums, and the block-error arithmetic.
#include "analysis/block_average.hpp"
#include "analysis/time_correlation.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <span>

using namespace terrace::analysis;

namespace {

/// FFT and direct sums differ by round-off only: O(ε log M) relative to the largest sum.
constexpr double fftRelativeTolerance = 1e-12;

std::vector<double> randomSeries(int n, std::uint64_t seed, double offset) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g(offset, 1.0);
    std::vector<double> x(n);
    for (double& v : x)
        v = g(rng);
    return x;
}

double largestAbs(const std::vector<double>& c) {
    double m = 0.0;
    for (double v : c)
        m = std::max(m, std::abs(v));
    return m;
}

} // namespace

TEST(FftCorrelation, EqualsDirectSumForOddAndEvenLengths) {
    for (int n : {2, 7, 64, 257, 1000}) {
        const auto x = randomSeries(n, 11 + n, 0.3); // a mean makes wrap-around errors visible
        const int maxLag = n - 1; // every lag, so that wrap-around would show up at once
        const auto direct = crossCorrelationDirect(x, x, maxLag);
        const auto fft = autocorrelationFft(x, maxLag);
        ASSERT_EQ(fft.size(), direct.size());
        const double scale = largestAbs(direct);
        for (int k = 0; k <= maxLag; ++k)
            EXPECT_NEAR(fft[k], direct[k], fftRelativeTolerance * scale)
                << "n " << n << " lag " << k;
    }
}

TEST(FftCorrelation, BlockSumsEqualDirectSumsOverEachBlocksOrigins) {
    const int n = 203, maxLag = 150, blocks = 5;
    BlockedAutocorrelation acf(n, maxLag, blocks);
    const auto x = randomSeries(n, 3, 1.0), y = randomSeries(n, 4, -0.5);
    acf.add(x, 1.0);
    acf.add(y, 2.0);
    const auto sums = acf.sums();
    const OriginBlocks& o = acf.blocks();
    for (int b = 0; b < blocks; ++b) {
        // Direct: a = series restricted to block b's origins, partner = whole series.
        std::vector<double> xb(n, 0.0), yb(n, 0.0);
        for (int t = o.begin(b); t < o.begin(b + 1); ++t)
            xb[t] = x[t], yb[t] = y[t];
        const auto dx = crossCorrelationDirect(xb, x, maxLag);
        const auto dy = crossCorrelationDirect(yb, y, maxLag);
        const double scale = largestAbs(dx) + 2.0 * largestAbs(dy);
        for (int k = 0; k <= maxLag; ++k)
            EXPECT_NEAR(sums[b][k], dx[k] + 2.0 * dy[k], fftRelativeTolerance * scale);
    }
}

TEST(FftCorrelation, BlocksPartitionTheOrigins) {
    const OriginBlocks o{103, 40, 8};
    for (int k : {0, 1, 39, 40}) {
        int total = 0;
        for (int b = 0; b < o.blocks; ++b)
            total += o.origins(b, k);
        EXPECT_EQ(total, o.samples - k) << "lag " << k;
    }
    EXPECT_EQ(o.begin(0), 0);
    EXPECT_EQ(o.begin(o.blocks), o.samples);
}

TEST(FftCorrelation, RejectsLagsThatWouldWrapOrEmptySeries) {
    EXPECT_THROW(BlockedAutocorrelation(10, 10, 1), std::invalid_argument);
    EXPECT_THROW(BlockedAutocorrelation(1, 0, 1), std::invalid_argument);
    EXPECT_THROW(BlockedAutocorrelation(10, 3, 11), std::invalid_argument);
    BlockedAutocorrelation acf(10, 3, 2);
    const std::vector<double> wrong(9, 1.0);
    EXPECT_THROW(acf.add(wrong), std::invalid_argument);
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
