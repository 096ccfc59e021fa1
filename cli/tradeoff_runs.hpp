#pragma once
// The runs of a `terrace tradeoff` search on disk: every replica a run of the sweep machinery
// under OUT/runs (so -j, mpirun and resume work, and a finished run is never made again), read
// back into the search's state (cli/tradeoff_state.hpp).
#include "cli/tradeoff_state.hpp"
#include <string>
#include <vector>

namespace terrace::cli {

/// One run of a setting: its seed and its directory under OUT/runs.
struct CaseRun {
    const Setting* setting;
    long seed;
    std::string label;
};

/// What a run is for. A bias run takes a g(r) frame, with DMD's configurational U and P, at
/// every sample; a cost window's run keeps the scene's frames, so that its CPU is the scene's.
enum class RunPurpose { Bias, Cost };

/// The runs as one sweep (each not yet complete on disk is run), `jobs` at once, in order, with
/// --set and `extraSet` for every run; returns the sweep's status.
int runCases(const Tradeoff& t, const std::vector<CaseRun>& runs, const std::string& extraSet,
             int jobs, RunPurpose purpose);

/// Runs every replica asked for of `rungs` and not yet on disk, at the bias runs' N; returns the
/// sweep's status.
int runPending(const Tradeoff& t, const std::vector<const Rung*>& rungs);

/// Reads every replica asked for of the reference and of each rung, the CPU they spent
/// (t.cpuSpent) and the heights of g(r)'s peak, on one window placed on all of them.
void readRound(Tradeoff& t);

} // namespace terrace::cli
