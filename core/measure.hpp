#pragma once
// Measurement switches: each turns off one optimisation that changes no observable, so that what
// it buys can be measured, or that it changes nothing can be checked. They are not part of a
// scene (a scene says what to simulate, not how to time it): they are read from the environment,
//   TERRACE_MEASURE=switch[,switch...]
//     no-hold-screen  DMD searches every pair without first screening it by its hold time
//                     (dmd/pair_prediction.hpp); the events are the same
//     no-sort-dmd     DMD keeps the bodies in the scene's numbering inside the engine instead of
//                     the Morton order of their cells (dmd/engine.hpp)
//     no-sort-smd     SMD keeps the bodies in the scene's numbering instead of the neighbour
//                     list's cell order (smd/engine.hpp); the trajectory is the same bit for bit
// Unset or empty: every optimisation on. Any other word is an error (std::invalid_argument), which
// terrace reports at start-up, before anything runs.
#include <string>

namespace terrace {

struct MeasureSwitches {
    bool holdScreen = true; // DMD's hold-time screen
    bool sortDmd = true;    // DMD's bodies in Morton order of their cells
    bool sortSmd = true;    // SMD's bodies in the neighbour list's cell order
};

/// The switches named in `text` (comma-separated, as TERRACE_MEASURE holds them).
MeasureSwitches parseMeasureSwitches(const std::string& text);

/// The switches TERRACE_MEASURE sets now (read at each call, so that a test can set it).
MeasureSwitches measureSwitches();

} // namespace terrace
