#pragma once
// The jittered horizon of the DMD searches (paper, "Implementation of the event-driven
// simulation"): each search is truncated at Δt (1 − j u) with u uniform in [0, 1), so that the
// virtual events of many pairs do not fall on one instant. u comes from a named stream ("dmd.hor")
// derived from the scene's one seed: SplitMix64 (Steele, Lea & Flood, OOPSLA 2014), cheap enough to
// draw at every search. Times in the caller's unit.
#include <cstdint>

namespace terrace::dmd {

class HorizonJitter {
public:
    /// horizon: Δt; jitter: j, the largest relative shortening.
    HorizonJitter(double horizon, double jitter, std::uint64_t seed)
        : horizon_(horizon), jitter_(jitter), state_(seed ^ std::uint64_t{0x646d642e686f72ull}) {
        ready_ = draw();
    }

    /// The next horizon of the stream. Drawn one call ahead: the caller compares with it at once,
    /// and the draw's chain of multiplications (~20 cycles) then runs beside other work instead
    /// of in front of that comparison. The values are the same.
    double next() {
        const double h = ready_;
        ready_ = draw();
        return h;
    }

    /// Where the stream stands, to continue it exactly in a resumed run (cli restart files).
    struct Position {
        std::uint64_t state;
        double ready;
    };
    Position position() const { return {state_, ready_}; }
    void resumeAt(const Position& p) {
        state_ = p.state;
        ready_ = p.ready;
    }

private:
    double draw() {
        std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        z ^= z >> 31;
        // uniform in [0, 1); z >> 11 < 2^53 converts as a signed integer, in one instruction
        const double u = static_cast<double>(static_cast<std::int64_t>(z >> 11)) * 0x1.0p-53;
        return horizon_ * (1.0 - jitter_ * u);
    }

    double horizon_, jitter_;
    std::uint64_t state_;
    double ready_; // the value next() returns
};

} // namespace terrace::dmd
