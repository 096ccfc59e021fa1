// The engine's small bookkeeping parts on their own: the jittered horizon, the stall watch and
// the bin tuning of the bounded queue.
#include "dmd/bin_tuning.hpp"
#include "dmd/event.hpp"
#include "dmd/horizon_jitter.hpp"
#include "dmd/stall_watch.hpp"
#include <gtest/gtest.h>
#include <set>
#include <stdexcept>

namespace test_engine_parts {

using namespace terrace::dmd;

TEST(HorizonJitter, StaysWithinItsBandAndFollowsTheSeed) {
    HorizonJitter a(0.04, 0.1, 7), b(0.04, 0.1, 7), c(0.04, 0.1, 8);
    std::set<double> seen;
    double lowest = 1.0, highest = 0.0, sum = 0.0;
    constexpr int n = 100000;
    bool differs = false;
    for (int k = 0; k < n; ++k) {
        const double h = a.next();
        EXPECT_EQ(h, b.next()); // same seed, same stream
        differs |= h != c.next();
        lowest = std::min(lowest, h);
        highest = std::max(highest, h);
        sum += h;
        seen.insert(h);
    }
    EXPECT_TRUE(differs);
    EXPECT_GT(lowest, 0.04 * 0.9);
    EXPECT_LE(highest, 0.04);
    // Uniform over [0.9, 1] horizons: the mean's standard error is 0.1/sqrt(12 n) ≈ 9e-5 of the
    // horizon, so 1e-3 is about ten of them.
    constexpr double meanTol = 0.001;
    EXPECT_NEAR(sum / n, 0.04 * 0.95, 0.04 * meanTol);   // uniform: the mean is mid-band
    EXPECT_EQ(seen.size(), static_cast<std::size_t>(n)); // no two horizons coincide
}

TEST(StallWatch, FiresOnlyAfterTheLimitAndResetsWhenTimeMoves) {
    StallWatch w;
    w.setLimit(3);
    for (int k = 0; k < 3; ++k)
        EXPECT_NO_THROW(w.check(1.0, 1.0, 4, 5));
    EXPECT_NO_THROW(w.check(1.0, 1.5, 4, 5)); // the clock moved: count starts again
    for (int k = 0; k < 3; ++k)
        EXPECT_NO_THROW(w.check(1.5, 1.5 + 1e-17, 4, 5)); // round-off is no progress
    try {
        w.check(1.5, 1.5, 4, 5);
        FAIL() << "a stopped clock was not reported";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("bodies 4 and 5"), std::string::npos);
    }
}

TEST(BinTuning, SizesBinsFromTheMeasuredRateAndLead) {
    BoundedPriorityQueue<Event> q(1.0, 4, 0.0);
    BinTuning t(0.04);
    // 8000 pushes over 2 time units, each 0.1 ahead: rate 4000, bins of 8/4000 = 0.002,
    // window 4 × 0.1 = 0.4 → 200 bins.
    for (int k = 0; k < 8000; ++k)
        t.pushed(0.1);
    t.retune(q, 2.0);
    EXPECT_DOUBLE_EQ(q.binWidth(), eventsPerBin / 4000.0);
    EXPECT_EQ(q.binCount(), 200u);
    for (std::uint64_t k = 1; k < retunePeriod; ++k)
        EXPECT_FALSE(t.due());
    EXPECT_TRUE(t.due());
}

} // namespace test_engine_parts
