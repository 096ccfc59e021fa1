#pragma once
// G. Paul's O(1) bounded priority queue, J. Comput. Phys. 221, 615 (2007), the `dmd.queue = bpq`
// choice (paper, "Implementation of the event-driven simulation"; REFERENCES.md).
//
// Time is cut into bins of width Δ (time units of 100 fs); event time t belongs to bin
// b(t) = ⌊t/Δ⌋. With c the current bin and n the number of bins:
//   b ≤ c          → a small binary heap that fine-sorts the current bin (also catches events
//   pushed
//                    "now" or, through round-off, slightly in the past);
//   c < b < c + n  → the unsorted doubly linked list number b mod n of a circular array;
//   b ≥ c + n      → an unsorted overflow list, rescanned once every n bins (the window has then
//                    slid by n, so nothing left in it can fall due before the next rescan).
// When the heap runs dry the current bin advances to the next non-empty list, whose events are
// heapified; if only the overflow holds events, the current bin jumps to the earliest of them.
// push, pop and erase cost O(1) on average when a bin holds a few to a few hundred events and the
// window nΔ spans the usual scheduling horizon; the heap part costs O(log(events per bin)).
//
// Order and ties are exactly those of BinaryHeapQueue: (time, push sequence), so both queues pop
// the same events in the same order. Memory per queued event: sizeof(E) + 24 B node (sequence,
// list links, location, generation), plus 16 B per event of the current bin and 4 B per bin.
#include "dmd/binary_heap_queue.hpp"
#include "dmd/event_queue.hpp"
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace terrace::dmd {

template <class E> class BoundedPriorityQueue {
public:
    BoundedPriorityQueue(double binWidth, std::size_t nBins, double startTime) {
        setBins(binWidth, nBins);
        jumpTo(binOf(startTime));
    }

    QueueHandle push(const E& e) {
        assert(!std::isnan(e.time));
        const std::uint32_t slot = pool_.acquire();
        Node& n = pool_[slot];
        n.event = e;
        n.sequence = nextSequence_++;
        if (size_ == 0) jumpTo(binOf(e.time)); // an empty calendar may restart anywhere
        place(slot);
        ++size_;
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
        release(slot);
        refill();
    }

    bool erase(QueueHandle h) {
        if (!pool_.holds(h)) return false;
        const std::uint32_t where = pool_[h.slot].where;
        if (where & kListed)
            unlink(h.slot);
        else
            detail::eraseAt(heap_, where, before(), placed());
        release(h.slot);
        refill();
        return true;
    }

    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }

    template <class Pred> std::size_t removeIf(Pred&& pred) {
        const std::size_t queuedBefore = size_;
        std::size_t kept = 0;
        for (const detail::HeapEntry& entry : heap_) {
            if (pred(static_cast<const E&>(pool_[entry.node].event)))
                release(entry.node);
            else
                heap_[kept++] = entry;
        }
        heap_.resize(kept);
        detail::heapify(heap_, before(), placed());
        for (std::uint32_t slot = 0; slot < pool_.slots(); ++slot) {
            const Node& n = pool_[slot];
            if (n.where != kFree && (n.where & kListed) && pred(static_cast<const E&>(n.event))) {
                unlink(slot);
                release(slot);
            }
        }
        refill();
        return queuedBefore - size_;
    }

    void clear() {
        for (std::uint32_t slot = 0; slot < pool_.slots(); ++slot)
            if (pool_[slot].where != kFree) release(slot);
        heap_.clear();
        std::fill(heads_.begin(), heads_.end(), kNil);
        binned_ = overflowed_ = 0;
    }

    // Re-bins every queued event under a new bin width and count; handles stay valid.
    void retune(double binWidth, std::size_t nBins) {
        // O(size): every queued node is visited once. The heap top is the earliest event, so the
        // new current bin is known before the nodes are re-placed (in slot order, which is
        // irrelevant to the pop order: that is fixed by (time, sequence) alone).
        const bool any = size_ > 0;
        const double earliest = any ? heap_.front().time : 0.0;
        heap_.clear();
        setBins(binWidth, nBins);
        if (any) jumpTo(binOf(earliest));
        for (std::uint32_t slot = 0; slot < pool_.slots(); ++slot)
            if (pool_[slot].where != kFree) place(slot);
        // A badly binned past may have grown the current-bin heap to the whole calendar.
        if (heap_.capacity() > 4 * heap_.size() + kHeapSlack) heap_.shrink_to_fit();
        refill(); // a no-op: the earliest event is in the current bin by construction
    }

    double binWidth() const { return binWidth_; }
    std::size_t binCount() const { return nBins_; }
    std::size_t overflowSize() const { return overflowed_; }
    std::size_t currentBinSize() const { return heap_.size(); }

    // Bytes reserved by the queue's containers (capacities, including sizeof(E) per slot).
    std::size_t bytesReserved() const {
        return pool_.bytesReserved() + heap_.capacity() * sizeof(detail::HeapEntry) +
               heads_.capacity() * sizeof(std::uint32_t);
    }

private:
    static constexpr std::uint32_t kNil = UINT32_MAX;
    static constexpr std::uint32_t kListed = 0x80000000u; // `where` = kListed | list number
    static constexpr std::uint32_t kFree = UINT32_MAX;    // `where` of a slot not in the queue
    // Bins far beyond any simulated time (or ±∞) saturate here, leaving room for c + n.
    static constexpr double kBinLimit = 0x1p60;
    // Current-bin heap capacity kept through a retune regardless of its size (entries).
    static constexpr std::size_t kHeapSlack = 1024;

    // Links first, then the event, whose time comes first: walking a list reads `next` and `time`,
    // which then usually share a cache line.
    struct Node {
        std::uint32_t prev = kNil;
        std::uint32_t next = kNil;
        std::uint32_t where = kFree; // heap index, or kListed | list number (n = overflow)
        std::uint32_t generation = 0;
        std::uint64_t sequence = 0;
        E event{};
    };

    void setBins(double binWidth, std::size_t nBins) {
        assert(binWidth > 0.0 && std::isfinite(binWidth));
        assert(nBins >= 1 && nBins < kListed - 1);
        binWidth_ = binWidth;
        inverseWidth_ = 1.0 / binWidth;
        nBins_ = nBins;
        heads_.assign(nBins + 1, kNil);
        binned_ = overflowed_ = 0;
        currentList_ = listOf(currentBin_);
    }

    std::int64_t binOf(double t) const {
        const double b = std::floor(t * inverseWidth_);
        return static_cast<std::int64_t>(std::clamp(b, -kBinLimit, kBinLimit));
    }
    std::uint32_t listOf(std::int64_t bin) const {
        const auto n = static_cast<std::int64_t>(nBins_);
        return static_cast<std::uint32_t>(((bin % n) + n) % n);
    }
    std::uint32_t overflowList() const { return static_cast<std::uint32_t>(nBins_); }

    void jumpTo(std::int64_t bin) {
        currentBin_ = bin;
        currentList_ = listOf(bin);
        nextRescanBin_ = bin + static_cast<std::int64_t>(nBins_);
    }
    void advanceBin() {
        ++currentBin_;
        if (++currentList_ == nBins_) currentList_ = 0;
    }

    // Puts a queued node where its bin says (see the table at the top).
    void place(std::uint32_t slot) {
        const std::int64_t bin = binOf(pool_[slot].event.time);
        if (bin <= currentBin_) {
            heap_.push_back({pool_[slot].event.time, slot});
            detail::siftUp(heap_, heap_.size() - 1, before(), placed());
        } else if (const std::int64_t ahead = bin - currentBin_;
                   ahead < static_cast<std::int64_t>(nBins_)) {
            // The list of bin c + ahead, from the current bin's list without a division.
            std::size_t list = currentList_ + static_cast<std::size_t>(ahead);
            if (list >= nBins_) list -= nBins_;
            link(slot, static_cast<std::uint32_t>(list));
            ++binned_;
        } else {
            link(slot, overflowList());
            ++overflowed_;
        }
    }

    void link(std::uint32_t slot, std::uint32_t list) {
        Node& n = pool_[slot];
        n.prev = kNil;
        n.next = heads_[list];
        if (n.next != kNil) pool_[n.next].prev = slot;
        heads_[list] = slot;
        n.where = kListed | list;
    }

    void unlink(std::uint32_t slot) {
        const Node& n = pool_[slot];
        const std::uint32_t list = n.where & ~kListed;
        if (n.prev != kNil)
            pool_[n.prev].next = n.next;
        else
            heads_[list] = n.next;
        if (n.next != kNil) pool_[n.next].prev = n.prev;
        if (list == overflowList())
            --overflowed_;
        else
            --binned_;
    }

    void release(std::uint32_t slot) {
        pool_[slot].where = kFree;
        pool_.release(slot);
        --size_;
    }

    // Restores the invariant that the heap holds the earliest event whenever the queue is not
    // empty.
    void refill() {
        while (heap_.empty() && size_ > 0) {
            if (binned_ == 0) {
                jumpTo(earliestOverflowBin());
                rescanOverflow();
            } else {
                advanceBin();
                if (currentBin_ >= nextRescanBin_) rescanOverflow();
            }
            loadCurrentBin();
        }
    }

    std::int64_t earliestOverflowBin() const {
        std::int64_t earliest = std::numeric_limits<std::int64_t>::max();
        for (std::uint32_t s = heads_[overflowList()]; s != kNil; s = pool_[s].next)
            earliest = std::min(earliest, binOf(pool_[s].event.time));
        return earliest;
    }

    // Moves every overflow event that the window [c, c + n) now covers into its list.
    void rescanOverflow() {
        nextRescanBin_ = currentBin_ + static_cast<std::int64_t>(nBins_);
        for (std::uint32_t s = heads_[overflowList()]; s != kNil;) {
            const std::uint32_t next = pool_[s].next;
            if (binOf(pool_[s].event.time) < nextRescanBin_) {
                unlink(s);
                place(s);
            }
            s = next;
        }
    }

    void loadCurrentBin() {
        const auto list = static_cast<std::uint32_t>(currentList_);
        for (std::uint32_t s = heads_[list]; s != kNil; s = pool_[s].next) {
            heap_.push_back({pool_[s].event.time, s});
            --binned_;
        }
        heads_[list] = kNil;
        detail::heapify(heap_, before(), placed());
    }

    auto before() const {
        return [this](const detail::HeapEntry& a, const detail::HeapEntry& b) {
            if (a.time != b.time) return a.time < b.time;
            return pool_[a.node].sequence < pool_[b.node].sequence;
        };
    }
    auto placed() {
        return [this](const detail::HeapEntry& entry, std::size_t i) {
            pool_[entry.node].where = static_cast<std::uint32_t>(i);
        };
    }

    detail::SlotPool<Node, &Node::next> pool_; // `next` links free slots
    std::vector<detail::HeapEntry> heap_;      // the current bin, fine-sorted
    std::vector<std::uint32_t> heads_;         // n bin lists, then the overflow list
    double binWidth_ = 1.0;                    // time units
    double inverseWidth_ = 1.0;                // 1/binWidth_: bins by multiplication
    std::size_t nBins_ = 1;
    std::int64_t currentBin_ = 0;
    std::size_t currentList_ = 0;    // listOf(currentBin_), kept in step with it
    std::int64_t nextRescanBin_ = 0; // the overflow is rescanned when c reaches this bin
    std::size_t size_ = 0;
    std::size_t binned_ = 0;     // events in the n bin lists
    std::size_t overflowed_ = 0; // events in the overflow list
    std::uint64_t nextSequence_ = 0;
};

} // namespace terrace::dmd
