#pragma once
// Long analyses can be stopped from outside: the run driver installs a predicate (a signal
// arrived) for the duration of an analysis, and the loops over frames and bodies call
// throwIfCancelled(), which throws Cancelled once the predicate says so. Without an installed
// predicate nothing is ever cancelled. One analysis at a time per thread.
#include <functional>
#include <stdexcept>

namespace terrace::analysis {

class Cancelled : public std::runtime_error {
public:
    Cancelled() : std::runtime_error("analysis cancelled") {}
};

/// Installs `cancelled` until destroyed (the previous predicate is restored then).
class ScopedCancellation {
public:
    explicit ScopedCancellation(std::function<bool()> cancelled);
    ~ScopedCancellation();
    ScopedCancellation(const ScopedCancellation&) = delete;
    ScopedCancellation& operator=(const ScopedCancellation&) = delete;

private:
    std::function<bool()> previous_;
};

void throwIfCancelled();

} // namespace terrace::analysis
