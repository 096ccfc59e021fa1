#pragma once
// The agendas of the DMD engine's schedule (dmd/schedule.hpp): each body's predicted events, of
// which the calendar holds only the earliest.
//
// Laid out for a large system, where an event's bodies are far apart in memory and every separate
// heap block is a cache and TLB miss: each body owns a block of `inlineEvents` slots in one array,
// in the engine's body order (bodies sorted in space, dmd/engine.hpp): four cache lines, the
// slots' times first (finding the earliest reads two lines), then the rest of each event and the
// agenda's size. A body whose agenda outgrows its block keeps the rest in a spill vector taken
// from a pool and given back when the agenda fits again. In the dense rods a body's agenda holds
// ~7 events (up to ~18), ~6 of them virtual events of its pairs (a truncated search resumes
// there); the old layout, a std::vector of 48-byte events per body, kept the largest capacity each
// had reached (16 events, 0.8 KB, for most bodies), where a block holds 12 in 256 B.
//
// The order of a body's events is that of a vector whose removal moves the last event into the
// gap: the slots of the block first, then the spill. Times in the engine's unit (100 fs).
#include "dmd/event.hpp"
#include "dmd/spill_pool.hpp"
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace terrace::dmd {

class Agendas {
public:
    /// Slots in a body's own block.
    static constexpr int inlineEvents = 12;

    explicit Agendas(int bodies) : block_(static_cast<std::size_t>(bodies)) {}

    int size(int i) const { return block_[i].size; }
    bool empty(int i) const { return block_[i].size == 0; }

    double time(int i, int k) const {
        const Block& b = block_[i];
        return k < inlineEvents ? b.time[k] : spill_[b.spill][k - inlineEvents].time;
    }
    /// The event in i's slot k (0 ≤ k < size(i)).
    PendingEvent at(int i, int k) const {
        const Block& b = block_[i];
        if (k >= inlineEvents) return spill_[b.spill][k - inlineEvents];
        const Rest& r = b.rest[k];
        return {b.time[k], r.j, r.countJ, r.kind, r.side};
    }

    /// Appends e to i's agenda; returns its slot.
    int push(int i, const PendingEvent& e) {
        Block& b = block_[i];
        if (b.size == maxEvents) throw std::logic_error("dmd: a body's agenda overflowed");
        const int k = b.size++;
        if (k < inlineEvents) {
            put(b, k, e);
        } else {
            if (b.spill < 0) b.spill = takeSpill();
            spill_[b.spill].push_back(e);
        }
        return k;
    }

    /// Removes i's slot k by moving the last event into it.
    void remove(int i, int k) {
        Block& b = block_[i];
        const int last = b.size - 1;
        if (k != last) {
            if (last < inlineEvents)
                copySlot(b, last, k);
            else if (k < inlineEvents)
                put(b, k, spill_[b.spill].back());
            else
                spill_[b.spill][k - inlineEvents] = spill_[b.spill].back();
        }
        truncate(i, last);
    }

    /// Keeps only i's events for which keep(event) holds, in their order; returns how many went.
    template <class Keep> int keepIf(int i, Keep&& keep) {
        const int n = size(i);
        int kept = 0;
        for (int k = 0; k < n; ++k) {
            const PendingEvent e = at(i, k);
            if (!keep(e)) continue;
            if (kept != k) setSlot(i, kept, e);
            ++kept;
        }
        truncate(i, kept);
        return n - kept;
    }

    void clear(int i) { truncate(i, 0); }

    /// Asks the caches for i's block (an event about to be taken from it).
    [[gnu::always_inline]] void prefetch(int i) const {
        const char* b = reinterpret_cast<const char*>(&block_[i]);
        for (std::size_t line = 0; line < sizeof(Block); line += 64)
            __builtin_prefetch(b + line);
    }

    /// Events waiting, over all agendas.
    std::size_t events() const {
        std::size_t n = 0;
        for (const Block& b : block_)
            n += b.size;
        return n;
    }
    std::size_t bytesReserved() const {
        std::size_t b = block_.capacity() * sizeof(Block) + spill_.capacity() * sizeof(spill_[0]) +
                        freeSpill_.capacity() * sizeof(int);
        for (const auto& s : spill_)
            b += s.capacity() * sizeof(PendingEvent);
        return b;
    }

private:
    static constexpr int maxEvents = 0xffff;

    // An event's fields but its time, which sits with the other slots' times.
    struct Rest {
        std::int32_t j;
        std::uint32_t countJ;
        EventKind kind;
        std::int8_t side;
    };
    struct alignas(64) Block {
        double time[inlineEvents];
        Rest rest[inlineEvents];
        std::int32_t spill = -1; // index into spill_, or −1
        std::uint16_t size = 0;
    };
    static_assert(sizeof(Rest) == 12 && sizeof(Block) == 256, "a block is four cache lines");

    static void put(Block& b, int k, const PendingEvent& e) {
        b.time[k] = e.time;
        b.rest[k] = {e.j, e.countJ, e.kind, e.side};
    }
    static void copySlot(Block& b, int from, int to) {
        b.time[to] = b.time[from];
        b.rest[to] = b.rest[from];
    }
    void setSlot(int i, int k, const PendingEvent& e) {
        if (k < inlineEvents)
            put(block_[i], k, e);
        else
            spill_[block_[i].spill][k - inlineEvents] = e;
    }
    /// Drops every event of i from slot n on; an agenda back within its block returns its spill.
    void truncate(int i, int n) {
        Block& b = block_[i];
        b.size = static_cast<std::uint16_t>(n);
        if (b.spill < 0) return;
        if (n > inlineEvents) {
            spill_[b.spill].resize(static_cast<std::size_t>(n - inlineEvents));
            return;
        }
        spill_[b.spill].clear();
        freeSpill_.push_back(b.spill);
        b.spill = -1;
    }
    int takeSpill() { return takeFromPool(spill_, freeSpill_); }

    std::vector<Block> block_;
    std::vector<std::vector<PendingEvent>> spill_; // overflow beyond the blocks, pooled
    std::vector<int> freeSpill_;                   // spill vectors no body holds
};

} // namespace terrace::dmd
