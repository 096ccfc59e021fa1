#pragma once
// Guaranteed progress of an event-driven run: a clock that stops advancing (a cascade of events at
// one instant, the classic failure of event-driven codes that re-schedule the same zero-time event
// forever) is detected and reported instead of spun on. Genuinely simultaneous events involve
// distinct bodies, a handful at a time, so a long run of events without the time advancing beyond
// round-off is a stuck run.
#include "core/units.hpp"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace terrace::dmd {

/// Consecutive events without the clock advancing beyond round-off before a run counts as stuck.
inline constexpr std::uint64_t stalledEventLimit = 1'000'000;

class StallWatch {
public:
    void setLimit(std::uint64_t n) { limit_ = n; }
    std::uint64_t limit() const { return limit_; }

    /// Called with every event about to run at `next` while the clock reads `now` (time unit 100
    /// fs); throws std::runtime_error naming the time and the bodies once the clock has stopped.
    /// name(i): the number by which the message names body i (the engine's own numbering may
    /// differ from the scene's; only a report pays for the translation).
    template <class Name> void check(double now, double next, int i, int j, Name&& name) {
        const double roundOff =
            64.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(next));
        if (next - now > roundOff) {
            stalled_ = 0;
            return;
        }
        if (++stalled_ <= limit_) return;
        std::ostringstream msg;
        msg << "dmd: the clock stopped at t = " << units::toFs(next) << " fs: " << stalled_
            << " consecutive events without time advancing (last: bodies " << name(i) << " and "
            << (j >= 0 ? name(j) : j) << "); the terraced dynamics is stuck";
        throw std::runtime_error(msg.str());
    }
    void check(double now, double next, int i, int j) {
        check(now, next, i, j, [](int k) { return k; });
    }

private:
    std::uint64_t stalled_ = 0, limit_ = stalledEventLimit;
};

} // namespace terrace::dmd
