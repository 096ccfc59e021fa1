#pragma once
// SIGINT handling for long runs: the first Ctrl-C asks the run loop to stop at the next sample
// (output is then written and flushed as for a finished run); a second one ends the process at
// once.
#include <atomic>
#include <csignal>

namespace terrace::cli {

class InterruptGuard {
public:
    InterruptGuard();
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;
    bool requested() const;
};

} // namespace terrace::cli
