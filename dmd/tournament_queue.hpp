#pragma once
// A tournament (winner) tree over the bodies, the `dmd.queue = tree` choice: the calendar of an
// engine whose bodies each hold at most one entry (dmd/schedule.hpp), as the complete binary tree
// of one event per particle of M. Marín, D. Risso and P. Cordero, J. Comput. Phys. 109, 306 (1993).
//
// Leaf b holds the entry of owner b (Event::i; one more leaf for the events of no owner, i < 0, the
// sample event), and every inner node the earliest entry below it, as (time, leaf, partner). A push
// for an owner replaces its entry (the schedule pushes only after its old one stopped standing);
// pop, erase and push walk from the leaf to the root, a push stopping where nothing changes. top is
// the root. Order and ties are exactly those of the other queues (time, push sequence), so all
// three pop the same events in the same order when no owner holds two entries at once.
//
// Why a tree: in a heap a pop walks a path chosen by its comparisons through the whole array, the
// lower levels of which are cold in a large system. Here a leaf's path is fixed by its body, and
// the bodies are numbered so that neighbours in space are neighbours in memory (the engine's Morton
// order): the lower levels an event walks are those its neighbours' events walked, the upper ones
// are few and always cached, and no entry is ever stale in it. Memory: 2 nodes of 16 B and one
// 48-B leaf per body, with no stale entries (a heap of lazy entries holds more than one per body).
// The inner nodes are an implicit tree over L leaves (node k's children 2k and 2k + 1, leaves at
// L … 2L − 1, any L), aligned so that two siblings share a cache line.
#include "core/huge_pages.hpp"
#include "dmd/event_queue.hpp"
#include "dmd/prefetch.hpp"
#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace terrace::dmd {

template <class E> class TournamentQueue {
public:
    /// owners: the bodies (entries of owners 0 … owners − 1, and of no owner).
    explicit TournamentQueue(int owners) : leaves_(static_cast<std::size_t>(owners) + 1) {
        if (owners < 0) throw std::invalid_argument("TournamentQueue: owners must be >= 0");
        leaf_.resize(leaves_);
        node_.resize(2 * leaves_);
        rebuild();
    }

    /// Queues e as its owner's entry, in place of the one it had, if any.
    QueueHandle push(const E& e) {
        const std::size_t b = leafOf(e);
        Leaf& l = leaf_[b];
        if (l.queued)
            retire(l);
        else
            ++size_;
        l.event = e;
        l.sequence = nextSequence_++;
        l.queued = true;
        update(b);
        return {static_cast<std::uint32_t>(b), l.generation};
    }

    const E& top() const {
        assert(size_ > 0);
        return leaf_[node_[1].leaf].event;
    }

    /// The owner and partner (Event::i, Event::j; −1 for none) of the earliest entry, read from
    /// the root alone: in a large system its leaf is far from the caches, and the engine wants
    /// to ask for the bodies of its next event without first waiting for that leaf. The partner
    /// is as rootPartner(entry) gives it where the entry type has one (dmd/event.hpp).
    std::pair<int, int> topBodies() const {
        const Node& root = node_[1];
        if (root.leaf == kNone || root.leaf == leaves_ - 1) return {-1, -1};
        return {static_cast<int>(root.leaf), root.partner};
    }
    /// Asks the caches for what popping the earliest entry reads: its leaf and the lower levels
    /// of its path (the upper ones are walked by every event and stay cached).
    [[gnu::always_inline]] void prefetchTop() const {
        if (node_[1].leaf != kNone) prefetchPath(node_[1].leaf);
    }
    /// The same for owner b's leaf and path, which a new entry of b walks.
    [[gnu::always_inline]] void prefetchPath(std::size_t b) const {
        prefetchLines(&leaf_[b], sizeof(Leaf));
        std::size_t k = leaves_ + b;
        for (int level = 0; level < prefetchedLevels && k > 1; ++level, k >>= 1)
            __builtin_prefetch(&node_[k]); // and its sibling: the two share a line
    }

    void pop() {
        assert(size_ > 0);
        const std::uint32_t b = node_[1].leaf;
        leave(leaf_[b]);
        --size_;
        update(b);
    }

    bool erase(QueueHandle h) {
        if (h.slot >= leaves_ || h.generation == 0) return false;
        Leaf& l = leaf_[h.slot];
        if (!l.queued || l.generation != h.generation) return false;
        leave(l);
        --size_;
        update(h.slot);
        return true;
    }

    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }

    template <class Pred> std::size_t removeIf(Pred&& pred) {
        std::size_t removed = 0;
        for (Leaf& l : leaf_)
            if (l.queued && pred(static_cast<const E&>(l.event))) {
                leave(l);
                ++removed;
            }
        size_ -= removed;
        if (removed > 0) rebuild();
        return removed;
    }

    void clear() {
        for (Leaf& l : leaf_)
            if (l.queued) leave(l);
        size_ = 0;
        rebuild();
    }

    std::size_t bytesReserved() const {
        return node_.capacity() * sizeof(Node) + leaf_.capacity() * sizeof(Leaf);
    }

