#pragma once
// One event of the DMD engine (DESIGN.md "DMD engine"; paper, "Implementation of the
// event-driven simulation"), at an absolute time (internal unit, 100 fs). An event belongs to the
// body whose prediction found it (i) and waits in that body's agenda; the calendar (the queue)
// holds a stamped copy of each body's earliest event (dmd/engine.hpp). The owner's events leave
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

struct Event {
    double time = 0.0;
    // Virtual events: U and dU/dt at the end point of the truncated search, so that the search
    // resumes there without re-evaluating (NaN: the pair was outside r_m, start afresh).
    double U = std::numeric_limits<double>::quiet_NaN();
    double dUdt = 0.0;
    std::int32_t i = -1;
    std::int32_t j = -1;      // partner of a pair event
    std::uint32_t countJ = 0; // event counter of j when predicted
    // Calendar entries (dmd/engine.hpp): the owner's entry stamp when queued, and where the
    // event sits in the owner's agenda.
    std::uint32_t stamp = 0;
    std::uint16_t slot = 0;
    EventKind kind = EventKind::Sample;
    std::int8_t side = 0; // Collision: LevelSide; CellCrossing: 2*axis + (0 down | 1 up)
};

} // namespace terrace::dmd
