#include "cli/analyse_command.hpp"
#include "analysis/run_analysis.hpp"
#include "cli/body_species.hpp"
#include "cli/output_dir.hpp"
#include "cli/run_driver.hpp"
#include "core/gsd_frame.hpp"
#include "core/initial_state.hpp"
#include "core/scene.hpp"
#include "core/scene_units.hpp"
#include "core/species_rotor.hpp"
#include "core/species_sphere.hpp"
#include "core/units.hpp"
#include "core/xyz.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace terrace::cli {

namespace {

/// The run's trajectory, extended XYZ or GSD (whichever it wrote), frame by frame.
long forEachFrame(const std::filesystem::path& path, const std::function<void(Snapshot&&)>& each,
                  std::string* partial) {
    if (path.extension() == ".gsd") return forEachGsdFrame(path, each);
    return forEachTrajectoryFrame(path.string(), each, partial);
}

/// A mixture's labels for the run's frames (empty without species): the names from its scene,
/// each body's species from the first frame where the trajectory carries them, else dealt again
/// by core's own initial state from the scene (species are dealt once, from the seed, and never
/// change; the frames are in the scene's numbering).
analysis::SpeciesLabels frameSpecies(const Scene& scene, const std::vector<std::int32_t>& first,
                                     int bodies, const std::filesystem::path& path) {
    if (scene.species.empty()) return {};
    analysis::SpeciesLabels labels = speciesNames(scene);
    if (static_cast<int>(first.size()) == bodies) {
        labels.ofBody = first;
    } else {
        auto deal = [&]<class K>(const auto& potential) {
            const auto start = buildInitialState<K>(scene, potential);
            if (start.size() != bodies)
                throw TrajectoryError(
                    path.string() + ": the trajectory holds " + std::to_string(bodies) +
                    " bodies where its scene.json makes " + std::to_string(start.size()));
            for (const auto& b : start.bodies)
                labels.ofBody.push_back(b.species);
        };
        if (scene.potential.kind == "steps")
            deal.template operator()<SpeciesSphere>(stepMixture(scene));
        else if (scene.potential.kind == "rod-lj")
            deal.template operator()<SpeciesRotor>(rodMixture(scene));
        else
            deal.template operator()<SpeciesSphere>(ljMixture(scene));
    }
    labels.check(bodies);
    return labels;
}

} // namespace

int analyseRun(const std::filesystem::path& dir) {
    // The CSVs go into DIR: not while a run is writing there.
    const OutputDirectory claimed(dir, OutputMode::Continue);
    // Two passes, never holding the trajectory: the first counts the whole frames (the blocks
    // of the analysis are laid out over them), the second streams them into the accumulators.
    const bool gsd = !std::filesystem::exists(dir / "trajectory.xyz") &&
                     std::filesystem::exists(dir / "trajectory.gsd");
    const std::filesystem::path path = dir / (gsd ? "trajectory.gsd" : "trajectory.xyz");
    std::string partial;
    int bodies = 0;
    double boxLength = 0.0, firstTime = 0.0, secondTime = 0.0;
    std::vector<std::int32_t> firstSpecies;
    const long frames = forEachFrame(
        path,
        [&, k = 0L](Snapshot&& f) mutable {
            if (k == 0) bodies = f.size(), boxLength = f.boxLength, firstTime = f.time;
            if (k == 0) firstSpecies = std::move(f.species);
            if (k == 1) secondTime = f.time;
            ++k;
        },
        &partial);
    if (!partial.empty()) std::fprintf(stderr, "terrace: warning: %s\n", partial.c_str());
    if (frames < 4)
        throw TrajectoryError(path.string() + ": " + std::to_string(frames) +
                              " whole frames, too few to correlate (at least 4)");
    // The run's own analysis settings where its scene.json is there, else the defaults.
    analysis::StreamingOptions options;
    options.rdfMaxAngstrom = 0.0; // without a scene: out to L/2
    UnitSystem csvUnits;          // the run's units, so that its CSVs keep their columns
    analysis::SpeciesLabels species;
    if (std::filesystem::exists(dir / "scene.json")) {
        const Scene scene = loadScene((dir / "scene.json").string());
        options = streamingOptions(scene);
        species = frameSpecies(scene, firstSpecies, bodies, path);
        csvUnits = unitSystem(scene);
        // g(r) frames as far apart in time as in the run (trajectory frames are sparser).
        const double frameFs = units::toFs(secondTime - firstTime);
        options.rdfEvery =
            std::max(1, static_cast<int>(
                            std::lround(scene.analysis.rdf_every * scene.run.sample_fs / frameFs)));
    }
    analysis::RunAnalysis accumulated(bodies, boxLength, units::toPs(secondTime - firstTime),
                                      frames, options, species);
    long fed = 0;
    std::string cutShort; // the same frame as in the first pass, already reported
    forEachFrame(
        path,
        [&](Snapshot&& f) {
            if (fed++ < frames) accumulated.add(f);
        },
        &cutShort);
    const auto summary = accumulated.write(dir, csvUnits);
    std::printf("%ld frames analysed; wrote the correlation CSVs in %s/\n", frames, dir.c_str());
    std::printf("%s\n", summary.dump().c_str());
    return 0;
}

} // namespace terrace::cli
