// Event queues (dmd/binary_heap_queue.hpp, dmd/bounded_priority_queue.hpp,
// dmd/tournament_queue.hpp) against an obviously
// correct reference: a std::map keyed by (time, push sequence), the order both queues promise.
//
// Every queue is driven through random push / pop / erase sequences whose times include exact ties,
// events "now" and a rounding error in the past, and events far beyond the bounded queue's window;
// pops must agree with the reference event by event. The bounded queue runs under several bin
// layouts, including degenerate ones (a single bin, bins much wider than the event horizon), so
// that the overflow rescan, the jump over empty bins and the current-bin heap are all exercised.
#include "dmd/binary_heap_queue.hpp"
#include "dmd/bounded_priority_queue.hpp"
#include "dmd/event.hpp"
#include "dmd/tournament_queue.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <map>
#include <new>
#include <random>
#include <utility>
#include <vector>

// Counts every allocation in this test program, so that a test can check that a queue in its
// steady state pushes without touching the allocator. Not inlined: GCC would otherwise see free()
// applied to the result of operator new at call sites and warn (-Wmismatched-new-delete), although
// the pair is malloc/free by construction.
namespace {
std::size_t allocationCount = 0;
}
[[gnu::noinline]] void* operator new(std::size_t bytes) {
    ++allocationCount;
    if (void* p = std::malloc(bytes)) return p;
    throw std::bad_alloc();
}
[[gnu::noinline]] void operator delete(void* p) noexcept {
    std::free(p);
}
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}

