#pragma once
// One event of the DMD engine (DESIGN.md "DMD engine"; paper, "Implementation of the
// event-driven simulation"), at an absolute time (internal unit, 100 fs). An event belongs to the
// body whose prediction found it (its owner, i) and waits in that body's agenda (PendingEvent);
// the calendar (the queue) holds a stamped copy of each body's earliest event (Event,
// dmd/schedule.hpp). The owner's events leave
// with its agenda when it has an event of its own; one of a pair is stale once its partner j has
// had an event since it was predicted, which the partner's event counter captured at prediction
// time reveals (lazy invalidation, Rapaport, J. Comput. Phys. 34, 184 (1980)).
#include <cstdint>
#include <limits>

namespace terrace::dmd {

enum class EventKind : std::uint8_t {
    Collision,    // U_ij reaches one of the two levels bounding the pair's terrace
    Virtual,      // a truncated search resumes here (paper: "virtual interaction")
    CellCrossing, // body i leaves its cell through a face
    Relist,       // body i has moved skin/3 from its list's anchor: rebuild its list
    Sample,       // all clocks are brought to this time (advanceTo)
};

/// Which level of the terrace a collision reaches.
enum class LevelSide : std::int8_t { Lower = -1, Upper = +1 };

/// A predicted event as it waits in the agenda of the body whose prediction found it (its
/// owner, dmd/agendas.hpp).
/// A virtual event carries no more than its time: the search that resumes there evaluates U and
/// dU/dt afresh (one evaluation more than resuming from stored values, 16 B less per waiting
/// event, of which there are ~7 per body in a dense liquid).
struct PendingEvent {
    double time = 0.0;
    std::int32_t j = -1;      // partner of a pair event
    std::uint32_t countJ = 0; // event counter of j when predicted
    EventKind kind = EventKind::Sample;
    std::int8_t side = 0; // Collision: LevelSide; CellCrossing: 2*axis + (0 down | 1 up)
};

/// A calendar entry (dmd/schedule.hpp): a stamped copy of its owner's earliest pending event, 32 B,
/// so that a large calendar's nodes stay small.
struct Event {
    double time = 0.0;
    std::int32_t i = -1;      // the owner
    std::int32_t j = -1;      // partner of a pair event
    std::uint32_t countJ = 0; // event counter of j when predicted
    std::uint32_t stamp = 0;  // the owner's entry stamp when queued
    std::uint16_t slot = 0;   // where the event sits in the owner's agenda
    EventKind kind = EventKind::Sample;
    std::int8_t side = 0;
};
static_assert(sizeof(Event) == 32);

/// What the calendar's root tells of an entry's partner (dmd/tournament_queue.hpp topBodies),
/// so that the engine asks the caches for no more of it than the event will read: j for a
/// collision, which rewrites both bodies' agendas, lists and entries; −2 − j for another event of
/// a pair, which reads only j's motion and book; −1 for an event of the owner alone.
inline std::int32_t rootPartner(const Event& e) {
    if (e.j < 0 || e.kind == EventKind::Collision) return e.j;
    return -2 - e.j;
}
/// The partner of a pair's other event from its rootPartner code (≤ −2).
inline int pairPartnerOfRootCode(int code) {
    return -2 - code;
}

} // namespace terrace::dmd
