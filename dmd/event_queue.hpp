#pragma once
// The DMD event calendar's interface (DESIGN.md "DMD engine"; paper, "Implementation of the
// event-driven simulation"). Three implementations sit behind it and are chosen by `dmd.queue`:
//   heap — dmd/binary_heap_queue.hpp, O(log n) per operation;
//   bpq  — dmd/bounded_priority_queue.hpp, G. Paul, J. Comput. Phys. 221, 615 (2007), O(1) average;
//   tree — dmd/tournament_queue.hpp, O(log n), one entry per owner (a push replaces its entry).
//
// Order: events leave strictly by (time, push sequence number). The queues number pushes 0, 1, 2,
// … and break exact time ties by that number, so that the same pushes produce the same pops in all
// of them (in the tree, as long as no owner holds two entries at once: the engine's calendar) and
// `heap`, `bpq` and `tree` runs are bit-identical. Times are in the internal unit (100 fs).
//
// Handles: push returns {slot, generation}. A slot's generation changes whenever its event leaves
// the queue (pop, erase, removeIf, clear), so erasing through a handle to an event that already
// left is a detectable no-op rather than the deletion of whichever event now occupies the slot.
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace terrace::dmd {

struct QueueHandle {
    std::uint32_t slot = 0;
    std::uint32_t generation = 0; // 0 is never issued: a default QueueHandle refers to nothing
};

template <class Q, class E>
concept EventQueue = requires(Q q, const Q cq, E e, QueueHandle h, bool (*pred)(const E&)) {
    { e.time } -> std::convertible_to<double>;
    { q.push(e) } -> std::same_as<QueueHandle>;
    { cq.top() } -> std::same_as<const E&>; // earliest event; precondition !empty()
    q.pop();                                // removes top()
    { q.erase(h) } -> std::same_as<bool>;   // false (no-op) if that event already left the queue
    { cq.size() } -> std::convertible_to<std::size_t>;
    { cq.empty() } -> std::convertible_to<bool>;
    { q.removeIf(pred) } -> std::convertible_to<std::size_t>; // stale-entry cleanup; count removed
    q.clear();
};

namespace detail {

// Storage for queued events with stable indices. Nodes live in fixed-size blocks, so growing the
// pool never moves or copies queued events (no transient doubling of a multi-megabyte array) and
// wastes at most one block. A released slot is threaded onto a free list through the node's own
// `FreeLink` member (a field the queue does not use while the slot is free), so the pool stops
// allocating once the queue's size stops growing and the free list costs no memory.
// Node must have a `std::uint32_t generation` member; generations skip 0 when they wrap, and a
// handle could be mistaken for a new one only after 2^32 - 1 reuses of the same slot.
template <class Node, std::uint32_t Node::*FreeLink> class SlotPool {
public:
    std::uint32_t acquire() {
        if (freeHead_ != kNone) {
            const std::uint32_t slot = freeHead_;
            freeHead_ = (*this)[slot].*FreeLink;
            return slot;
        }
        if (slots_ == blocks_.size() * kBlockSize)
            blocks_.push_back(std::make_unique<Node[]>(kBlockSize));
        const auto slot = static_cast<std::uint32_t>(slots_++);
        (*this)[slot].generation = 1;
        return slot;
    }

    void release(std::uint32_t slot) {
        Node& n = (*this)[slot];
        n.generation = (n.generation == UINT32_MAX) ? 1 : n.generation + 1;
        n.*FreeLink = freeHead_;
        freeHead_ = slot;
    }

    // Whether h names an event that is still queued.
    bool holds(QueueHandle h) const {
        return h.slot < slots_ && h.generation != 0 && (*this)[h.slot].generation == h.generation;
    }

    QueueHandle handle(std::uint32_t slot) const { return {slot, (*this)[slot].generation}; }
    Node& operator[](std::uint32_t slot) { return blocks_[slot >> kBlockBits][slot & kBlockMask]; }
    const Node& operator[](std::uint32_t slot) const {
        return blocks_[slot >> kBlockBits][slot & kBlockMask];
    }
    // Slots ever handed out (queued or free): the range to scan for queued events.
    std::size_t slots() const { return slots_; }

    // Bytes held (capacity, not size): what the queue costs in memory.
    std::size_t bytesReserved() const {
        return blocks_.size() * kBlockSize * sizeof(Node) +
               blocks_.capacity() * sizeof(std::unique_ptr<Node[]>);
    }

private:
    static constexpr std::uint32_t kBlockBits = 12; // 4096 nodes: ~100–200 kB blocks
    static constexpr std::size_t kBlockSize = std::size_t{1} << kBlockBits;
    static constexpr std::uint32_t kBlockMask = kBlockSize - 1;
    static constexpr std::uint32_t kNone = UINT32_MAX;

    std::vector<std::unique_ptr<Node[]>> blocks_;
    std::size_t slots_ = 0;
    std::uint32_t freeHead_ = kNone;
};

} // namespace detail
} // namespace terrace::dmd