namespace terrace::dmd::test_event_queue {

struct TestEvent {
    double time = 0.0; // time units
    std::uint32_t id = 0;
};

static_assert(EventQueue<BinaryHeapQueue<TestEvent>, TestEvent>);
static_assert(EventQueue<BoundedPriorityQueue<TestEvent>, TestEvent>);

// Bin layouts of the bounded queue, as default-constructible types for the typed tests.
struct BpqTypical : BoundedPriorityQueue<TestEvent> { // window ≈ the mean horizon
    BpqTypical() : BoundedPriorityQueue(0.02, 64, 0.0) {}
};
struct BpqSingleBin : BoundedPriorityQueue<TestEvent> { // everything beyond "now" overflows
    BpqSingleBin() : BoundedPriorityQueue(0.05, 1, 0.0) {}
};
struct BpqWideBins : BoundedPriorityQueue<TestEvent> { // the whole horizon in one bin
    BpqWideBins() : BoundedPriorityQueue(50.0, 4, 0.0) {}
};
struct BpqNegativeStart : BoundedPriorityQueue<TestEvent> { // bins below zero, mod arithmetic
    BpqNegativeStart() : BoundedPriorityQueue(0.3, 7, -5.0) {}
};

// Seeds of the named random streams below.
constexpr std::uint64_t kRandomOpsSeed = 7001;
constexpr std::uint64_t kStressSeed = 7002;
constexpr std::uint64_t kRetuneSeed = 7003;

// The reference: ordered by (time, sequence), with the sequence counted exactly as the queues do.
class ReferenceQueue {
public:
    void push(const TestEvent& e) {
        const Key key{e.time, sequence_++};
        events_.emplace(key, e.id);
        keyOf_.emplace(e.id, key);
    }
    std::uint32_t topId() const { return events_.begin()->second; }
    double topTime() const { return events_.begin()->first.first; }
    void pop() {
        keyOf_.erase(events_.begin()->second);
        events_.erase(events_.begin());
    }
    void erase(std::uint32_t id) {
        events_.erase(keyOf_.at(id));
        keyOf_.erase(id);
    }
    std::size_t size() const { return events_.size(); }
    template <class Pred> std::size_t removeIf(Pred pred) {
        std::size_t removed = 0;
        for (auto it = events_.begin(); it != events_.end();) {
            if (!pred(TestEvent{it->first.first, it->second})) {
                ++it;
                continue;
            }
            keyOf_.erase(it->second);
            it = events_.erase(it);
            ++removed;
        }
        return removed;
    }

private:
    using Key = std::pair<double, std::uint64_t>;
    std::map<Key, std::uint32_t> events_;
    std::map<std::uint32_t, Key> keyOf_;
    std::uint64_t sequence_ = 0;
};

// Drives one queue and the reference through the same random operations, checking every pop.
template <class Q> class Driver {
public:
    explicit Driver(std::uint64_t seed) : rng_(seed) {}

    Q queue;
    ReferenceQueue reference;
    double now = 0.0;

    // A delay mix like an event calendar's: mostly exponential, some exact ties, events "now" and
    // one rounding error in the past, and a tail far beyond any bounded window.
    double drawTime() {
        const double u = uniform_(rng_);
        if (u < 0.65) return now + exponential_(rng_);
        if (u < 0.75) return now + 0.125 * std::floor(8.0 * uniform_(rng_)); // ties on a grid
        if (u < 0.82) return now;
        if (u < 0.88) return std::nextafter(now, -1e300); // round-off: slightly in the past
        return now + 1000.0 * uniform_(rng_);
    }

    void push(double time) {
        const TestEvent e{time, nextId_++};
        slotOf_.push_back(live_.size());
        live_.push_back({e.id, queue.push(e)});
        reference.push(e);
    }

    void pop() {
        ASSERT_FALSE(queue.empty());
        ASSERT_EQ(queue.top().id, reference.topId());
        ASSERT_EQ(queue.top().time, reference.topTime());
        now = queue.top().time;
        forget(queue.top().id);
        queue.pop();
        reference.pop();
    }

    void eraseRandomLive() {
        if (live_.empty()) return;
        const std::size_t k = std::uniform_int_distribution<std::size_t>(0, live_.size() - 1)(rng_);
        const auto [id, handle] = live_[k];
        ASSERT_TRUE(queue.erase(handle));
        reference.erase(id);
        forget(id);
    }

    void eraseRandomDead() {
        if (dead_.empty()) return;
        const std::size_t k = std::uniform_int_distribution<std::size_t>(0, dead_.size() - 1)(rng_);
        const std::size_t before = queue.size();
        ASSERT_FALSE(queue.erase(dead_[k]));
        ASSERT_EQ(queue.size(), before);
    }

    // One random operation; `pushBias` > 0.5 grows the queue.
    void step(double pushBias) {
        const double u = uniform_(rng_);
        if (u < pushBias || queue.empty())
            push(drawTime());
        else if (u < pushBias + 0.1)
            eraseRandomLive();
        else if (u < pushBias + 0.15)
            eraseRandomDead();
        else
            pop();
        ASSERT_EQ(queue.size(), reference.size());
        ASSERT_EQ(queue.empty(), reference.size() == 0);
    }

    void drain() {
        while (!queue.empty()) {
            pop();
            if (::testing::Test::HasFatalFailure()) return;
        }
        EXPECT_EQ(reference.size(), 0u);
    }

    // Stale-entry cleanup through the queue and the reference alike; the counts must agree.
    template <class Pred> void removeIf(Pred pred) {
        const std::size_t expected = reference.removeIf(pred);
        ASSERT_EQ(queue.removeIf(pred), expected);
        for (std::size_t k = 0; k < live_.size();) {
            if (pred(TestEvent{0.0, live_[k].first}))
                forget(live_[k].first);
            else
                ++k;
        }
        ASSERT_EQ(queue.size(), reference.size());
    }

    const std::vector<std::pair<std::uint32_t, QueueHandle>>& live() const { return live_; }
    const std::vector<QueueHandle>& dead() const { return dead_; }

private:
    // Moves an event that left the queue from the live list to the dead handles (O(1)).
    void forget(std::uint32_t id) {
        const std::size_t k = slotOf_[id];
        dead_.push_back(live_[k].second);
        live_[k] = live_.back();
        slotOf_[live_[k].first] = k;
        live_.pop_back();
    }

    std::mt19937_64 rng_;
    std::uniform_real_distribution<double> uniform_{0.0, 1.0};
    std::exponential_distribution<double> exponential_{1.0};
    std::uint32_t nextId_ = 0;
    std::vector<std::pair<std::uint32_t, QueueHandle>> live_; // events still queued
    std::vector<std::size_t> slotOf_;                         // id → index in live_
    std::vector<QueueHandle> dead_;                           // handles of events that left
};

template <class Q> class EventQueueTest : public ::testing::Test {};

using QueueKinds = ::testing::Types<BinaryHeapQueue<TestEvent>, BpqTypical, BpqSingleBin,
                                    BpqWideBins, BpqNegativeStart>;
TYPED_TEST_SUITE(EventQueueTest, QueueKinds);

TYPED_TEST(EventQueueTest, RandomOperationsPopInReferenceOrder) {
    // Grow, hold, then shrink, so that each phase of the queue's life is checked.
    Driver<TypeParam> d(kRandomOpsSeed);
    for (const double pushBias : {0.7, 0.45, 0.2})
        for (int i = 0; i < 20000; ++i) {
            d.step(pushBias);
            if (this->HasFatalFailure()) return;
        }
    d.drain();
}

TYPED_TEST(EventQueueTest, EventsFarBeyondAnyWindowComeOutInOrder) {
    Driver<TypeParam> d(kRandomOpsSeed);
    for (const double t : {1e9, 3.0, 1e6, std::numeric_limits<double>::infinity(), 1e15, 3.0, 0.5})
        d.push(t);
    d.drain();
}

TYPED_TEST(EventQueueTest, EventsAtOrBeforeTheCurrentTimeAreServedNext) {
    Driver<TypeParam> d(kRandomOpsSeed);
    for (int i = 0; i < 200; ++i)
        d.push(0.37 * i);
    for (int i = 0; i < 50; ++i)
        d.pop();
    // An event computed "now" can land a rounding error before the last popped time, or even
    // before the start of the current bin; it must still leave before everything later.
    const double now = d.now;
    d.push(now);
    d.push(std::nextafter(now, 0.0));
    d.push(now - 0.5);
    d.push(now);
    for (int i = 0; i < 4; ++i)
        d.pop();
    EXPECT_LE(d.now, now);
    d.drain();
}

TYPED_TEST(EventQueueTest, EraseOfAnEventThatLeftReturnsFalse) {
    TypeParam q;
    const QueueHandle first = q.push({1.0, 1});
    const QueueHandle second = q.push({2.0, 2});
    EXPECT_FALSE(q.erase(QueueHandle{})); // a default handle refers to nothing
    q.pop();                              // `first` leaves by pop
    EXPECT_FALSE(q.erase(first));
    EXPECT_TRUE(q.erase(second));
    EXPECT_FALSE(q.erase(second));
    EXPECT_TRUE(q.empty());
    // The freed slots are reused; the old handles must not reach the new occupants.
    const QueueHandle third = q.push({3.0, 3});
    const QueueHandle fourth = q.push({4.0, 4});
    EXPECT_FALSE(q.erase(first));
    EXPECT_FALSE(q.erase(second));
    EXPECT_EQ(q.size(), 2u);
    EXPECT_TRUE(q.erase(fourth));
    EXPECT_EQ(q.top().id, 3u);
    EXPECT_TRUE(q.erase(third));
    EXPECT_TRUE(q.empty());
}

TYPED_TEST(EventQueueTest, RemoveIfDropsExactlyTheMatchingEvents) {
    Driver<TypeParam> d(kRandomOpsSeed);
    for (int i = 0; i < 3000; ++i)
        d.step(0.7);
    ASSERT_FALSE(this->HasFatalFailure());
    const std::size_t before = d.queue.size();
    const std::size_t deadBefore = d.dead().size();
    d.removeIf([](const TestEvent& e) { return e.id % 3 == 0; });
    ASSERT_FALSE(this->HasFatalFailure());
    ASSERT_LT(d.queue.size(), before); // the predicate did match something
    for (std::size_t k = deadBefore; k < d.dead().size(); ++k)
        EXPECT_FALSE(d.queue.erase(d.dead()[k]));
    for (int i = 0; i < 3000; ++i) {
        d.step(0.5);
        if (this->HasFatalFailure()) return;
    }
    d.drain();
}

TYPED_TEST(EventQueueTest, ClearEmptiesTheQueueAndInvalidatesHandles) {
    Driver<TypeParam> d(kRandomOpsSeed);
    for (int i = 0; i < 2000; ++i)
        d.step(0.8);
    ASSERT_FALSE(this->HasFatalFailure());
    d.queue.clear();
    EXPECT_TRUE(d.queue.empty());
    EXPECT_EQ(d.queue.size(), 0u);
    for (const auto& [id, handle] : d.live())
        EXPECT_FALSE(d.queue.erase(handle)) << "event " << id;
    // Still usable afterwards, including at times long before the cleared events.
    TypeParam& q = d.queue;
    q.push({5.0, 1});
    q.push({-2.0, 2});
    q.push({5.0, 3});
    EXPECT_EQ(q.top().id, 2u);
    q.pop();
    EXPECT_EQ(q.top().id, 1u); // tie at t = 5: first pushed leaves first
    q.pop();
    EXPECT_EQ(q.top().id, 3u);
}

TYPED_TEST(EventQueueTest, SteadyStateHoldsDoNotAllocate) {
    // Hold model: pop the earliest, push one at now + delay. Once the queue has reached its size
    // and its bins have seen their busiest moments, slots come from the free list.
    constexpr int kQueued = 5000;
    constexpr int kHolds = 200000;
    TypeParam q;
    std::mt19937_64 rng(kRandomOpsSeed);
    std::exponential_distribution<double> delay(1.0);
    for (int i = 0; i < kQueued; ++i)
        q.push({delay(rng), 0});
    const auto holds = [&] {
        for (int i = 0; i < kHolds; ++i) {
            const double now = q.top().time;
            q.pop();
            q.push({now + delay(rng), 0});
        }
    };
    holds(); // warm-up
    const std::size_t before = allocationCount;
    holds();
    EXPECT_EQ(allocationCount - before, 0u);
    EXPECT_EQ(q.size(), static_cast<std::size_t>(kQueued));
}

// The bounded queue only: retune re-bins everything and keeps order and handles.
TEST(BoundedPriorityQueue, RetunePreservesOrderAndHandles) {
    Driver<BpqTypical> d(kRetuneSeed);
    const std::pair<double, std::size_t> layouts[] = {
        {1.0, 3}, {0.001, 1000}, {7.0, 1}, {0.05, 40}};
    for (const auto& [width, bins] : layouts) {
        for (int i = 0; i < 5000; ++i) {
            d.step(0.6);
            if (::testing::Test::HasFatalFailure()) return;
        }
        d.queue.retune(width, bins);
        EXPECT_EQ(d.queue.binWidth(), width);
        EXPECT_EQ(d.queue.binCount(), bins);
        EXPECT_EQ(d.queue.size(), d.reference.size());
    }
    // Handles issued before the retunes still erase their events.
    for (int i = 0; i < 100 && !d.live().empty(); ++i)
        d.eraseRandomLive();
    d.drain();
}

TEST(BoundedPriorityQueue, OverflowIsRescannedIntoTheWindow) {
    BoundedPriorityQueue<TestEvent> q(1.0, 4, 0.0);
    q.push({0.5, 0});
    for (std::uint32_t i = 1; i <= 20; ++i)
        q.push({1.0 * i + 0.5, i}); // bins 1..20: 3 in the window, the rest in the overflow
    EXPECT_EQ(q.overflowSize(), 17u);
    for (std::uint32_t i = 0; i <= 20; ++i) {
        ASSERT_EQ(q.top().id, i);
        q.pop();
    }
    EXPECT_TRUE(q.empty());
    EXPECT_EQ(q.overflowSize(), 0u);
}

TEST(BoundedPriorityQueue, RetuneRebinsFromTheEarliestEvent) {
    // After retune the current bin must be the earliest event's, not one that swallows the whole
    // calendar into the heap (correct, but O(log n) again) or leaves it all in the overflow.
    BoundedPriorityQueue<TestEvent> q(1000.0, 2, 0.0);
    for (std::uint32_t i = 0; i < 100; ++i)
        q.push({50.0 + i, i});
    EXPECT_EQ(q.currentBinSize(), 100u);
    q.retune(1.0, 10);
    EXPECT_EQ(q.currentBinSize(), 1u);
    EXPECT_EQ(q.overflowSize(), 90u);
    for (std::uint32_t i = 0; i < 100; ++i) {
        ASSERT_EQ(q.top().id, i);
        q.pop();
    }
}

// The tournament tree holds one entry per owner (Event::i; i < 0: no owner) and a push replaces
// the owner's entry. Against a reference of the same rule (a map keyed by (time, push sequence)
// and each owner's key): random pushes (replacing or not), pops, erases through current and stale
// handles, cleanups and clears, with ties, for several numbers of owners (below). Then, when the
// caller drops an owner's entry before its next push, as the engine's schedule does, the tree pops
// what the heap pops.
struct OwnedEvent {
    double time = 0.0;
    std::int32_t i = -1;
    std::uint32_t id = 0;
};
static_assert(EventQueue<TournamentQueue<OwnedEvent>, OwnedEvent>);
void checkTreeAgainstReference(int owners);

TEST(EventQueues, TournamentTreeKeepsOneEntryPerOwnerInReferenceOrder) {
    // None, one, 256 (with the leaf of no owner: 1, 2 and 257 leaves), and odd numbers, for which
    // the implicit tree is not a full one; 70 001 gives paths of 17 levels.
    for (const int kOwners : {0, 1, 37, 256, 70001}) {
        SCOPED_TRACE(kOwners);
        checkTreeAgainstReference(kOwners);
    }
}

void checkTreeAgainstReference(int kOwners) {
    TournamentQueue<OwnedEvent> tree(kOwners);
    std::map<std::pair<double, std::uint64_t>, OwnedEvent> reference;
    std::map<int, std::pair<double, std::uint64_t>> keyOf; // owner (−1 too) → its entry's key
    std::map<int, QueueHandle> handleOf;
    std::vector<QueueHandle> gone;
    std::uint64_t sequence = 0;
    std::uint32_t id = 0;
    std::mt19937_64 rng(kRandomOpsSeed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    double now = 0.0;
    const auto forget = [&](int owner) {
        reference.erase(keyOf.at(owner));
        keyOf.erase(owner);
        gone.push_back(handleOf.at(owner));
        handleOf.erase(owner);
    };
    for (int step = 0; step < 200000; ++step) {
        const double u = uniform(rng);
        if (u < 0.55) {
            const int owner = static_cast<int>(rng() % (kOwners + 1)) - 1;
            // ties: a coarse grid of times
            const double t = now + std::floor(uniform(rng) * 50.0) * 0.01;
            const OwnedEvent e{t, owner, id++};
            if (keyOf.count(owner)) forget(owner);
            const auto key = std::make_pair(t, sequence++);
            reference[key] = e;
            keyOf[owner] = key;
            handleOf[owner] = tree.push(e);
        } else if (u < 0.9) {
            if (reference.empty()) continue;
            const OwnedEvent expected = reference.begin()->second;
            ASSERT_EQ(tree.top().id, expected.id) << "step " << step;
            now = expected.time;
            tree.pop();
            forget(expected.i);
        } else if (u < 0.97) {
            if (!gone.empty() && uniform(rng) < 0.5) { // an entry that already left: a no-op
                ASSERT_FALSE(tree.erase(gone[rng() % gone.size()]));
                continue;
            }
            if (handleOf.empty()) continue;
            auto it = handleOf.begin();
            std::advance(it, static_cast<long>(rng() % handleOf.size()));
            const int owner = it->first;
            ASSERT_TRUE(tree.erase(it->second));
            forget(owner);
        } else if (u < 0.999) {
            const std::uint32_t cut = id;
            const auto stale = [cut](const OwnedEvent& e) { return (e.id + cut) % 3 == 0; };
            std::size_t expected = 0;
            for (auto it = keyOf.begin(); it != keyOf.end();) {
                const int owner = (it++)->first;
                if (stale(reference.at(keyOf.at(owner)))) {
                    forget(owner);
                    ++expected;
                }
            }
            ASSERT_EQ(tree.removeIf(stale), expected);
        } else {
            tree.clear();
            while (!keyOf.empty())
                forget(keyOf.begin()->first);
        }
        ASSERT_EQ(tree.size(), reference.size());
        ASSERT_EQ(tree.empty(), reference.empty());
        if (!reference.empty()) {
            ASSERT_EQ(tree.top().id, reference.begin()->second.id);
            // The top's owner from the root alone (these events have no partner).
            const int owner = reference.begin()->second.i;
            ASSERT_EQ(tree.topBodies(), std::make_pair(owner < 0 ? -1 : owner, -1));
            tree.prefetchTop();
        } else {
            ASSERT_EQ(tree.topBodies(), std::make_pair(-1, -1));
        }
        if (kOwners > 0) tree.prefetchPath(rng() % kOwners);
    }
    // A copy queues what the original queues, apart from it.
    TournamentQueue<OwnedEvent> copy = tree;
    while (!reference.empty()) {
        ASSERT_EQ(copy.top().id, reference.begin()->second.id);
        copy.pop();
        reference.erase(reference.begin());
    }
    EXPECT_TRUE(copy.empty());
    EXPECT_EQ(tree.size(), keyOf.size());
}

// The engine asks for the next event's bodies by the root alone: owner and partner of the top.
TEST(EventQueues, TournamentTreeNamesTheTopsBodiesAtItsRoot) {
    TournamentQueue<Event> tree(10);
    const auto event = [](double t, int i, int j) {
        Event e;
        e.time = t;
        e.i = i;
        e.j = j;
        e.kind = i < 0 ? EventKind::Sample : EventKind::Collision;
        return e;
    };
    EXPECT_EQ(tree.topBodies(), std::make_pair(-1, -1));
    tree.push(event(3.0, 4, 7));
    EXPECT_EQ(tree.topBodies(), std::make_pair(4, 7));
    tree.push(event(2.0, 9, -1));
    EXPECT_EQ(tree.topBodies(), std::make_pair(9, -1));
    tree.push(event(1.0, -1, -1)); // the sample event: no body
    EXPECT_EQ(tree.topBodies(), std::make_pair(-1, -1));
    tree.pop();
    tree.push(event(5.0, 9, 2)); // replaces 9's entry
    EXPECT_EQ(tree.topBodies(), std::make_pair(4, 7));
    tree.pop();
    EXPECT_EQ(tree.topBodies(), std::make_pair(9, 2));
    EXPECT_EQ(tree.top().j, 2);
}

// The root tells a collision, which rewrites its partner's agenda, list and entry, from another
// event of a pair, which reads only the partner's motion and book (dmd/event.hpp rootPartner).
TEST(EventQueues, TournamentTreeTellsAtItsRootHowMuchOfThePartnerTheTopReads) {
    TournamentQueue<Event> tree(10);
    Event e;
    e.time = 1.0;
    e.i = 4;
    e.j = 7;
    e.kind = EventKind::Virtual;
    tree.push(e);
    EXPECT_EQ(tree.topBodies(), std::make_pair(4, -2 - 7));
    EXPECT_EQ(tree.top().j, 7); // the entry itself keeps its partner
    e.kind = EventKind::Collision;
    tree.push(e); // replaces 4's entry
    EXPECT_EQ(tree.topBodies(), std::make_pair(4, 7));
    e.j = -1;
    e.kind = EventKind::Virtual; // a body's own entry event
    tree.push(e);
    EXPECT_EQ(tree.topBodies(), std::make_pair(4, -1));
    e.j = 0;
    e.kind = EventKind::Virtual; // partner 0 stays apart from "none"
    tree.push(e);
    EXPECT_EQ(tree.topBodies(), std::make_pair(4, -2));
}

TEST(EventQueues, TournamentTreePopsAsTheHeapWhenOwnersDropTheirEntryFirst) {
    constexpr int kOwners = 500;
    TournamentQueue<OwnedEvent> tree(kOwners);
    BinaryHeapQueue<OwnedEvent> heap;
    std::vector<QueueHandle> inHeap(kOwners + 1);
    std::vector<bool> queued(kOwners + 1, false);
    std::mt19937_64 rng(kStressSeed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    double now = 0.0;
    for (int step = 0; step < 300000; ++step) {
        if (uniform(rng) < 0.5 || heap.empty()) {
            const int owner = static_cast<int>(rng() % (kOwners + 1)) - 1;
            const OwnedEvent e{now + std::floor(uniform(rng) * 20.0) * 0.05, owner,
                               static_cast<std::uint32_t>(step)};
            if (queued[owner + 1]) heap.erase(inHeap[owner + 1]); // the heap needs it erased
            inHeap[owner + 1] = heap.push(e);
            queued[owner + 1] = true;
            tree.push(e);
        } else {
            ASSERT_EQ(tree.top().id, heap.top().id) << "step " << step;
            ASSERT_EQ(tree.top().time, heap.top().time);
            now = heap.top().time;
            queued[heap.top().i + 1] = false;
            heap.pop();
            tree.pop();
        }
        ASSERT_EQ(tree.size(), heap.size());
    }
}

// Heap and bounded queue, fed the same 10^6 operations, must pop the same events in the same
// order (bit-identical DMD trajectories under `dmd.queue = heap` and `bpq` rely on it).
TEST(EventQueues, HeapAndBoundedQueuePopIdenticalSequencesUnderStress) {
    constexpr int kOperations = 1'000'000;
    Driver<BinaryHeapQueue<TestEvent>> heap(kStressSeed);
    Driver<BpqTypical> bpq(kStressSeed);
    std::mt19937_64 rng(kStressSeed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int i = 0; i < kOperations; ++i) {
        // Hold-model-like: the queue grows to a few thousand events, then holds its size.
        const double pushBias = heap.queue.size() < 4000 ? 0.55 : 0.45;
        heap.step(pushBias);
        bpq.step(pushBias);
        if (::testing::Test::HasFatalFailure()) return;
        if (!heap.queue.empty()) {
            ASSERT_EQ(heap.queue.top().id, bpq.queue.top().id) << "operation " << i;
            ASSERT_EQ(heap.queue.top().time, bpq.queue.top().time);
        }
        if (uniform(rng) < 1e-4) { // the engine's occasional stale-entry cleanup
            const auto stale = [i](const TestEvent& e) { return (e.id + i) % 5 == 0; };
            heap.removeIf(stale);
            bpq.removeIf(stale);
            if (::testing::Test::HasFatalFailure()) return;
        }
    }
    EXPECT_EQ(heap.queue.size(), bpq.queue.size());
}

} // namespace terrace::dmd::test_event_queue
