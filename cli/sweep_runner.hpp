#pragma once
// `terrace sweep`: the runs of a sweep plan (cli/sweep_plan.hpp), each a `terrace run` child
// process (cli/run_process.hpp) in OUT/<run name>, handed out one at a time to whichever slot is
// free: -j local slots, and remote workers (MPI ranks, cli/sweep_mpi.hpp) when there are any.
// Runs differ in cost by orders of magnitude, so nothing is split up in advance.
//   resume     a directory that holds the complete result of the same resolved scene is not
//              run again, nor one whose failure is recorded (unless retryFailed); a run with a
//              restart file of the same scene is continued; anything else is run afresh
//   failures   a run that fails (an unstable SMD step, a refused scene, a crash) records its
//              error in its row and in OUT/<run>/FAILED.json; the sweep goes on
//   signals    SIGINT, SIGTERM or SIGHUP stop the handing out; running children get the signal
//              once and end as an interrupted run does (their output written); the table is
//              rewritten and the sweep exits 128 + the signal: the same command goes on later
//   progress   one line on stderr per run that ends: runs done of all, failures, ETA
// OUT/sweep.csv (cli/sweep_table.hpp) is rewritten whole after every run that ends.
#include "cli/run_process.hpp"
#include "cli/sweep_plan.hpp"
#include <filesystem>
#include <optional>

namespace terrace::cli {

struct SweepOptions {
    std::filesystem::path out;
    int jobs = 1; // runs at once in this process
    bool quiet = false;
    bool retryFailed = false;
    bool strict = false; // keys a run's engine does not read refuse the sweep (refuseIgnoredKeys)
};

/// Workers elsewhere (the other MPI ranks): each asks for a run, runs it and reports its end.
class RemoteWorkers {
public:
    struct Report {
        int worker = 0;
        int run = -1;   // the run that ended; -1: the worker's first request
        ChildExit exit; // how it ended
        double wallSeconds = 0.0;
        bool leaving = false; // the worker stops (it was signalled): no answer expected
    };
    virtual ~RemoteWorkers() = default;
    virtual int count() const = 0;
    /// A report that has arrived, if any (without blocking).
    virtual std::optional<Report> poll() = 0;
    /// Answers a report: the next run and how to start it, or run < 0 for "no more work".
    virtual void assign(int worker, int run, RunAction action) = 0;
};

/// Runs the sweep; returns the exit status: 0 when every run is done, 1 when some failed,
/// 128 + the signal when stopped by one.
int runSweep(const SweepPlan& plan, const SweepOptions& options, RemoteWorkers* remote = nullptr);

} // namespace terrace::cli
