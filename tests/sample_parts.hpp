#pragma once
// For the engine tests of both engines: what the run driver takes of a sample when nothing needs
// it whole.
#include "core/snapshot.hpp"
#include <gtest/gtest.h>
#include <span>
#include <vector>

namespace terrace::testing {

/// The parts the run driver takes of a sample when nothing needs it whole (some bodies' states,
/// every position) are the whole snapshot's own entries, bit for bit.
template <class E> void expectPartsOfTheSnapshot(const E& e) {
    const Snapshot whole = e.snapshot();
    const std::vector<int> some{whole.size() - 1, 0, whole.size() / 2, 3};
    const Snapshot part = e.snapshot(std::span<const int>(some));
    ASSERT_EQ(part.size(), 4);
    EXPECT_EQ(part.time, whole.time);
    EXPECT_EQ(part.boxLength, whole.boxLength);
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(part.position[k], whole.position[some[k]]);
        EXPECT_EQ(part.velocity[k], whole.velocity[some[k]]);
        EXPECT_EQ(part.axis[k], whole.axis[some[k]]);
        EXPECT_EQ(part.omega[k], whole.omega[some[k]]);
    }
    const Snapshot where = e.positions();
    EXPECT_EQ(where.position, whole.position);
    for (int b = 0; b < whole.size(); ++b) // what a g(r) frame reads, body by body
        ASSERT_EQ(e.position(b), whole.position[b]) << "body " << b;
    EXPECT_TRUE(where.velocity.empty() && where.axis.empty() && where.omega.empty());
    EXPECT_EQ(where.time, whole.time);
}

} // namespace terrace::testing
