// The agendas' storage (dmd/agendas.hpp): a body's block and its spill behave as one vector whose
// removal moves the last event into the gap, whatever the mix of pushes, removals, filters and
// clears, and a spill goes back to the pool once its body's agenda fits its block again.
#include "dmd/agendas.hpp"
#include <gtest/gtest.h>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace test_agendas {

namespace {

using terrace::dmd::Agendas;
using terrace::dmd::EventKind;
using terrace::dmd::PendingEvent;

// Every kind, every side a slot may hold (a level side ±1, a cell face 0–5), partners up to the
// largest an agenda can name and counters over the whole 32 bits: a slot packs all but the time.
PendingEvent event(int id) {
    PendingEvent e;
    e.time = 0.5 * id;
    e.j = id % 7 == 0 ? -1 : id % 11 == 0 ? Agendas::maxBodies - 1 - id % 3 : id;
    e.countJ = static_cast<std::uint32_t>(3 * id) * 2654435761u;
    e.kind = static_cast<EventKind>(id % 5);
    e.side = static_cast<std::int8_t>(id % 8 - 2);
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
    // (a vector grown by doubling holds at most twice what it was asked for; a spilled slot is
    // 16 B)
    const std::size_t oneSpill = 2 * Agendas::inlineEvents * 16 + 64;
    EXPECT_LE(agendas.bytesReserved(), empty + oneSpill);
    for (int i = 0; i < bodies; ++i)
        EXPECT_EQ(agendas.size(i), Agendas::inlineEvents);
}

// A crowd of spills (every body past its block at once, as after a lattice start) that mostly goes
// back leaves its containers idle in the pool: compacting frees them, and the agendas that still
// spill keep every event, in order, and go on as before.
TEST(Agendas, CompactingFreesTheSpillsACrowdLeftIdle) {
    constexpr int bodies = 400;
    Agendas agendas(bodies);
    std::vector<std::vector<PendingEvent>> model(bodies);
    const std::size_t empty = agendas.bytesReserved();
    int id = 1;
    for (int i = 0; i < bodies; ++i)
        for (int k = 0; k < 3 * Agendas::inlineEvents; ++k) {
            model[i].push_back(event(id++));
            agendas.push(i, model[i].back());
        }
    ASSERT_EQ(agendas.spillsHeld(), static_cast<std::size_t>(bodies));
    const std::size_t crowd = agendas.bytesReserved();
    for (int i = 0; i < bodies; ++i)
        while (agendas.size(i) > (i % 10 == 0 ? Agendas::inlineEvents + 2 : 1)) {
            agendas.remove(i, 0);
            model[i][0] = model[i].back();
            model[i].pop_back();
        }
    EXPECT_EQ(agendas.spillsHeld(), static_cast<std::size_t>(bodies / 10));
    EXPECT_EQ(agendas.spillsKept(), static_cast<std::size_t>(bodies)); // idle, not freed
    EXPECT_GE(agendas.bytesReserved(), crowd);
    agendas.compactSpills();
    EXPECT_EQ(agendas.spillsKept(), static_cast<std::size_t>(bodies / 10));
    // What is left: the held spills, each with the capacity its 2·inlineEvents events grew it to
    // (doubling: at most 4·inlineEvents 16-B slots), and their vectors' headers.
    EXPECT_LE(agendas.bytesReserved(),
              empty + bodies / 10 * (4 * Agendas::inlineEvents * 16 + sizeof(std::vector<int>)));
    EXPECT_LT(agendas.bytesReserved(), empty + (crowd - empty) / 5);
    for (int i = 0; i < bodies; ++i) {
        ASSERT_EQ(agendas.size(i), static_cast<int>(model[i].size()));
        for (int k = 0; k < agendas.size(i); ++k)
            expectSame(agendas.at(i, k), model[i][k]);
    }
    // The renumbered spills are the bodies' own: they grow, shrink and return as before.
    for (int i = 0; i < bodies; i += 10) {
        model[i].push_back(event(id++));
        agendas.push(i, model[i].back());
        agendas.remove(i, 1);
        model[i][1] = model[i].back();
        model[i].pop_back();
        for (int k = 0; k < agendas.size(i); ++k)
            expectSame(agendas.at(i, k), model[i][k]);
        agendas.clear(i);
    }
    EXPECT_EQ(agendas.spillsHeld(), 0u);
    agendas.compactSpills(); // nothing to free: 40 idle are within the pool's slack
    EXPECT_EQ(agendas.spillsKept(), static_cast<std::size_t>(bodies / 10));
}

// A partner beyond what a slot can name is refused when the agendas are made, by name.
TEST(Agendas, RefuseMoreBodiesThanASlotCanName) {
    EXPECT_NO_THROW(Agendas(1));
    try {
        Agendas tooMany(Agendas::maxBodies + 1);
        FAIL() << "expected the body count to be refused";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("26 bits"), std::string::npos) << e.what();
    }
}

} // namespace

} // namespace test_agendas
