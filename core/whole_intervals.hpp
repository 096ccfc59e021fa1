#pragma once
// How many whole intervals a length holds, as the run and the scene's validation both count them:
// a ratio within limits::gridTolerance of a whole number is that number (9 ps / 9 fs is not
// exact in binary), any other holds its floor and leaves a part (cli/run_driver.cpp planRun).
#include "core/scene.hpp"
#include <cmath>

namespace terrace {

/// Whether `ratio` (length / interval) is a whole number of intervals, within the grid tolerance.
inline bool isWholeRatio(double ratio) {
    return std::abs(ratio - std::round(ratio)) <= limits::gridTolerance * std::max(1.0, ratio);
}

/// The whole intervals in `ratio`: its nearest integer when it is whole, else its floor.
inline long wholeIntervals(double ratio) {
    return isWholeRatio(ratio) ? std::lround(ratio) : long(std::floor(ratio));
}

} // namespace terrace
