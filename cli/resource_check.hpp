#pragma once
// Resources checked before a run: the memory the engine and the analysis will hold, estimated from
// the body count and the scene's settings, against what this machine can give the process now
// (MemAvailable, or the room left under the process's cgroup limit if smaller); and the bytes the
// run will write (trajectory, thermo.csv, restart files, results) against the free space of the
// output directory's file system (statvfs). A run beyond either is refused before anything is
// allocated or written, with one line naming the estimate, what is available and the key to
// change; one that would fill more than half the free space runs, with a warning.
//
// The estimates are of the largest the run will hold or write, from the structures' sizes (the
// engines' per-body records and neighbour lists at the scene's mean density, the analysis'
// accumulators), not measured: docs/PERFORMANCE.md "Resources checked before a run" compares them
// with the peak RSS and the files of real runs.
#include "core/scene.hpp"
#include <filesystem>
#include <string>

namespace terrace::cli {

/// Bytes of memory a run will hold at its peak, by holder.
struct MemoryEstimate {
    double engine = 0.0;   // the engine: bodies, lists, calendar, … and the process's own
    double analysis = 0.0; // the streaming analysis (analysisBytes)
    double total() const { return engine + analysis; }
};

/// The engine's and the analysis' memory for the scene's bodies and settings.
MemoryEstimate memoryEstimate(const Scene& scene);

/// Bytes a run will write into its output directory, by file.
struct DiskEstimate {
    double trajectory = 0.0; // trajectory.xyz (extended XYZ text, 17 significant digits) or
                             // trajectory.gsd (single precision)
    std::string trajectoryName = "trajectory.xyz";
    double thermo = 0.0;  // thermo.csv
    double restart = 0.0; // restart.bin, twice: the new one beside the old until it replaces it
    double results = 0.0; // scene.json, initial.xyz, summary.json, the correlation CSVs
    double total() const { return trajectory + thermo + restart + results; }
};

DiskEstimate diskEstimate(const Scene& scene);

/// Memory this process can take now, and what sets it.
struct MemoryRoom {
    double bytes = 0.0;                     // 0 if unknown
    std::string whose = "this machine has"; // what leaves `bytes`, as the refusal says it
};

/// MemAvailable of /proc/meminfo; less if a cgroup memory limit (v1 or v2) of the process or one
/// of its ancestors leaves less room, or the process's address-space limit (ulimit -v).
MemoryRoom availableMemory();

/// Free bytes of the file system that holds `dir` (or its nearest existing ancestor), for an
/// unprivileged process (statvfs f_bavail); negative if unknown.
double freeDiskBytes(const std::filesystem::path& dir);

/// "" when the estimate fits in the room (or the room is unknown, 0); otherwise the refusal,
/// naming the key that set the larger share, the estimate and what is available.
std::string memoryRefusal(const Scene& scene, const MemoryEstimate& need, const MemoryRoom& room);

/// A run's bytes to write against the free space.
struct DiskVerdict {
    enum class Kind { Fits, Warn, Refuse } kind = Kind::Fits;
    std::string message; // the refusal or the warning ("" when it fits)
};

/// `need` bytes still to be written into `dir`, whose file system has `freeBytes` free (negative:
/// unknown, nothing said): refused beyond the free space, warned beyond half of it.
DiskVerdict diskVerdict(const Scene& scene, const DiskEstimate& need, double written,
                        double freeBytes, const std::filesystem::path& dir);

/// Bytes with a binary unit: "512 B", "3.4 MiB", "38 GiB", "9.1 TiB".
std::string showBytes(double bytes);

/// The check before a run into `dir` (continuing: the run there, whose files already hold some of
/// what it writes): throws SceneError with the refusal, prints a warning to stderr.
void checkResources(const Scene& scene, const std::filesystem::path& dir, bool continuing);

} // namespace terrace::cli
