#pragma once
// The DMD engine's schedule (DESIGN.md "DMD engine"; paper, "Implementation of the event-driven
// simulation"): the calendar and the per-body agendas that feed it.
//
// Every predicted event is filed in the agenda of the body whose prediction found it (Event::i);
// the calendar (the queue: a binary heap, G. Paul's bounded priority queue or a tournament tree
// over the bodies, dmd/event_queue.hpp) holds one entry per body, a stamped copy of the earliest
// event of its agenda, put there by settle() once the body's predictions are done. A collision
// makes some 20 predicted events stale, which then mostly never reach the calendar. An entry goes
// stale when its owner's entry stamp moves on (lazy invalidation), or is erased through its stored
// handle (`eager`); a pair event goes stale when its partner's event counter has moved on since its
// prediction (Rapaport, J. Comput. Phys. 34, 184 (1980)). With lazy invalidation the calendar is
// cleaned of stale entries when it grows beyond a multiple of its size after the previous cleanup;
// the bins of the bounded queue are tuned from the measured push rate (dmd/bin_tuning.hpp).
//
// Apart from the engine (dmd/engine.hpp) because this state is the schedule's alone: the engine
// and the searches (dmd/pair_prediction.hpp) only file events (schedule), pop entries, and ask
// that a body's events be dropped (invalidate). Each body's book (BodyBook) lives here too: most
// of its fields are the schedule's, and the clock and axis rate that the engine and the searches
// read share its cache line. Times in the engine's unit (100 fs).
#include "core/branch_free.hpp"
#include "core/huge_pages.hpp"
#include "dmd/agendas.hpp"
#include "dmd/bin_tuning.hpp"
#include "dmd/binary_heap_queue.hpp"
#include "dmd/bounded_priority_queue.hpp"
#include "dmd/event.hpp"
#include "dmd/event_queue.hpp"
#include "dmd/settings.hpp"
#include "dmd/tournament_queue.hpp"
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
    std::uint32_t counter = 0;      // bumped whenever its velocities change
    std::uint32_t entryStamp = 0;   // stamp of its current calendar entry
    std::int32_t entryPartner = -1; // the partner of that entry (−1: a body event, or none)
    // Neighbours in the list of the owners whose entry is about that partner (−1: none).
    std::int32_t aboutPrev = -1, aboutNext = -1;
    // The first owner whose entry is about this body (−1: none): here, not in an array of its
    // own, because the book is read anyway wherever the list is (settle checks the partner's
    // counter, invalidate bumps the body's own), and another array would be one more miss.
    std::int32_t aboutFirst = -1;
    std::uint16_t agendaFirst = 0; // index of its earliest event (unknownFirst: scan)
    bool unsettled = false;        // listed for settle() to renew its entry
};
static_assert(sizeof(BodyBook) == 64, "a body's scalars fill one cache line");

