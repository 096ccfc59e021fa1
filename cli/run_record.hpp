#pragma once
// What a run keeps as it goes, apart from the engine: the plan of its time grid, its position on
// that grid, the files it grows, and the statistics of its samples that become summary.json.
#include "analysis/run_analysis.hpp"
#include "cli/cpu_clock.hpp"
#include "cli/interrupt.hpp"
#include "cli/restart.hpp"
#include "cli/sample_statistics.hpp"
#include "cli/thermo.hpp"
#include "core/gsd_frame.hpp"
#include "core/heat_bath.hpp"
#include "core/output_file.hpp"
#include "core/pressure.hpp"
#include "core/scene.hpp"
#include "core/snapshot.hpp"
#include "core/vec.hpp"
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace terrace::cli {

struct RunPlan {
    double sampleInterval = 0.0;     // time units
    double thermostatInterval = 0.0; // time units
    long equilibrationTicks = 0;     // thermostat intervals, the last one partial when
                                     // run.equilibrate_ps is not a whole number of them
    long productionSamples = 0;      // samples after the one at the start of production
    double equilibrationEnd = 0.0;   // run.equilibrate_ps, time units
    double productionLength = 0.0;   // run.time_ps, time units (≥ productionSamples intervals)
    bool partialTick = false;        // the last thermostat interval is cut short
    bool unsampledTail = false;      // production goes on past its last sample
    long trajectoryEvery = 0;        // in samples; 0 = none
    bool trajectoryGsd = false;      // trajectory.gsd (output.trajectory_format gsd), else .xyz
    GsdBodyType gsdType;             // what a GSD trajectory records of the bodies
    long thermoEvery = 0;            // in samples; 0 = none
    long restartEvery = 0;           // in samples; 0 = none
    long restartEveryTicks = 0;      // in thermostat intervals, during equilibration

    /// The time of production sample s. When the thermostat and sample intervals agree this is
    /// (ticks + s)·Δt, one grid from t = 0, as runs have always been sampled.
    double productionTime(long s, double tStart) const;
    /// The end of equilibration's thermostat interval k (1 … equilibrationTicks): k intervals,
    /// or run.equilibrate_ps for a last one cut short.
    double tickTime(long k) const;
    /// Production's end: its last sample, or run.time_ps past its start when that lies beyond.
    double productionEnd(double tStart) const;
};

/// The scene's intervals on the engine's grid (the scene validation has checked that they are
/// whole multiples: SMD moves in whole steps, outputs come at whole samples).
RunPlan planRun(const Scene& scene);

/// The analysis settings of a scene (analysis.rdf_max is in σ there, in Å here).
analysis::StreamingOptions streamingOptions(const Scene& scene);

/// Bytes the run's analysis will hold in memory at most (the sample statistics, a few hundred
/// bytes, aside).
double analysisBytes(const Scene& scene);

/// Where the run stands on its grid: the phase, thermostat ticks and samples done, production's
/// start and the CPU seconds of each phase before the current engine's stretch.
struct RunPosition {
    bool inProduction = false;
    long tick = 0, sample = 0;
    double tStart = 0.0, cpuEquilibration = 0.0, cpuProduction = 0.0;
};

/// The files production grows sample by sample (closed where the scene writes none).
struct RunFiles {
    AppendFile trajectory, thermo;
    std::optional<GsdWriter> gsd; // the trajectory, when it is GSD
    /// Each open file reaches the disk: before a restart file that counts their bytes.
    void sync();
    /// Their lengths and the checksums of their tails (tailChecksum), as a restart file records
    /// them: called after sync().
    nlohmann::json sizes() const;
};

nlohmann::json vec3Json(const Vec3& v);

/// Adds one stretch of an engine's life (statistics at its start and end) to the production's
/// statistics: counters (events.*, steps, ...) add their increase over the stretch, everything
/// else takes its value at the end. Production is one stretch unless restart points rebuilt the
/// engine.
void accumulateStatistics(nlohmann::json& production, const nlohmann::json& start,
                          const nlohmann::json& end);

/// Collisions (DMD's events up + down + reflect) in engine statistics; 0 for SMD's.
double collisionCount(const nlohmann::json& statistics);

/// Merges the production's engine statistics into the summary and adds collisions_per_ps and
/// collisions_per_cpu_second (DMD: up + down + reflect), all_events_per_ps and
/// all_events_per_cpu_second (DMD: every event, the bookkeeping ones too) and steps_per_ps (SMD)
/// where those counters exist.
void addEngineStatistics(nlohmann::json& summary, const nlohmann::json& production,
                         double simulatedPs);

/// What a run gathered, handed from the engine loop to the summary.
struct RunRecord {
    SampleStatistics samples; // of the production samples' energies, K_trans, virial, …
    SampleRecord thermoRow;   // the sample of thermo.csv's last row: the next is taken since it
    std::unique_ptr<analysis::RunAnalysis> analysis; // null with fewer than 4 samples planned
    CpuClock analysisClock;                          // CPU time of the analysis
    // The process's CPU when this stretch of the run was asked for, before its engine was built
    // (RunTarget), and what earlier stretches of a continued run spent (restart.bin): the run's
    // own CPU, whatever else the process ran before it (the Python module runs scenes in its
    // interpreter's process).
    double processCpuAtStart = CpuClock::now(), processCpuEarlier = 0.0;
    Vec3 momentumInitial = Vec3::Zero(), momentumFinal = Vec3::Zero(); // internal units
    nlohmann::json production = nlohmann::json::object(); // engine statistics over production
    double simulatedPs = 0.0, cpuSeconds = 0.0, cpuEquilibration = 0.0;
    double sampleInterval = 0.0, kT = 0.0;
    double volume = 0.0;                               // Å³
    VirialKind virialKind = VirialKind::Instantaneous; // what SampleRecord::virial holds
    int bodies = 0, dof = 0;   // dof: of the kinetic energy, as the heat bath keeps momentum or not
    bool heatBath = false;     // run.heat_bath is set: the engine thermostats the whole run
    std::string interruptedBy; // the signal that stopped the run ("" if none)
    std::string interruptedIn; // equilibration | production | analysis
    std::string failure;       // the first error that ended the run ("" if none)
    long restartsWritten = 0;  // restart files written over the whole run
    std::size_t hugePageBytes = 0;     // most of the process seen in huge pages at an engine's end
    int continuations = 0;             // times the run was continued from a restart file
    std::uint64_t sceneChecksum = 0;   // CRC-64 of DIR/scene.json as the run wrote it
    double restartEveryPs = 0.0;       // 0: no restart files
    std::vector<std::string> warnings; // from the scene (sceneWarnings)
    std::string meltWarning;           // a lattice start not melted by equilibration's end
    UnitSystem outputUnits;            // of thermo.csv, the CSVs and summary.json's "reduced"

    /// A record for a run of `bodies` bodies in a box of side boxLength (Å) under `plan`, with
    /// the analysis the scene asks for (none with fewer than 4 samples planned); `species`: a
    /// mixture's labels (cli/body_species.hpp), empty for one kind of body.
    RunRecord(const Scene& scene, const RunPlan& plan, int bodies, double boxLength,
              int rotationalDof, VirialKind virialKind,
              const analysis::SpeciesLabels& species = {});
    RunRecord() = default;

    /// CPU seconds the run has spent so far: its engine, samples, g(r) frames with their
    /// configurational sums, analysis and files.
    double processCpu() const { return processCpuEarlier + CpuClock::now() - processCpuAtStart; }

    void add(const SampleRecord& e, const Snapshot& s) {
        samples.add(e);
        if (!analysis) return;
        analysisClock.start();
        analysis->add(s);
        analysisClock.stop();
    }
    /// A sample taken from the engine: the analysis gets only what it reads (the followed
    /// bodies, and on a g(r) frame every position, read from the engine body by body), so that
    /// no large system's sample, nor its positions, is held beside the engine (~0.1 GB of
    /// sample, 24 MB of positions, at 10⁶ rods).
    template <class E> void addParts(const SampleRecord& e, const E& engine) {
        samples.add(e);
        if (!analysis) return;
        const Snapshot followed = engine.snapshot(analysis->followedBodies());
        analysisClock.start();
        if (analysis->wantsPositions())
            analysis->add(followed, [&engine](int b) { return engine.position(b); });
        else
            analysis->add(followed, nullptr);
        analysisClock.stop();
    }
};

/// The rotational degrees of freedom of a run's n bodies together: `rotationalDof` each (the
/// kind's), but none for a body of a sphere species among rods (Scene::species kind sphere,
/// core/species_rotor.hpp); `species`: the bodies' labels, empty for one kind of body.
int rotationalDofs(const Scene& scene, int rotationalDof, const analysis::SpeciesLabels& species,
                   int n);

/// Writes summary.json, then the correlation analysis (cancelled by a signal that arrives
/// during it: more than `tolerated` signals in all), then summary.json again with the analysis'
/// results.
/// `analysed`: whether the analysis ran to its end (or was not due: fewer than 4 samples).
nlohmann::json writeSummaryAndAnalysis(const Scene& scene, RunRecord& run,
                                       const std::filesystem::path& dir,
                                       const InterruptGuard& interrupt, int tolerated,
                                       bool& analysed);

/// The run's position and accumulators from a restart file: the phase, the sample statistics and
/// the analysis' state (after checking that the growing files still hold what the file says they
/// did), and what the file carries over. Fills `run` and opens `files` where they were. Nothing
/// is replayed: its cost does not grow with the samples taken.
RunPosition resumeRun(const nlohmann::json& restart, const RunPlan& plan,
                      const std::filesystem::path& dir, RunRecord& run, RunFiles& files);

} // namespace terrace::cli
