#pragma once
// How a run ends on a signal. SIGINT (Ctrl-C), SIGTERM (a batch system's time limit, kill) and
// SIGHUP (a closed terminal) all do the same:
//   1st signal   the run loop stops at the next sample; the restart file, the summary (marked
//                interrupted, naming the signal) and the analysis are written as for a finished
//                run; the exit status is 128 + the signal's number;
//   2nd signal   the analysis, if it is running, is cancelled (the summary is already written);
//   3rd signal   the process ends at once (the files written so far stay whole).
// SIGXFSZ is ignored for the guard's lifetime, so that a write past a file-size limit fails with
// EFBIG and is reported like any other failed write instead of killing the process.
#include <atomic>
#include <csignal>
#include <string>

namespace terrace::cli {

class InterruptGuard {
public:
    InterruptGuard();
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

    /// A signal has asked the run to stop.
    bool requested() const { return count() > 0; }
    /// Signals received since the guard was installed.
    int count() const;
    /// The first signal's number (0: none).
    int signal() const;
    /// "SIGTERM" and so on ("" for none).
    std::string signalName() const;
    /// The exit status for an interrupted run: 128 + the first signal's number.
    int exitStatus() const { return 128 + signal(); }
};

} // namespace terrace::cli
