#pragma once
// The DMD engine's schedule (DESIGN.md "DMD engine"; paper, "Implementation of the event-driven
// simulation"): the calendar and the per-body agendas that feed it.
//
// Every predicted event is filed in the agenda of the body whose prediction found it (Event::i);
// the calendar (the queue: a binary heap or G. Paul's bounded priority queue, dmd/event_queue.hpp)
// holds one entry per body, a stamped copy of the earliest event of its agenda, put there by
// settle() once the body's predictions are done. A collision makes some 20 predicted events
// stale, which then mostly never reach the calendar. An entry goes stale when its owner's entry
// stamp moves on (lazy invalidation), or is erased through its stored handle (`eager`); a pair
// event goes stale when its partner's event counter has moved on since its prediction (Rapaport,
// J. Comput. Phys. 34, 184 (1980)). With lazy invalidation the calendar is cleaned of stale
// entries when it grows beyond a multiple of its size after the previous cleanup; the bins of the
// bounded queue are tuned from the measured push rate (dmd/bin_tuning.hpp).
//
// Apart from the engine (dmd/engine.hpp) because this state is the schedule's alone: the engine
// and the searches (dmd/pair_prediction.hpp) only file events (schedule), pop entries, and ask
// that a body's events be dropped (invalidate). Each body's book (BodyBook) lives here too: most
// of its fields are the schedule's, and the clock and axis rate that the engine and the searches
// read share its cache line. Times in the engine's unit (100 fs).
#include "core/branch_free.hpp"
#include "dmd/bin_tuning.hpp"
#include "dmd/binary_heap_queue.hpp"
#include "dmd/bounded_priority_queue.hpp"
#include "dmd/event.hpp"
#include "dmd/event_queue.hpp"
#include "dmd/settings.hpp"
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace terrace::dmd {

/// The queue is cleaned of stale events when it exceeds this multiple of its size after the last
/// cleanup (and at least cleanupMinimumPerBody entries per body).
inline constexpr double cleanupGrowth = 3.0;
inline constexpr double cleanupMinimumPerBody = 16.0;
/// A body's list of the owners of calendar entries about it is pruned from this size on.
inline constexpr std::size_t aboutPruneSize = 32;

/// A body's scalars, in one cache line: an event reads most of them for its own body, and
/// clock, axis rate and counter for each partner; in a large system, where an event's bodies
/// are far apart in memory, that is one line fetched per body instead of one per array.
struct alignas(64) BodyBook {
    double clock = 0.0;    // its local clock: the time its stored state is for
    double axisRate = 0.0; // axisRateBound at its clock (rad per time unit)
    // time of its earliest agenda event (+∞: agenda empty, −∞: unknown)
    double agendaFirstTime = std::numeric_limits<double>::infinity();
    // time of its calendar entry (+∞: none)
    double queuedAt = std::numeric_limits<double>::infinity();
    std::uint64_t unsettledRound = 0; // round in which it was last marked unsettled
    std::uint32_t counter = 0;        // bumped whenever its velocities change
    std::uint32_t entryStamp = 0;     // stamp of its current calendar entry
    std::int32_t entryPartner = -1;   // the partner of that entry (−1: a body event)
    std::uint16_t agendaFirst = 0;    // index of its earliest event (unknownFirst: scan)
};
static_assert(sizeof(BodyBook) == 64, "a body's scalars fill one cache line");

/// Owner: the engine whose schedule this is (dmd::Engine<K, P>). Nothing here depends on it: it
/// gives each engine its own copy of these functions, as when they were the engine's members, so
/// that g++ inlines them as it did then (it weighs a function by its calls, and with the calls of
/// every engine in one copy it kept some of the small steps out of line: a call more per event).
template <class Owner> class Schedule {
public:
    using Queue = std::variant<BinaryHeapQueue<Event>, BoundedPriorityQueue<Event>>;

    Schedule(int bodies, bool eager, double horizon)
        : book_(bodies), agenda_(bodies), entry_(eager ? bodies : 0), about_(bodies), eager_(eager),
          tuning_(horizon) {}

    /// The calendar of the kind the settings name, starting at now.
    void openCalendar(QueueKind kind, double horizon, double now) {
        if (kind == QueueKind::Heap)
            queue_.emplace<BinaryHeapQueue<Event>>(eager_); // handles only to erase (eager)
        else
            queue_.emplace<BoundedPriorityQueue<Event>>(horizon / 16.0, 1024, now);
    }
    /// f(q) with the calendar's queue, of its own type: the members below that take a Q are
    /// handed the q that this gives.
    template <class F> void visitQueue(F&& f) { std::visit(std::forward<F>(f), queue_); }
    /// The bins of the bounded queue sized from the pushes so far.
    void retuneBins(double now) {
        if (auto* bpq = std::get_if<BoundedPriorityQueue<Event>>(&queue_))
            tuning_.retune(*bpq, now);
    }

    BodyBook& book(int i) { return book_[i]; }
    const BodyBook& book(int i) const { return book_[i]; }

    /// Every event is filed in the agenda of the body it belongs to (e.i: the body whose
    /// prediction found it); the calendar (the queue) holds one entry per body, a copy of the
    /// earliest event of its agenda, put there by settle() once the body's predictions are done.
    /// A collision invalidates some 20 events of its two bodies; with one entry per body they
    /// mostly never reach the calendar, which then pushes and pops a third as many entries.
    [[gnu::flatten]] void schedule(const Event& e) { // (flat: push_back was a call per event)
        auto& agenda = agenda_[e.i];
        if (agenda.size() >= std::numeric_limits<std::uint16_t>::max())
            throw std::logic_error("dmd: a body's agenda overflowed");
        agenda.push_back(e);
        // The earliest is kept as events arrive, so that settling a body just refilled needs no
        // scan; ties keep the first, as the scan does. By a select, not a branch (whether it is
        // earlier is a coin toss); an unknown earliest has time −∞ and stays unknown.
        const bool earlier = e.time < book_[e.i].agendaFirstTime;
        const auto last = static_cast<std::uint16_t>(agenda.size() - 1);
        book_[e.i].agendaFirst = earlier ? last : book_[e.i].agendaFirst;
        book_[e.i].agendaFirstTime = lesser(e.time, book_[e.i].agendaFirstTime);
        if (e.time < book_[e.i].queuedAt) markUnsettled(e.i);
    }

    void markUnsettled(int i) {
        if (book_[i].unsettledRound == settleRound_) return;
        book_[i].unsettledRound = settleRound_;
        unsettled_.push_back(i);
    }

    /// Gives every body marked unsettled the calendar entry of its earliest valid agenda event.
    /// An earliest event whose partner has moved on since is dropped from the agenda and the
    /// search repeats (the others wait until they come first, or until the agenda is emptied);
    /// a drop moves another event, so the entry is then renewed too: it records its event's place.
    /// now: the engine's time, from which the bin tuning measures the lead of each push.
    template <class Q> void settle(Q& q, double now) {
        for (const int i : unsettled_) {
            auto& agenda = agenda_[i];
            bool moved = false;
            std::size_t best = 0;
            for (;;) {
                if (agenda.empty()) break;
                best = earliestInAgenda(i);
                const Event& a = agenda[best];
                if (a.j < 0 || book_[a.j].counter == a.countJ) break;
                ++staleInAgendas_;
                removeFromAgenda(i, best);
                moved = true;
            }
            if (agenda.empty()) {
                dropEntry(q, i);
                continue;
            }
            if (!moved && agenda[best].time >= book_[i].queuedAt)
                continue; // the queued entry stands
            dropEntry(q, i);
            Event entry = agenda[best];
            entry.stamp = ++book_[i].entryStamp;
            entry.slot = static_cast<std::uint16_t>(best);
            book_[i].queuedAt = entry.time;
            const QueueHandle h = q.push(entry);
            if (eager_) entry_[i] = h;
            book_[i].entryPartner = entry.j;
            if (entry.j >= 0) keepAbout(entry.j, i);
            maxQueueSize_ = std::max<std::uint64_t>(maxQueueSize_, q.size());
            tuning_.pushed(entry.time - now);
        }
        unsettled_.clear();
        ++settleRound_;
    }

    /// i's calendar entry no longer stands: the stamp makes it stale (lazy), or it is erased
    /// (eager).
    template <class Q> void dropEntry(Q& q, int i) {
        if (!std::isfinite(book_[i].queuedAt)) return;
        ++book_[i].entryStamp;
        book_[i].queuedAt = std::numeric_limits<double>::infinity();
        if (eager_) q.erase(entry_[i]);
    }

    /// Whether a calendar entry is its owner's current one (only the stamp can tell, in either
    /// mode: the partner's counter is checked once the entry is taken).
    bool isCurrentEntry(const Event& e) const { return e.stamp == book_[e.i].entryStamp; }

    /// The entry just popped leaves its owner's agenda; the owner needs a new one.
    void takeFromAgenda(const Event& e) {
        removeFromAgenda(e.i, e.slot);
        ++book_[e.i].entryStamp;
        book_[e.i].queuedAt = std::numeric_limits<double>::infinity();
        markUnsettled(e.i);
    }

    /// Bodies whose calendar entry is about i (a pair event with partner i) are listed with i, so
    /// that invalidating i renews those entries at once. A body that rarely collides would pile
    /// up owners whose entries have moved on, and the same owner once per entry it renewed (a
    /// chain of virtual events); when its list reaches 32, 64, 128, … entries, it keeps only the
    /// owners whose entry is about i now, each once (amortised O(1) per entry).
    void keepAbout(int i, int owner) {
        auto& list = about_[i];
        if (list.size() >= aboutPruneSize && (list.size() & (list.size() - 1)) == 0) {
            std::erase_if(list, [&](int k) { return !entryIsAbout(k, i); });
            std::sort(list.begin(), list.end());
            list.erase(std::unique(list.begin(), list.end()), list.end());
        }
        list.push_back(owner);
    }
    bool entryIsAbout(int owner, int i) const {
        return std::isfinite(book_[owner].queuedAt) && book_[owner].entryPartner == i;
    }

    /// Index of the earliest event of i's non-empty agenda (the first of equals).
    std::size_t earliestInAgenda(int i) {
        auto& first = book_[i].agendaFirst;
        if (first == unknownFirst) {
            const auto& agenda = agenda_[i];
            std::size_t best = 0;
            for (std::size_t k = 1; k < agenda.size(); ++k)
                if (agenda[k].time < agenda[best].time) best = k;
            first = static_cast<std::uint16_t>(best);
            book_[i].agendaFirstTime = agenda[best].time;
        }
        return first;
    }
    /// Removes one event by moving the last into its place: the earliest must be found again.
    void removeFromAgenda(int i, std::size_t slot) {
        auto& agenda = agenda_[i];
        agenda[slot] = agenda.back();
        agenda.pop_back();
        book_[i].agendaFirst = unknownFirst;
        book_[i].agendaFirstTime = -std::numeric_limits<double>::infinity();
    }

    void forgetAgenda(int i) {
        agenda_[i].clear();
        book_[i].agendaFirst = 0; // the next event scheduled is the earliest
        book_[i].agendaFirstTime = std::numeric_limits<double>::infinity();
        ++book_[i].entryStamp;
        book_[i].queuedAt = std::numeric_limits<double>::infinity();
    }

    /// Body i's velocities changed: its pending events no longer hold. Its agenda is emptied, and
    /// the bodies whose calendar entry is about i get their next one at once: with lazy
    /// invalidation the old entries stay in the calendar, stale, with eager invalidation they are
    /// erased; either way the same entries are pushed in the same order, so both give the same
    /// trajectory. Other events about i that wait in agendas go stale by its counter and are
    /// dropped when they come first.
    template <class Q> void invalidate(Q& q, int i) {
        ++book_[i].counter;
        dropEntry(q, i);
        for (const int k : about_[i])
            if (entryIsAbout(k, i)) {
                dropEntry(q, k);
                markUnsettled(k);
            }
        about_[i].clear();
        forgetAgenda(i);
    }

    /// Forgets every pending event: the calendar is emptied, and every body's events are
    /// invalidated.
    template <class Q> void forgetAll(Q& q) {
        q.clear();
        for (int i = 0; i < static_cast<int>(book_.size()); ++i) {
            ++book_[i].counter;
            forgetAgenda(i);
        }
        for (auto& h : about_)
            h.clear();
    }

    /// After every processed event: with lazy invalidation, the calendar is cleaned of stale
    /// entries once it has grown cleanupGrowth-fold; the bins are retuned when due.
    template <class Q> void afterEvent(Q& q, double now) {
        if (!eager_ && static_cast<double>(q.size()) > cleanupThreshold_) {
            q.removeIf([this](const Event& e) {
                return e.kind != EventKind::Sample && !isCurrentEntry(e);
            });
            ++cleanups_;
            resetCleanupThreshold(q.size());
        }
        if constexpr (std::is_same_v<Q, BoundedPriorityQueue<Event>>)
            if (tuning_.due()) tuning_.retune(q, now);
    }
    /// The next cleanup comes when the calendar has grown cleanupGrowth-fold from `queued`.
    void resetCleanupThreshold(std::size_t queued) {
        cleanupThreshold_ = std::max(cleanupMinimumPerBody * static_cast<double>(book_.size()),
                                     cleanupGrowth * static_cast<double>(queued));
    }

    std::size_t queueSize() const {
        return std::visit([](const auto& q) { return q.size(); }, queue_);
    }
    std::size_t bytesReserved() const {
        std::size_t b = std::visit([](const auto& q) { return q.bytesReserved(); }, queue_);
        b += book_.capacity() * sizeof(BodyBook);
        b += agenda_.capacity() * sizeof(agenda_[0]) + entry_.capacity() * sizeof(QueueHandle) +
             about_.capacity() * sizeof(about_[0]);
        for (const auto& a : agenda_)
            b += a.capacity() * sizeof(Event);
        for (const auto& h : about_)
            b += h.capacity() * sizeof(int);
        return b;
    }
    std::uint64_t maxQueueSize() const { return maxQueueSize_; }
    std::uint64_t cleanups() const { return cleanups_; }
    std::uint64_t staleInAgendas() const { return staleInAgendas_; }

private:
    static constexpr std::uint16_t unknownFirst = std::numeric_limits<std::uint16_t>::max();

    std::vector<BodyBook> book_;
    std::vector<std::vector<Event>> agenda_; // each body's pending events (e.i = the body)
    std::vector<QueueHandle> entry_;         // eager: the handle of each body's calendar entry
    std::vector<std::vector<int>> about_;    // owners whose entry is about the body
    std::vector<int> unsettled_;             // bodies whose entry settle() must renew
    std::uint64_t settleRound_ = 1;
    bool eager_;
    Queue queue_;
    BinTuning tuning_;
    std::uint64_t maxQueueSize_ = 0, cleanups_ = 0, staleInAgendas_ = 0;
    double cleanupThreshold_ = 0.0;
};

} // namespace terrace::dmd