/// Owner: the engine state whose schedule this is (dmd::EngineState<K, P>). Nothing here depends
/// on it: it gives each engine its own copy of these functions, as when they were the engine's
/// members, so
/// that g++ inlines them as it did then (it weighs a function by its calls, and with the calls of
/// every engine in one copy it kept some of the small steps out of line: a call more per event).
template <class Owner> class Schedule {
public:
    using Queue =
        std::variant<BinaryHeapQueue<Event>, BoundedPriorityQueue<Event>, TournamentQueue<Event>>;

    Schedule(int bodies, bool eager, double horizon)
        : book_(bodies), agendas_(bodies), entry_(eager ? bodies : 0), eager_(eager),
          tuning_(horizon) {}

    /// The calendar of the kind the settings name, starting at now.
    void openCalendar(QueueKind kind, double horizon, double now) {
        if (kind == QueueKind::Heap)
            queue_.emplace<BinaryHeapQueue<Event>>(eager_); // handles only to erase (eager)
        else if (kind == QueueKind::Tree)
            queue_.emplace<TournamentQueue<Event>>(static_cast<int>(book_.size()));
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
    /// Asks the caches for i's book and agenda.
    [[gnu::always_inline]] void prefetch(int i) const {
        __builtin_prefetch(&book_[i]);
        agendas_.prefetch(i);
    }
    [[gnu::always_inline]] void prefetchBook(int i) const { __builtin_prefetch(&book_[i]); }
    const BodyBook& book(int i) const { return book_[i]; }

    /// Every event is filed in the agenda of the body it belongs to (e.i: the body whose
    /// prediction found it); the calendar (the queue) holds one entry per body, a copy of the
    /// earliest event of its agenda, put there by settle() once the body's predictions are done.
    /// A collision invalidates some 20 events of its two bodies; with one entry per body they
    /// mostly never reach the calendar, which then pushes and pops a third as many entries.
    [[gnu::flatten]] void schedule(int i, const PendingEvent& e) {
        // (flatten: otherwise the filing is a call per event)
        if (agendas_.size(i) == Agendas::inlineEvents) dropStale(i);
        const int last = agendas_.push(i, e);
        // The earliest is kept as events arrive, so that settling a body just refilled needs no
        // scan; ties keep the first, as the scan does. By a select, not a branch (whether it is
        // earlier is a coin toss); an unknown earliest has time −∞ and stays unknown.
        const bool earlier = e.time < book_[i].agendaFirstTime;
        book_[i].agendaFirst = earlier ? static_cast<std::uint16_t>(last) : book_[i].agendaFirst;
        book_[i].agendaFirstTime = lesser(e.time, book_[i].agendaFirstTime);
        if (e.time < book_[i].queuedAt) markUnsettled(i);
    }

    /// Drops the stale events of i's agenda (partner moved on since), so that a full block need
    /// not spill (a quarter of the events waiting are stale). Events move, so i's calendar entry,
    /// which records its event's slot, is renewed.
    void dropStale(int i) {
        const int dropped = agendas_.keepIf(
            i, [&](const PendingEvent& a) { return a.j < 0 || book_[a.j].counter == a.countJ; });
        if (dropped == 0) return;
        staleInAgendas_ += static_cast<std::uint64_t>(dropped);
        book_[i].agendaFirst = unknownFirst;
        book_[i].agendaFirstTime = -std::numeric_limits<double>::infinity();
        if (std::isfinite(book_[i].queuedAt)) {
            visitQueue([&](auto& q) { dropEntry(q, i); });
            markUnsettled(i);
        }
    }

    void markUnsettled(int i) {
        if (book_[i].unsettled) return;
        book_[i].unsettled = true;
        unsettled_.push_back(i);
    }

    /// Gives every body marked unsettled the calendar entry of its earliest valid agenda event.
    /// An earliest event whose partner has moved on since is dropped from the agenda and the
    /// search repeats (the others wait until they come first, or until the agenda is emptied);
    /// a drop moves another event, so the entry is then renewed too: it records its event's place.
    /// now: the engine's time, from which the bin tuning measures the lead of each push.
    template <class Q> void settle(Q& q, double now) {
        for (const int i : unsettled_) {
            book_[i].unsettled = false;
            bool moved = false;
            int best = 0;
            PendingEvent a; // the earliest valid event, once found
            for (;;) {
                if (agendas_.empty(i)) break;
                best = earliestInAgenda(i);
                a = agendas_.at(i, best);
                if (a.j < 0 || book_[a.j].counter == a.countJ) break;
                ++staleInAgendas_;
                removeFromAgenda(i, best);
                moved = true;
            }
            if (agendas_.empty(i)) {
                dropEntry(q, i);
                continue;
            }
            if (!moved && a.time >= book_[i].queuedAt) continue; // the queued entry stands
            dropEntry(q, i);
            const Event entry{a.time,
                              i,
                              a.j,
                              a.countJ,
                              ++book_[i].entryStamp,
                              static_cast<std::uint16_t>(best),
                              a.kind,
                              a.side};
            book_[i].queuedAt = entry.time;
            const QueueHandle h = q.push(entry);
            if (eager_) entry_[i] = h;
            if (entry.j >= 0) linkAbout(i, entry.j);
            maxQueueSize_ = std::max<std::uint64_t>(maxQueueSize_, q.size());
            tuning_.pushed(entry.time - now);
        }
        unsettled_.clear();
    }

    /// i's calendar entry no longer stands: the stamp makes it stale (lazy), or it is erased
    /// (eager).
    template <class Q> void dropEntry(Q& q, int i) {
        if (!std::isfinite(book_[i].queuedAt)) return;
        unlinkAbout(i);
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
        unlinkAbout(e.i);
        ++book_[e.i].entryStamp;
        book_[e.i].queuedAt = std::numeric_limits<double>::infinity();
        markUnsettled(e.i);
    }

    /// The owners whose calendar entry is about i (a pair event with partner i) are listed with i,
    /// so that invalidating i renews those entries at once. Each body has at most one entry, so
    /// the lists are threaded through the books (aboutPrev, aboutNext) from the first owner in
    /// the partner's book (aboutFirst), and an owner leaves its list the moment its entry stops
    /// standing.
    void linkAbout(int owner, int i) {
        BodyBook& b = book_[owner];
        b.entryPartner = i;
        b.aboutPrev = -1;
        b.aboutNext = book_[i].aboutFirst;
        if (b.aboutNext >= 0) book_[b.aboutNext].aboutPrev = owner;
        book_[i].aboutFirst = owner;
    }
    void unlinkAbout(int owner) {
        BodyBook& b = book_[owner];
        if (b.entryPartner < 0) return;
        if (b.aboutPrev >= 0)
            book_[b.aboutPrev].aboutNext = b.aboutNext;
        else
            book_[b.entryPartner].aboutFirst = b.aboutNext;
        if (b.aboutNext >= 0) book_[b.aboutNext].aboutPrev = b.aboutPrev;
        b.entryPartner = b.aboutPrev = b.aboutNext = -1;
    }

    /// Index of the earliest event of i's non-empty agenda (the first of equals).
    int earliestInAgenda(int i) {
        auto& first = book_[i].agendaFirst;
        if (first == unknownFirst) {
            const int n = agendas_.size(i);
            int best = 0;
            double bestTime = agendas_.time(i, 0);
            for (int k = 1; k < n; ++k) {
                const double t = agendas_.time(i, k);
                if (t < bestTime) {
                    best = k;
                    bestTime = t;
                }
            }
            first = static_cast<std::uint16_t>(best);
            book_[i].agendaFirstTime = bestTime;
        }
        return first;
    }
    /// Removes one event by moving the last into its place: the earliest must be found again.
    void removeFromAgenda(int i, int slot) {
        agendas_.remove(i, slot);
        book_[i].agendaFirst = unknownFirst;
        book_[i].agendaFirstTime = -std::numeric_limits<double>::infinity();
    }

    void forgetAgenda(int i) {
        agendas_.clear(i);
        book_[i].agendaFirst = 0; // the next event scheduled is the earliest
        book_[i].agendaFirstTime = std::numeric_limits<double>::infinity();
        unlinkAbout(i);
        ++book_[i].entryStamp;
        book_[i].queuedAt = std::numeric_limits<double>::infinity();
    }

    /// Body i's velocities changed: its pending events no longer hold. Its agenda is emptied, and
    /// the bodies whose calendar entry is about i get their next one at once: with lazy
    /// invalidation the old entries stay in the calendar, stale, with eager invalidation they are
    /// erased; either way the same entries are pushed in the same order, so both give the same
    /// trajectory. Other events about i that wait in agendas go stale by its counter and are
    /// dropped when they come first.
    /// askAhead: whether to ask the caches now for what settle() will read of those bodies, their
    /// agendas and calendar paths, which in a large system are far and would be waited on when
    /// the event ends; the event's predictions run meanwhile.
    template <class Q> void invalidate(Q& q, int i, bool askAhead) {
        ++book_[i].counter;
        dropEntry(q, i);
        for (int k = book_[i].aboutFirst; k >= 0;) {
            const int next = book_[k].aboutNext;
            dropEntry(q, k); // leaves i's list
            markUnsettled(k);
            if (askAhead) {
                agendas_.prefetch(k);
                if constexpr (requires { q.prefetchPath(std::size_t{}); })
                    q.prefetchPath(static_cast<std::size_t>(k));
            }
            k = next;
        }
        forgetAgenda(i);
    }

    /// Forgets every pending event: the calendar is emptied, and every body's events are
    /// invalidated.
    template <class Q> void forgetAll(Q& q) {
        q.clear();
        for (int i = 0; i < static_cast<int>(book_.size()); ++i) {
            ++book_[i].counter;
            forgetAgenda(i); // leaves the list it was in
        }
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
    /// Bytes held, by part: the calendar, the books (with the lists of owners whose entry is
    /// about each body) and the agendas; and the events waiting in agendas.
    struct Memory {
        std::size_t calendar = 0, books = 0, agendas = 0;
        std::size_t agendaEvents = 0; // events, not bytes
    };
    Memory memory() const {
        Memory m;
        m.calendar = std::visit([](const auto& q) { return q.bytesReserved(); }, queue_) +
                     entry_.capacity() * sizeof(QueueHandle) + unsettled_.capacity() * sizeof(int);
        m.books = book_.capacity() * sizeof(BodyBook);
        m.agendas = agendas_.bytesReserved();
        m.agendaEvents = agendas_.events();
        return m;
    }
    std::size_t bytesReserved() const {
        const Memory m = memory();
        return m.calendar + m.books + m.agendas;
    }
    /// Frees the calendar and the agendas, keeping the books (each body's clock): for an engine
    /// about to be dropped (Engine::shed).
    void shed() {
        agendas_ = Agendas(0);
        queue_.emplace<BinaryHeapQueue<Event>>();
        std::vector<QueueHandle>().swap(entry_);
        std::vector<int>().swap(unsettled_);
    }
    /// Frees the agenda spills a passing crowd left idle (dmd/agendas.hpp).
    void compactSpills() { agendas_.compactSpills(); }
    const Agendas& agendas() const { return agendas_; }
    std::uint64_t maxQueueSize() const { return maxQueueSize_; }
    std::uint64_t cleanups() const { return cleanups_; }
    std::uint64_t staleInAgendas() const { return staleInAgendas_; }

private:
    static constexpr std::uint16_t unknownFirst = std::numeric_limits<std::uint16_t>::max();

    BodyArray<BodyBook> book_;
    Agendas agendas_;                // each body's pending events
    std::vector<QueueHandle> entry_; // eager: the handle of each body's calendar entry
    std::vector<int> unsettled_;     // bodies whose entry settle() must renew
    bool eager_;
    Queue queue_;
    BinTuning tuning_;
    std::uint64_t maxQueueSize_ = 0, cleanups_ = 0, staleInAgendas_ = 0;
    double cleanupThreshold_ = 0.0;
};

} // namespace terrace::dmd
