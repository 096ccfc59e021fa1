#pragma once
// `mpirun -np K terrace sweep ...`: rank 0 hands out the runs (cli/sweep_runner.hpp) and runs
// -j of them itself; every other rank asks for a run, runs it as a child process and reports its
// end, until rank 0 has no more. A rank never waits in a spinning MPI call while a run goes on
// (probes and tests with short sleeps), so the ranks' CPU goes to the runs. The output directory
// must be one that every rank sees (a shared file system on a cluster).
#include "cli/sweep_runner.hpp"
#include <string>
#include <vector>

namespace terrace::cli {

/// Whether an MPI launcher (mpirun, srun) started this process as one of several.
bool launchedByMpi();

/// Whether this terrace was built with MPI.
bool haveMpi();

/// The sweep across the MPI job's ranks; every rank calls it. Rank 0 reads and checks the sweep
/// (errors printed once, by rank 0); returns the exit status (rank 0's, the others 0).
int mpiSweep(const std::filesystem::path& sweepFile, const std::vector<std::string>& extraSets,
             const SweepOptions& options);

} // namespace terrace::cli
