#pragma once
// Where a production sample goes: its energies into the run's record and thermo.csv, the bodies
// into trajectory.xyz or trajectory.gsd (at its interval), and the analysis. A restart point keeps
// the analysis' state and the sample statistics, never the samples (cli/restart.hpp). Nothing takes
// a sample whole: at 10⁶ bodies a frame's text alone is ~0.3 GB, and beside the engine it would
// raise the run's peak, so every file is written piece by piece from the engine.
#include "cli/run_record.hpp"
#include "core/engine.hpp"
#include "core/units.hpp"
#include "core/xyz.hpp"
#include <numeric>
#include <span>
#include <vector>

namespace terrace::cli {

/// The engine's bodies begin … end−1 as a snapshot, taken when a piece of a frame is written.
template <class E> auto bodiesOf(const E& engine) {
    return [&engine, bodies = std::vector<int>()](int begin, int end) mutable {
        bodies.resize(static_cast<std::size_t>(end - begin));
        std::iota(bodies.begin(), bodies.end(), begin);
        return engine.snapshot(std::span<const int>(bodies));
    };
}

/// The engine's bodies as one trajectory frame, handed to `sink` piece by piece.
template <class E>
void writeFrame(const E& engine, int n, TrajectoryLayout layout, const PieceSink& sink) {
    const Snapshot none = engine.snapshot(std::span<const int>()); // its time and box
    writeXyzFramePieces(n, none.time, none.boxLength, layout, bodiesOf(engine), sink);
}

class SampleSink {
public:
    SampleSink(const RunPlan& plan, int rotationalDof, RunRecord& run, RunFiles& files)
        : plan_(plan),
          layout_(layoutFor(rotationalDof)), thermoLayout_{run.virialKind,  run.volume,
                                                           run.dof,         run.bodies,
                                                           run.outputUnits, run.heatBath},
          run_(run), files_(files) {}

    /// Production begins: its files are opened empty in `dir` (thermo.csv with its header).
    void openProduction(const std::filesystem::path& dir) {
        if (plan_.trajectoryEvery > 0 && plan_.trajectoryGsd)
            files_.gsd.emplace(dir / "trajectory.gsd", "terrace", "hoomd", 1, 4, hoomdChunkNames());
        else if (plan_.trajectoryEvery > 0)
            files_.trajectory = AppendFile(dir / "trajectory.xyz", 0);
        if (plan_.thermoEvery > 0) {
            files_.thermo = AppendFile(dir / "thermo.csv", 0);
            files_.thermo.append(thermoHeader(thermoLayout_));
        }
    }

    /// Production sample `sample` of the engine as it is now; `collisions` since production
    /// began.
    template <Engine E> void record(const E& engine, long sample, double collisions) {
        const double u = engine.potentialEnergy(), kin = engine.kineticEnergy();
        // The time on the plan's grid, from the sample's index: exact up to one rounding, where
        // the engine's clock less production's start carries the round-off of every interval.
        SampleRecord e{units::toPs(double(sample) * plan_.sampleInterval), u + kin, u, kin};
        e.kineticTranslational = engine.translationalKineticEnergy();
        e.virial = engine.virial();
        e.collisions = collisions;
        e.time = engine.time();
        e.bath = engine.thermostatEnergy();
        const int n = run_.bodies;
        // The configurational estimators on g(r) frames, where the analysis reads every body
        // anyway (an O(N) pass: every sample would cost DMD a force evaluation per sample).
        const bool frame = run_.analysis && run_.analysis->wantsPositions();
        const bool rowDue = plan_.thermoEvery > 0 && sample % plan_.thermoEvery == 0;
        double continuousU = e.potential;
        if (frame || rowDue) {
            const ContinuousSums c =
                engine.continuousSums(frame ? run_.analysis->terracing() : nullptr);
            if (frame) e.continuousPotential = c.potential, e.continuousVirial = c.virial;
            continuousU = c.potential;
        }
        if (rowDue) {
            const SampleRecord* before = sample > 0 ? &run_.thermoRow : nullptr;
            files_.thermo.append(thermoRow(e, before, continuousU, thermoLayout_));
            run_.thermoRow = e;
        }
        if (plan_.trajectoryEvery > 0 && sample % plan_.trajectoryEvery == 0) {
            if (files_.gsd) {
                const Snapshot none = engine.snapshot(std::span<const int>()); // time and box
                writeHoomdFrame(*files_.gsd, n, none.time, none.boxLength, bodiesOf(engine),
                                plan_.gsdType, std::uint64_t(sample));
            } else {
                files_.trajectory.appendPieces(
                    [&](const PieceSink& sink) { writeFrame(engine, n, layout_, sink); });
            }
        }
        run_.addParts(e, engine);
    }

private:
    const RunPlan& plan_;
    TrajectoryLayout layout_;
    ThermoLayout thermoLayout_;
    RunRecord& run_;
    RunFiles& files_;
};

} // namespace terrace::cli
