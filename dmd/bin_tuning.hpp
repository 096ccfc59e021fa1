#pragma once
// Bins of the bounded priority queue (dmd/bounded_priority_queue.hpp) sized from what the engine
// measures: the push rate and the lead time of pushed events (how far ahead of "now" they fall).
// A few events per bin, and a window of bins spanning the usual lead, keep push and pop O(1)
// (G. Paul, J. Comput. Phys. 221, 615 (2007), sec. 3). Times in the engine's unit (100 fs).
#include "dmd/bounded_priority_queue.hpp"
#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace terrace::dmd {

/// Events per bin aimed at, and the period (in events) of the retuning.
inline constexpr double eventsPerBin = 8.0;
inline constexpr std::uint64_t retunePeriod = 1u << 16;

class BinTuning {
public:
    /// horizon: the search horizon, the shortest window the bins may span.
    explicit BinTuning(double horizon) : horizon_(horizon) {}

    void pushed(double lead) {
        ++pushes_;
        leadSum_ += lead;
    }
    /// After every processed event: true when the queue is due for a retune.
    bool due() { return ++events_ >= retunePeriod; }

    template <class E> void retune(BoundedPriorityQueue<E>& q, double now) {
        // Before any event has run, the pushes of the initial prediction stand in for the rate:
        // they cover about one horizon.
        const double elapsed = now > start_ ? now - start_ : horizon_;
        if (pushes_ > 0) {
            const double rate = static_cast<double>(pushes_) / elapsed;
            const double width = eventsPerBin / rate;
            const double window = std::max(4.0 * leadSum_ / static_cast<double>(pushes_), horizon_);
            const double bins = std::clamp(window / width, 64.0, double(1 << 22));
            q.retune(width, static_cast<std::size_t>(bins));
        }
        events_ = pushes_ = 0;
        leadSum_ = 0.0;
        start_ = now;
    }

private:
    double horizon_;
    std::uint64_t events_ = 0, pushes_ = 0;
    double leadSum_ = 0.0, start_ = 0.0;
};

} // namespace terrace::dmd
