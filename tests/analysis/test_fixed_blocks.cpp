// Block means laid out before the samples come (analysis/fixed_blocks.hpp): a series that reaches
// its planned length gives blockMean's numbers bit for bit; one stopped short counts its part-
// filled blocks by their samples; the state goes on to the same bits; the plan is a bound.
#include "analysis/fixed_blocks.hpp"
#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <random>
#include <vector>

namespace test_fixed_blocks {

using namespace terrace::analysis;

namespace {

std::vector<double> noise(std::size_t n, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> d(-1200.0, 3.0);
    std::vector<double> x(n);
    for (double& v : x)
        v = d(rng);
    return x;
}

bool sameBits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

} // namespace

TEST(FixedBlocks, AWholeSeriesGivesBlockMeansNumbersBitForBit) {
    for (const int blocks : {1, 2, 8, 13})
        for (std::size_t n = 1; n <= 60; ++n) {
            const auto x = noise(n, unsigned(n));
            FixedBlocks f(long(n), blocks);
            for (double v : x)
                f.add(v);
            const Estimate a = f.estimate(), b = blockMean(x, blocks);
            EXPECT_TRUE(sameBits(a.mean, b.mean)) << n << " in " << blocks;
            EXPECT_TRUE(sameBits(a.err, b.err) || (std::isnan(a.err) && std::isnan(b.err)))
                << n << " in " << blocks << ": " << a.err << " vs " << b.err;
            EXPECT_EQ(a.samples, b.samples);
        }
}

// Stopped at 10 of 16 planned samples in 4 blocks: blocks of 4, 4, 2 and none, weighted by their
// samples (blockRatio), not 4 blocks laid over the 10.
TEST(FixedBlocks, ASeriesStoppedShortCountsItsBlocksBySamples) {
    const auto x = noise(10, 7);
    FixedBlocks f(16, 4);
    for (double v : x)
        f.add(v);
    const std::vector<double> sums{x[0] + x[1] + x[2] + x[3], x[4] + x[5] + x[6] + x[7],
                                   x[8] + x[9], 0.0};
    const Estimate expected = blockRatio(sums, std::vector<double>{4, 4, 2, 0});
    const Estimate got = f.estimate();
    EXPECT_DOUBLE_EQ(got.mean, expected.mean);
    EXPECT_DOUBLE_EQ(got.err, expected.err);
    EXPECT_EQ(got.samples, 3);
    double mean = 0.0;
    for (double v : x)
        mean += v / 10.0;
    EXPECT_NEAR(got.mean, mean, 1e-12 * std::abs(mean));
}

TEST(FixedBlocks, MoreSamplesThanPlannedAreRefused) {
    FixedBlocks f(3, 8);
    f.add(1.0), f.add(2.0), f.add(3.0);
    EXPECT_THROW(f.add(4.0), std::out_of_range);
    EXPECT_THROW(FixedBlocks(5, 0), std::invalid_argument);
    EXPECT_THROW(FixedBlocks(-1, 8), std::invalid_argument);
    EXPECT_THROW(FixedBlocks(5, 8).estimate(), std::invalid_argument); // no sample yet
}

// Written after 37 of 100 samples and read into blocks of the same plan, it goes on to the same
// bits as the blocks that never stopped; the same size after 1 sample as after 99; a state of
// another plan is refused.
TEST(FixedBlocks, ItsStateGoesOnToTheSameBits) {
    const auto x = noise(100, 11);
    FixedBlocks whole(100, 8), first(100, 8);
    for (std::size_t k = 0; k < 37; ++k)
        whole.add(x[k]), first.add(x[k]);
    StateWriter out;
    first.write(out);
    const auto bytes = out.take();
    FixedBlocks second(100, 8);
    StateReader in(bytes);
    second.read(in, "blocks");
    in.finish();
    for (std::size_t k = 37; k < 100; ++k)
        whole.add(x[k]), second.add(x[k]);
    EXPECT_TRUE(sameBits(whole.estimate().mean, second.estimate().mean));
    EXPECT_TRUE(sameBits(whole.estimate().err, second.estimate().err));
    StateWriter full;
    second.write(full);
    EXPECT_EQ(full.take().size(), bytes.size());
    FixedBlocks other(200, 8);
    StateReader again(bytes);
    EXPECT_THROW(other.read(again, "blocks"), std::invalid_argument);
    FixedBlocks fewer(100, 4);
    StateReader once_more(bytes);
    EXPECT_THROW(fewer.read(once_more, "blocks"), std::invalid_argument);
}

} // namespace test_fixed_blocks
