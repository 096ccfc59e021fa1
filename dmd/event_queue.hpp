#pragma once
// The DMD event calendar's interface (DESIGN.md "DMD engine"; paper, "Implementation of the
// event-driven simulation"). Two implementations sit behind it and are chosen by `dmd.queue`:
//   heap — dmd/binary_heap_queue.hpp, O(log n) per operation;
//   bpq  — dmd/bounded_priority_queue.hpp, G. Paul, J. Comput. Phys. 221, 615 (2007), O(1) average.
//
// Order: events leave strictly by (time, push sequence number). Both queues number pushes 0, 1, 2,
// … and break exact time ties by that number, so that the same pushes produce the same pops in both
// queues and `heap` and `bpq` runs are bit-identical. Times are in the internal unit (100 fs).
//
// Handles: push returns {slot, generation}. A slot's generation changes whenever its event leaves
// the queue (pop, erase, removeIf, clear), so erasing through a handle to an event that already
// left is a detectable no-op rather than the deletion of whichever event now occupies the slot.
#include <concepts>
#include <cstddef>
#include <cstdint>
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

// Storage for queued events with stable indices: a released slot goes onto a free list and is
// reused by a later push, so the pool stops allocating once the queue's size stops growing.
// Node must have a `std::uint32_t generation` member; generations skip 0 when they wrap, and a
// handle could be mistaken for a new one only after 2^32 - 1 reuses of the same slot.
template <class Node> class SlotPool {
public:
    std::uint32_t acquire() {
        if (!free_.empty()) {
            const std::uint32_t slot = free_.back();
            free_.pop_back();
            return slot;
        }
        nodes_.emplace_back();
        nodes_.back().generation = 1;
        return static_cast<std::uint32_t>(nodes_.size() - 1);
    }

    void release(std::uint32_t slot) {
        std::uint32_t& g = nodes_[slot].generation;
        g = (g == UINT32_MAX) ? 1 : g + 1;
        free_.push_back(slot);
    }

    // Whether h names an event that is still queued.
    bool holds(QueueHandle h) const {
        return h.slot < nodes_.size() && h.generation != 0 &&
               nodes_[h.slot].generation == h.generation;
    }

    QueueHandle handle(std::uint32_t slot) const { return {slot, nodes_[slot].generation}; }
    Node& operator[](std::uint32_t slot) { return nodes_[slot]; }
    const Node& operator[](std::uint32_t slot) const { return nodes_[slot]; }
    std::size_t slots() const { return nodes_.size(); }

    // Bytes held (capacity, not size): what the queue costs in memory.
    std::size_t bytesReserved() const {
        return nodes_.capacity() * sizeof(Node) + free_.capacity() * sizeof(std::uint32_t);
    }

private:
    std::vector<Node> nodes_;
    std::vector<std::uint32_t> free_;
};

} // namespace detail
} // namespace terrace::dmd
