// The agendas' storage (dmd/agendas.hpp): a body's block and its spill behave as one vector whose
// removal moves the last event into the gap, whatever the mix of pushes, removals, filters and
// clears, and a spill goes back to the pool once its body's agenda fits its block again.
#include "dmd/agendas.hpp"
#include <gtest/gtest.h>
#include <random>
#include <vector>

namespace {

using terrace::dmd::Agendas;
using terrace::dmd::EventKind;
using terrace::dmd::PendingEvent;

PendingEvent event(int id) {
    PendingEvent e;
    e.time = 0.5 * id;
    e.j = id % 7 == 0 ? -1 : id;
    e.countJ = static_cast<std::uint32_t>(3 * id);
    e.kind = id % 3 == 0 ? EventKind::Collision : EventKind::Virtual;
    e.side = static_cast<std::int8_t>(id % 5 - 2);
    return e;
}

void expectSame(const PendingEvent& a, const PendingEvent& b) {
    EXPECT_EQ(a.time, b.time);
    EXPECT_EQ(a.j, b.j);
    EXPECT_EQ(a.countJ, b.countJ);
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.side, b.side);
}

// Three bodies driven at random against three std::vectors with the same removal rule.
TEST(Agendas, BehaveAsVectorsWithSwapRemoval) {
    constexpr int bodies = 3;
    Agendas agendas(bodies);
    std::vector<std::vector<PendingEvent>> model(bodies);
    std::mt19937 rng(12345);
    int id = 1;
    int spilled = 0; // pushes that went past a block
    for (int step = 0; step < 20000; ++step) {
        const int i = static_cast<int>(rng() % bodies);
        auto& m = model[i];
        const unsigned action = rng() % 100;
        if (action < 55 || m.empty()) { // push, so that agendas reach past their blocks
            const PendingEvent e = event(id++);
            const int slot = agendas.push(i, e);
            EXPECT_EQ(slot, static_cast<int>(m.size()));
            spilled += slot >= Agendas::inlineEvents;
            m.push_back(e);
        } else if (action < 90) { // remove a slot
            const int k = static_cast<int>(rng() % m.size());
            agendas.remove(i, k);
            m[k] = m.back();
            m.pop_back();
        } else if (action < 97) { // keep only some
            const int modulus = 2 + static_cast<int>(rng() % 3);
            auto keep = [&](const PendingEvent& e) { return e.countJ % modulus != 0; };
            const int dropped = agendas.keepIf(i, keep);
            const auto before = m.size();
            std::erase_if(m, [&](const PendingEvent& e) { return !keep(e); });
            EXPECT_EQ(dropped, static_cast<int>(before - m.size()));
        } else {
            agendas.clear(i);
            m.clear();
        }
        ASSERT_EQ(agendas.size(i), static_cast<int>(m.size()));
        for (int k = 0; k < agendas.size(i); ++k) {
            expectSame(agendas.at(i, k), m[k]);
            ASSERT_EQ(agendas.time(i, k), m[k].time);
        }
    }
    EXPECT_GT(spilled, 200) << "the test must exercise the spill";
    std::size_t waiting = 0;
    for (const auto& m : model)
        waiting += m.size();
    EXPECT_EQ(agendas.events(), waiting);
}

// A spill is returned when its agenda fits the block again, and taken again by the next body
// that needs one: the memory of many bodies that spill in turn is that of one spill.
TEST(Agendas, SpillsAreReturnedAndReused) {
    constexpr int bodies = 64;
    Agendas agendas(bodies);
    const std::size_t empty = agendas.bytesReserved();
    for (int i = 0; i < bodies; ++i) {
        for (int k = 0; k < 2 * Agendas::inlineEvents; ++k)
            agendas.push(i, event(k + 1));
        while (agendas.size(i) > Agendas::inlineEvents)
            agendas.remove(i, 0);
    }
    // (a vector grown by doubling holds at most twice what it was asked for)
    const std::size_t oneSpill = 2 * Agendas::inlineEvents * sizeof(PendingEvent) + 64;
    EXPECT_LE(agendas.bytesReserved(), empty + oneSpill);
    for (int i = 0; i < bodies; ++i)
        EXPECT_EQ(agendas.size(i), Agendas::inlineEvents);
}

} // namespace
