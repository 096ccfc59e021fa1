#pragma once
// Binary min-heap event queue (J. W. J. Williams, Commun. ACM 7, 347 (1964); Floyd's bottom-up
// heap construction, Commun. ACM 7, 701 (1964)), the `dmd.queue = heap` choice.
//
// The heap array holds (time, node) pairs ordered by (time, push sequence); the events themselves
// stay in a slot pool so that handles remain valid while heap entries move. Every node records its
// heap index, which makes erase by handle O(log n). push, pop and erase are O(log n), top O(1),
// removeIf O(n) (filter, then re-heapify). Memory per queued event: sizeof(E) plus the node's heap
// index and generation (8 B), its sequence number (8 B) and one heap entry (16 B).
#include "dmd/event_queue.hpp"
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace terrace::dmd {
namespace detail {

// The time is cached next to the node index so that sifting reads contiguous memory; the push
// sequence, needed only for exact ties, is looked up in the node.
struct HeapEntry {
    double time;
    std::uint32_t node;
};

// `before(a, b)`: strict (time, sequence) order. `placed(entry, i)`: tells the owner that entry now
// sits at index i (erase by handle needs each node's heap index).
template <class Before, class Placed>
void siftUp(std::vector<HeapEntry>& heap, std::size_t i, Before before, Placed placed) {
    const HeapEntry moving = heap[i];
    while (i > 0) {
        const std::size_t parent = (i - 1) / 2;
        if (!before(moving, heap[parent])) break;
        heap[i] = heap[parent];
        placed(heap[i], i);
        i = parent;
    }
    heap[i] = moving;
    placed(moving, i);
}

template <class Before, class Placed>
void siftDown(std::vector<HeapEntry>& heap, std::size_t i, Before before, Placed placed) {
    const std::size_t n = heap.size();
    const HeapEntry moving = heap[i];
    for (;;) {
        std::size_t child = 2 * i + 1;
        if (child >= n) break;
        if (child + 1 < n && before(heap[child + 1], heap[child])) ++child;
        if (!before(heap[child], moving)) break;
        heap[i] = heap[child];
        placed(heap[i], i);
        i = child;
    }
    heap[i] = moving;
    placed(moving, i);
}

// Removes heap[i]: the last entry fills the hole and moves up or down as its key requires.
template <class Before, class Placed>
void eraseAt(std::vector<HeapEntry>& heap, std::size_t i, Before before, Placed placed) {
    const HeapEntry last = heap.back();
    heap.pop_back();
    if (i == heap.size()) return;
    heap[i] = last;
    if (i > 0 && before(last, heap[(i - 1) / 2]))
        siftUp(heap, i, before, placed);
    else
        siftDown(heap, i, before, placed);
}

// Floyd's O(n) construction; every entry's index is reported once at the end.
template <class Before, class Placed>
void heapify(std::vector<HeapEntry>& heap, Before before, Placed placed) {
    for (std::size_t i = heap.size() / 2; i-- > 0;)
        siftDown(heap, i, before, [](const HeapEntry&, std::size_t) {});
    for (std::size_t i = 0; i < heap.size(); ++i)
        placed(heap[i], i);
}

} // namespace detail

template <class E> class BinaryHeapQueue {
public:
    /// handles: whether erase() is to be used. Without it (the engine's lazy invalidation never
    /// erases) the heap does not record each node's heap index: a sift then writes only the heap's
    /// own contiguous entries, not a node of the pool at every level, which in a large calendar is
    /// a cache miss per level. The order of the events is the same either way.
    BinaryHeapQueue() = default;
    explicit BinaryHeapQueue(bool handles) : handles_(handles) {}

    QueueHandle push(const E& e) {
        const std::uint32_t slot = pool_.acquire();
        Node& n = pool_[slot];
        n.event = e;
        n.sequence = nextSequence_++;
        heap_.push_back({e.time, slot});
        detail::siftUp(heap_, heap_.size() - 1, before(), placed());
        return pool_.handle(slot);
    }

    const E& top() const {
        assert(!heap_.empty());
        return pool_[heap_.front().node].event;
    }

    void pop() {
        assert(!heap_.empty());
        const std::uint32_t slot = heap_.front().node;
        detail::eraseAt(heap_, 0, before(), placed());
        pool_.release(slot);
    }

    bool erase(QueueHandle h) {
        if (!handles_) throw std::logic_error("BinaryHeapQueue: erase without handles");
        if (!pool_.holds(h)) return false;
        detail::eraseAt(heap_, pool_[h.slot].heapIndex, before(), placed());
        pool_.release(h.slot);
        return true;
    }

    std::size_t size() const { return heap_.size(); }
    bool empty() const { return heap_.empty(); }

    template <class Pred> std::size_t removeIf(Pred&& pred) {
        std::size_t kept = 0;
        for (const detail::HeapEntry& entry : heap_) {
            if (pred(static_cast<const E&>(pool_[entry.node].event)))
                pool_.release(entry.node);
            else
                heap_[kept++] = entry;
        }
        const std::size_t removed = heap_.size() - kept;
        heap_.resize(kept);
        detail::heapify(heap_, before(), placed());
        return removed;
    }

    void clear() {
        for (const detail::HeapEntry& entry : heap_)
            pool_.release(entry.node);
        heap_.clear();
    }

    // Bytes reserved by the queue's containers (capacities, including sizeof(E) per slot).
    std::size_t bytesReserved() const {
        return pool_.bytesReserved() + heap_.capacity() * sizeof(detail::HeapEntry);
    }

private:
    struct Node {
        E event{};
        std::uint64_t sequence = 0;
        std::uint32_t heapIndex = 0;
        std::uint32_t generation = 0;
    };

    auto before() const {
        return [this](const detail::HeapEntry& a, const detail::HeapEntry& b) {
            if (a.time != b.time) return a.time < b.time;
            return pool_[a.node].sequence < pool_[b.node].sequence;
        };
    }
    auto placed() {
        return [this](const detail::HeapEntry& entry, std::size_t i) {
            if (handles_) pool_[entry.node].heapIndex = static_cast<std::uint32_t>(i);
        };
    }

    detail::SlotPool<Node, &Node::heapIndex> pool_; // heapIndex links free slots
    std::vector<detail::HeapEntry> heap_;
    std::uint64_t nextSequence_ = 0;
    bool handles_ = true;
};

} // namespace terrace::dmd
