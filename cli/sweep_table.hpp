#pragma once
// What a sweep knows of each of its runs, and sweep.csv: one row per run in sweep order (not the
// order in which runs finished, so that the table does not depend on how the runs were spread
// over processes), with the run's overrides and its summary's numbers. The table is rewritten
// whole (core/output_file.hpp) after every run that ends, so a sweep stopped at any moment leaves
// a valid table of what it had.
#include "cli/run_process.hpp"
#include "cli/sweep_plan.hpp"
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace terrace::cli {

enum class RunStatus { Pending, Ok, Failed, Interrupted };

struct SweepEntry {
    RunStatus status = RunStatus::Pending;
    std::string message;       // why a run failed or stopped
    nlohmann::json summary;    // the run's summary.json (null if none)
    double wallSeconds = -1.0; // as the sweep timed it; < 0: not run this time
    bool reused = false;       // found complete (or failed) from before
};

/// A summary of a run that ended as asked: not interrupted, no error, its analysis done.
bool completeSummary(const nlohmann::json& summary);

/// The file recording a failed run (its scene and the error): a failure is a result, and the
/// same run is not tried again unless asked.
inline constexpr const char* failedFileName = "FAILED.json";

/// What the sweep makes of a directory before running: Skip (with `found` filled) when it holds
/// the complete result of the same resolved scene, or its recorded failure (unless
/// retryFailed); Continue when it holds a restart file of the same scene; otherwise Fresh.
RunAction resumeAction(const std::filesystem::path& dir, const SweepRun& run, bool retryFailed,
                       SweepEntry& found);

/// The entry of a run whose process ended with `exit`, from what it left in dir; a failure is
/// recorded in dir/FAILED.json.
SweepEntry finishedEntry(const std::filesystem::path& dir, const SweepRun& run,
                         const ChildExit& exit);

/// The text of sweep.csv.
std::string sweepTable(const SweepPlan& plan, const std::vector<SweepEntry>& entries);

const char* statusName(RunStatus s);

} // namespace terrace::cli
