// The lines a prefetch asks for (dmd/prefetch.hpp): every line an object covers, each once,
// wherever it starts; the layouts the engine prefetches from included.
#include "core/linear_rotor.hpp"
#include "dmd/prefetch.hpp"
#include <gtest/gtest.h>
#include <vector>

namespace test_prefetch {

namespace {

using terrace::dmd::cacheLine;
using terrace::dmd::linesCovered;

TEST(Prefetch, EveryLineAnObjectCoversOnce) {
    // 96-byte objects in an array mapped 16 B past a page (a rod's states, were they not
    // aligned): two lines, then three.
    EXPECT_EQ(linesCovered(4096 + 16, 96).count, 2u);
    EXPECT_EQ(linesCovered(4096 + 16 + 96, 96).count, 3u);
    EXPECT_EQ(linesCovered(4096 + 16 + 96, 96).first, 4096u + 64u);
    // A rod's kept orbit (32 B, 32-aligned) and a book (64 B, 64-aligned): one line.
    EXPECT_EQ(linesCovered(4096 + 32, 32).count, 1u);
    EXPECT_EQ(linesCovered(4096 + 64, 64).count, 1u);
    // An agenda block (256 B, 64-aligned): four; a list record of 176 B: three or four.
    EXPECT_EQ(linesCovered(8192, 256).count, 4u);
    EXPECT_EQ(linesCovered(8192 + 16, 176).count, 3u);
    EXPECT_EQ(linesCovered(8192 + 48, 176).count, 4u);
    // Against a count of the distinct lines byte by byte, at every offset in a line.
    for (std::uintptr_t start = 1024; start < 1024 + cacheLine; ++start)
        for (std::size_t bytes : {1u, 8u, 48u, 63u, 64u, 65u, 96u, 128u, 176u, 256u}) {
            std::size_t distinct = 0;
            for (std::uintptr_t a = start; a < start + bytes; ++a)
                distinct += a == start || a % cacheLine == 0;
            const auto lines = linesCovered(start, bytes);
            EXPECT_EQ(lines.count, distinct) << start << " " << bytes;
            EXPECT_EQ(lines.first, start - start % cacheLine);
        }
}

// A rod's state is aligned to 32 B, so that in any array, a large one that the heap maps 16 B past
// a page included, each covers two lines and a partner's prediction fetches no third.
TEST(Prefetch, EveryRodStateInAnArrayCoversTwoLines) {
    using State = terrace::LinearRotor::State;
    static_assert(sizeof(State) == 96 && alignof(State) == 32);
    for (const std::size_t n : {7u, 20000u}) { // 20 000 states: 1.9 MB, a mapped block
        const std::vector<State> states(n);
        for (std::size_t i = 0; i < n; ++i)
            ASSERT_EQ(
                linesCovered(reinterpret_cast<std::uintptr_t>(&states[i]), sizeof(State)).count, 2u)
                << "state " << i << " of " << n;
    }
}

} // namespace

} // namespace test_prefetch
