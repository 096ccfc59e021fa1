#pragma once
// One entry of the DMD event calendar (DESIGN.md "DMD engine"; paper, "Implementation of the
// event-driven simulation"). Events are scheduled at absolute times (internal unit, 100 fs) and
// stay in the queue until popped; an event is stale when one of its bodies has had an event since
// it was scheduled, which the per-body event counters captured at scheduling time reveal (lazy
// invalidation, Rapaport, J. Comput. Phys. 34, 184 (1980)).
#include <cstdint>
#include <limits>

namespace terrace::dmd {

enum class EventKind : std::uint8_t {
    Collision,    // U_ij reaches one of the two levels bounding the pair's terrace
    Virtual,      // a truncated search resumes here (paper: "virtual interaction")
    CellCrossing, // body i leaves its cell through a face
    Relist,       // body i has moved half the skin from its list's anchor: rebuild its list
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
    std::uint32_t countI = 0; // event counter of i when scheduled
    std::uint32_t countJ = 0; // event counter of j when scheduled
    EventKind kind = EventKind::Sample;
    std::int8_t side = 0; // Collision: LevelSide; CellCrossing: 2*axis + (0 down | 1 up)
};

} // namespace terrace::dmd
