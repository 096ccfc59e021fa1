#pragma once
// One run of a sweep as a child process: `terrace run` (this same executable) with the sweep's
// scene and the run's overrides, or `terrace run --continue` on a run a restart file can finish.
// A process of its own keeps a run's CPU clock, its memory and a crash to itself, and makes a
// run's output the same whoever started it (a sweep with -j 1, -j 8 or under mpirun on any rank).
// The child gets a process group of its own, so that a terminal's Ctrl-C reaches the sweep alone
// and the sweep passes it on once (the child then stops at its next sample and writes). Its
// standard output and error go to DIR/run.log.
#include "cli/sweep_plan.hpp"
#include <chrono>
#include <csignal>
#include <filesystem>
#include <optional>
#include <sys/types.h>

namespace terrace::cli {

enum class RunAction { Fresh, Continue, Skip };

/// How a child ended.
struct ChildExit {
    bool signalled = false; // killed by a signal (code is its number) rather than exiting
    int code = 0;           // exit status, or the signal's number
};

class RunProcess {
public:
    RunProcess() = default;
    /// Starts the run `run` of `plan` in `dir` (created if needed); Fresh overwrites whatever an
    /// earlier run left there, Continue resumes from its restart file.
    RunProcess(const SweepPlan& plan, const SweepRun& run, const std::filesystem::path& dir,
               RunAction action);
    RunProcess(RunProcess&& other) noexcept : pid_(other.pid_) { other.pid_ = -1; }
    RunProcess& operator=(RunProcess&& other) noexcept;
    RunProcess(const RunProcess&) = delete;
    RunProcess& operator=(const RunProcess&) = delete;
    /// A child still running is sent SIGKILL and reaped: no orphan outlives its sweep's error.
    ~RunProcess();

    bool running() const { return pid_ > 0; }
    /// The child's end, once it has ended (without blocking).
    std::optional<ChildExit> poll();
    /// Passes a signal on to the child.
    void signal(int sig) const;

private:
    pid_t pid_ = -1;
};

/// Waiting for children without spinning and without lag: while it lives, SIGCHLD is blocked
/// except inside wait(), which sleeps until a child ends, a signal arrives or the timeout passes,
/// whichever comes first (ppoll with SIGCHLD unblocked). A sweep's loop then notices a run's end
/// at once, so that short runs are not padded by a polling interval.
class ChildWatch {
public:
    ChildWatch();
    ~ChildWatch();
    ChildWatch(const ChildWatch&) = delete;
    ChildWatch& operator=(const ChildWatch&) = delete;
    void wait(std::chrono::milliseconds timeout) const;

private:
    sigset_t previousMask_;
    struct sigaction previousAction_;
};

/// The path of this executable (/proc/self/exe).
std::filesystem::path selfExecutable();

/// The executable a sweep's children run: this one, unless setRunExecutable named another (the
/// Python module, which lives in a Python process, names the terrace executable of its build).
std::filesystem::path runExecutable();
void setRunExecutable(const std::filesystem::path& executable);

/// The environment variable through which a sweep hands its children its process id.
inline constexpr const char* sweepPidVariable = "TERRACE_SWEEP_PID";

/// In a child of a sweep (sweepPidVariable set): the child is sent SIGTERM when its sweep ends,
/// however it ends (kill -9 included), and stops as at a Ctrl-C, its restart file written; were
/// it left running, it would hold its directory's lock against the next sweep. posix_spawn
/// cannot ask for this (PR_SET_PDEATHSIG), so the child does, first thing in main(). A sweep
/// that ended before then is no longer the parent: the child then ends at once. The variable is
/// removed (a child's own children are not the sweep's); returns whether it was set.
bool stopWithSweep();

} // namespace terrace::cli
