#pragma once
// The agendas of the DMD engine's schedule (dmd/schedule.hpp): each body's predicted events, of
// which the calendar holds only the earliest.
//
// Laid out for a large system, where an event's bodies are far apart in memory and every separate
// heap block is a cache and TLB miss: each body owns a block of `inlineEvents` slots in one array,
// in the engine's body order (bodies sorted in space, dmd/engine.hpp): four cache lines, the
// slots' times first (finding the earliest reads two lines), then the rest of each event, packed
// in 8 B, and the agenda's size. A body whose agenda outgrows its block keeps the rest in a spill
// vector, of the same 16-B slots, taken from a pool and given back when the agenda fits again.
// Most of an agenda's events are virtual events of its pairs (a truncated search resumes there),
// and a block of 15 holds a typical agenda whole; a vector per body would instead keep the largest
// capacity each had ever reached. Agenda sizes and the memory they take: docs/PERFORMANCE.md.
//
// The order of a body's events is that of a vector whose removal moves the last event into the
// gap: the slots of the block first, then the spill. Times in the engine's unit (100 fs).
#include "core/huge_pages.hpp"
#include "dmd/event.hpp"
#include "dmd/prefetch.hpp"
#include "dmd/spill_pool.hpp"
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace terrace::dmd {

class Agendas {
    // A packed slot's word (Rest below): partner, kind and side.
    static constexpr int partnerBits = 26, kindBits = 3;

public:
    /// Slots in a body's own block.
    static constexpr int inlineEvents = 15;
    /// Bodies an agenda can name as partners (a packed slot keeps 26 bits of j).
    static constexpr int maxBodies = (1 << partnerBits) - 1;

    explicit Agendas(int bodies) : block_(static_cast<std::size_t>(checkedBodies(bodies))) {}

    int size(int i) const { return block_[i].size; }
    bool empty(int i) const { return block_[i].size == 0; }

    double time(int i, int k) const {
        const Block& b = block_[i];
        return k < inlineEvents ? b.time[k] : spill_[b.spill][k - inlineEvents].time;
    }
    /// The event in i's slot k (0 ≤ k < size(i)).
    PendingEvent at(int i, int k) const {
        const Block& b = block_[i];
        if (k >= inlineEvents) {
            const Spilled& s = spill_[b.spill][k - inlineEvents];
            return unpack(s.time, s.rest);
        }
        return unpack(b.time[k], b.rest[k]);
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
            spill_[b.spill].push_back({e.time, pack(e)});
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
                putSpilled(b, k, spill_[b.spill].back());
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

    /// Frees the spills a passing crowd left idle (dmd/spill_pool.hpp compactPool).
    void compactSpills() {
        compactPool(spill_, freeSpill_, [&](auto&& renumber) {
            for (Block& b : block_)
                if (b.spill >= 0) renumber(b.spill);
        });
    }
    /// Spills held now, and kept in all (held or idle).
    std::size_t spillsHeld() const { return spill_.size() - freeSpill_.size(); }
    std::size_t spillsKept() const { return spill_.size(); }

    /// Asks the caches for i's block (an event about to be taken from it).
    [[gnu::always_inline]] void prefetch(int i) const { prefetchLines(&block_[i], sizeof(Block)); }

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
            b += s.capacity() * sizeof(Spilled);
        return b;
    }

private:
    static constexpr int maxEvents = 0xffff;

    // An event's fields but its time, which sits with the other slots' times: j + 1 (0: none),
    // the kind and side + 2 (side in [−2, 5]: a level side ±1, or a cell face 0–5) in one word.
    struct Rest {
        std::uint32_t tagged;
        std::uint32_t countJ;
    };
    struct Spilled {
        double time;
        Rest rest;
    };
    struct alignas(64) Block {
        double time[inlineEvents];
        Rest rest[inlineEvents];
        std::int32_t spill = -1; // index into spill_, or −1
        std::uint16_t size = 0;
    };
    static_assert(sizeof(Rest) == 8 && sizeof(Spilled) == 16, "a slot is 16 B");
    static_assert(sizeof(Block) == 256, "a block is four cache lines");
    static_assert(static_cast<int>(EventKind::Sample) < (1 << kindBits));

    static int checkedBodies(int bodies) {
        if (bodies > maxBodies)
            throw std::invalid_argument(
                "dmd: at most " + std::to_string(maxBodies) +
                " bodies (an agenda slot keeps a partner in 26 bits), not " +
                std::to_string(bodies));
        return bodies;
    }
    static Rest pack(const PendingEvent& e) {
        const auto j = static_cast<std::uint32_t>(e.j + 1);
        const auto kind = static_cast<std::uint32_t>(e.kind);
        const auto side = static_cast<std::uint32_t>(e.side + 2);
        return {j | kind << partnerBits | side << (partnerBits + kindBits), e.countJ};
    }
    static PendingEvent unpack(double time, Rest r) {
        constexpr std::uint32_t partnerMask = (1u << partnerBits) - 1;
        constexpr std::uint32_t kindMask = (1u << kindBits) - 1;
        return {
            time, static_cast<std::int32_t>(r.tagged & partnerMask) - 1, r.countJ,
            static_cast<EventKind>(r.tagged >> partnerBits & kindMask),
            static_cast<std::int8_t>(static_cast<int>(r.tagged >> (partnerBits + kindBits)) - 2)};
    }
    static void put(Block& b, int k, const PendingEvent& e) {
        b.time[k] = e.time;
        b.rest[k] = pack(e);
    }
    static void putSpilled(Block& b, int k, const Spilled& s) {
        b.time[k] = s.time;
        b.rest[k] = s.rest;
    }
    static void copySlot(Block& b, int from, int to) {
        b.time[to] = b.time[from];
        b.rest[to] = b.rest[from];
    }
    void setSlot(int i, int k, const PendingEvent& e) {
        if (k < inlineEvents)
            put(block_[i], k, e);
        else
            spill_[block_[i].spill][k - inlineEvents] = {e.time, pack(e)};
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

    BodyArray<Block> block_;
    std::vector<std::vector<Spilled>> spill_; // overflow beyond the blocks, pooled
    std::vector<int> freeSpill_;              // spill vectors no body holds
};

} // namespace terrace::dmd