private:
    static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
    // Path levels asked for ahead of a walk, from the leaf up: above them a tree of 10⁶ leaves
    // has fewer than 2¹⁰ nodes (16 KB), which the walks of every event keep in the caches.
    static constexpr int prefetchedLevels = 11;

    struct Node {
        double time = std::numeric_limits<double>::infinity();
        std::uint32_t leaf = kNone; // the earliest entry below (kNone: none)
        std::int32_t partner = -1;  // rootPartner or Event::j, if any: topBodies reads no leaf
    };
    static_assert(sizeof(Node) == 16, "two siblings to 32 bytes");
    struct Leaf {
        E event{};
        std::uint64_t sequence = 0;
        std::uint32_t generation = 1; // of its entry; changes whenever an entry leaves (0 never)
        bool queued = false;
    };

    std::size_t leafOf(const E& e) const {
        if (e.i < 0) return leaves_ - 1;
        if (static_cast<std::size_t>(e.i) >= leaves_ - 1)
            throw std::out_of_range("TournamentQueue: an event's owner beyond the bodies");
        return static_cast<std::size_t>(e.i);
    }
    // The leaf's entry leaves the queue (replaced, or gone): handles to it stop holding.
    static void retire(Leaf& l) {
        l.generation = l.generation == UINT32_MAX ? 1 : l.generation + 1;
    }
    static void leave(Leaf& l) {
        retire(l);
        l.queued = false;
    }

    // Strict order of two nodes by (time, push sequence); an empty node comes after every entry.
    bool before(const Node& a, const Node& b) const {
        if (a.time != b.time) return a.time < b.time;
        if (a.leaf == kNone) return false;
        if (b.leaf == kNone) return true;
        return leaf_[a.leaf].sequence < leaf_[b.leaf].sequence;
    }
    Node nodeOfLeaf(std::size_t b) const {
        const Leaf& l = leaf_[b];
        if (!l.queued) return Node{};
        std::int32_t partner = -1;
        if constexpr (requires { rootPartner(l.event); })
            partner = rootPartner(l.event);
        else if constexpr (requires { l.event.j; })
            partner = l.event.j;
        return Node{l.event.time, static_cast<std::uint32_t>(b), partner};
    }

    /// Leaf b changed: its ancestors again hold the earliest below them. A node that comes out as
    /// it was ends the walk, unless it is b's own (a new entry of b at the time of its old one
    /// may stand elsewhere among ties).
    void update(std::size_t b) {
        std::size_t k = leaves_ + b;
        node_[k] = nodeOfLeaf(b);
        for (k >>= 1; k >= 1; k >>= 1) {
            const Node& left = node_[2 * k];
            const Node& right = node_[2 * k + 1];
            const Node winner = before(right, left) ? right : left;
            Node& here = node_[k];
            if (winner.leaf == here.leaf && winner.time == here.time && winner.leaf != b) return;
            here = winner;
        }
    }
    void rebuild() {
        for (std::size_t b = 0; b < leaves_; ++b)
            node_[leaves_ + b] = nodeOfLeaf(b);
        for (std::size_t k = leaves_; k-- > 1;)
            node_[k] = before(node_[2 * k + 1], node_[2 * k]) ? node_[2 * k + 1] : node_[2 * k];
    }

    std::size_t leaves_;
    std::size_t size_ = 0;
    std::uint64_t nextSequence_ = 0;
    BodyArray<Leaf> leaf_;
    BodyArray<Node> node_; // node_[0] unused; node_[1] the root; 64-B aligned (HugePageAllocator)
};

} // namespace terrace::dmd
