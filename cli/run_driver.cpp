#include "cli/run_driver.hpp"
#include "analysis/cancellation.hpp"
#include "analysis/windowed_correlation.hpp"
#include "cli/heat_bath_summary.hpp"
#include "cli/reduced_summary.hpp"
#include "cli/thermo.hpp"
#include "core/scene_units.hpp"
#include "core/whole_intervals.hpp"
#include "smd/parameters.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace terrace::cli {

RunPlan planRun(const Scene& scene) {
    RunPlan plan;
    // On SMD's grid an interval is a whole number of steps (the scene validation refuses any
    // other); rounding the ratio only removes its binary round-off.
    auto onGrid = [&](double fs) {
        const double interval = units::fromFs(fs);
        if (scene.engine != "smd") return interval;
        const double dt = units::fromFs(smd::readSmdSection(scene.smd).dt_fs);
        return std::max(1.0, std::round(interval / dt)) * dt;
    };
    plan.sampleInterval = onGrid(scene.run.sample_fs);
    plan.thermostatInterval = onGrid(scene.run.thermostat_fs);
    // Run lengths are honoured as typed. Equilibration ends on a rescale at run.equilibrate_ps,
    // its last thermostat interval cut short where the length is not a whole number of them;
    // production is sampled at whole sample intervals and runs on, unsampled, to run.time_ps
    // (the analysis needs equally spaced samples). A length within limits::gridTolerance of a
    // whole number of intervals is that whole number: only its binary round-off differs.
    // Under SMD both lengths are whole numbers of steps (smd/parameters.hpp).
    const auto lengthOnGrid = [&](double ps) {
        const double t = units::fromPs(ps);
        if (scene.engine != "smd") return t;
        const double dt = units::fromFs(smd::readSmdSection(scene.smd).dt_fs);
        return std::round(t / dt) * dt;
    };
    plan.equilibrationEnd = lengthOnGrid(scene.run.equilibrate_ps);
    plan.productionLength = lengthOnGrid(scene.run.time_ps);
    const double ticks = plan.equilibrationEnd / plan.thermostatInterval;
    plan.partialTick = plan.equilibrationEnd > 0.0 && !isWholeRatio(ticks);
    plan.equilibrationTicks = wholeIntervals(ticks) + (plan.partialTick ? 1 : 0);
    const double samples = plan.productionLength / plan.sampleInterval;
    plan.unsampledTail = !isWholeRatio(samples);
    plan.productionSamples = wholeIntervals(samples);
    auto inSamples = [&](double interval) {
        return interval > 0.0 ? std::max(1L, long(std::llround(interval / plan.sampleInterval)))
                              : 0L;
    };
    plan.trajectoryEvery = inSamples(units::fromFs(scene.output.trajectory_every_fs));
    plan.trajectoryGsd = scene.output.trajectory_format == "gsd";
    if (plan.trajectoryGsd) plan.gsdType = gsdBodyType(scene);
    plan.thermoEvery = inSamples(units::fromFs(scene.output.thermo_every_fs));
    plan.restartEvery = inSamples(units::fromPs(scene.output.restart_every_ps));
    if (plan.restartEvery > 0)
        plan.restartEveryTicks =
            std::max(1L, long(std::llround(units::fromPs(scene.output.restart_every_ps) /
                                           plan.thermostatInterval)));
    return plan;
}

double RunPlan::productionTime(long s, double tStart) const {
    if (thermostatInterval == sampleInterval && !partialTick)
        return double(equilibrationTicks + s) * sampleInterval;
    return tStart + double(s) * sampleInterval;
}

double RunPlan::tickTime(long k) const {
    return partialTick && k == equilibrationTicks ? equilibrationEnd
                                                  : double(k) * thermostatInterval;
}

double RunPlan::productionEnd(double tStart) const {
    return unsampledTail ? tStart + productionLength : productionTime(productionSamples, tStart);
}

analysis::StreamingOptions streamingOptions(const Scene& scene) {
    analysis::StreamingOptions o;
    const auto& a = scene.analysis;
    o.blocks = a.blocks;
    o.maxLagPs = a.max_lag_ps;
    o.rdfBinAngstrom = a.rdf_bin_angstrom;
    o.rdfMaxAngstrom = a.rdf_max * scene.potential.sigma; // 0 stays 0: L/2
    o.rdfEvery = a.rdf_every;
    o.followBodies = a.follow_bodies;
    o.lagsPerLevel = a.lags_per_level;
    o.beta = scene.kT() > 0.0 ? 1.0 / scene.kT() : 0.0;
    return o;
}

double analysisBytes(const Scene& scene) {
    const RunPlan plan = planRun(scene);
    const double n = scene.state.particles.empty() ? double(scene.state.n)
                                                   : double(scene.state.particles.size());
    const double samples = double(plan.productionSamples) + 1.0;
    const auto& a = scene.analysis;
    const double followed = a.follow_bodies > 0 ? std::min(n, double(a.follow_bodies)) : n;
    // Multiple-tau levels up to the longest lag (at most half the run): 9 doubles per followed
    // body per slot, p slots per level beyond the first; the first's FFT windows and kept
    // transforms (WindowedCorrelation); g(r): three coordinates and a cell index per body.
    const double p = a.lags_per_level;
    const double lag =
        a.max_lag_ps > 0.0 ? units::fromPs(a.max_lag_ps) / plan.sampleInterval : 0.5 * samples;
    const double levels = 1.0 + std::max(0.0, std::ceil(std::log2(std::max(1.0, lag / (p - 1)))));
    const double perFollowed = (levels - 1.0) * p * 9.0 * sizeof(double) +
                               double(analysis::WindowedCorrelation::bytesPerBody(int(p)));
    // A mixture follows its bodies twice (the total's curves and their species'), and keeps
    // each body's species twice for g(r) (given and sorted by cell).
    const double times = scene.species.empty() ? 1.0 : 2.0;
    const double labels = scene.species.empty() ? 0.0 : 2.0 * sizeof(std::int32_t);
    return times * followed * perFollowed + n * (3.0 * sizeof(double) + 2.0 * sizeof(int) + labels);
}

int rotationalDofs(const Scene& scene, int rotationalDof, const analysis::SpeciesLabels& species,
                   int n) {
    if (species.ofBody.empty()) return rotationalDof * n;
    int total = 0;
    for (const std::int32_t a : species.ofBody)
        total += scene.species[a].kind == "sphere" ? 0 : rotationalDof;
    return total;
}

RunRecord::RunRecord(const Scene& scene, const RunPlan& plan, int n, double boxLength,
                     int rotationalDof, VirialKind virial, const analysis::SpeciesLabels& species)
    : sampleInterval(plan.sampleInterval), kT(scene.kT()), volume(std::pow(boxLength, 3)),
      virialKind(virial), bodies(n),
      dof(heatBathDof(heatBathOf(scene).kind, rotationalDofs(scene, rotationalDof, species, n), n)),
      heatBath(heatBathOf(scene).on()), restartEveryPs(scene.output.restart_every_ps),
      warnings(sceneWarnings(scene)), outputUnits(unitSystem(scene)) {
    const long planned = plan.productionSamples + 1;
    if (planned >= 4)
        analysis = std::make_unique<analysis::RunAnalysis>(
            bodies, boxLength, units::toPs(plan.sampleInterval), planned, streamingOptions(scene),
            species);
    // The configurational estimators come on the analysis' g(r) frames.
    const long every = scene.analysis.rdf_every;
    samples = SampleStatistics(SamplePlan{planned, analysis ? (planned + every - 1) / every : 0,
                                          virialKind, volume, dof, kT, heatBath});
}

namespace {

/// A checksum (CRC-64) of the chunks of frame frames−1 of a GSD trajectory, which later frames
/// leave as they are: a restart point records it, so that a continued run knows the file is its
/// own. IoError or TrajectoryError when the file does not hold that frame.
std::uint64_t gsdLastFrameChecksum(const std::filesystem::path& path, std::uint64_t frames) {
    const GsdContents c = readGsdContents(path);
    std::uint64_t crc = 0;
    bool any = false;
    for (const auto& e : c.index)
        if (e.frame + 1 == frames) crc = crc64(readGsdChunk(path, e), crc), any = true;
    if (!any)
        throw IoError(path.string() + " holds no frame " + std::to_string(frames - 1) +
                      ": it was changed after restart.bin was written");
    return crc;
}

} // namespace

void RunFiles::sync() {
    for (AppendFile* f : {&trajectory, &thermo})
        if (f->isOpen()) f->sync();
    if (gsd) gsd->flush();
}

nlohmann::json RunFiles::sizes() const {
    nlohmann::json out;
    for (const auto& [name, f] :
         {std::pair<std::string, const AppendFile*>{"trajectory", &trajectory},
          {"thermo", &thermo}}) {
        const std::int64_t size = f->isOpen() ? f->size() : 0;
        out[name + "_bytes"] = size;
        out[name + "_tail_crc64"] = size > 0 ? tailChecksum(f->path(), size) : std::uint64_t(0);
    }
    // A GSD file is not cut at a length (its index is rewritten in place): its frames count,
    // and the checksum of its last frame's chunks says the file is this run's.
    if (gsd) {
        out["trajectory_gsd_frames"] = gsd->frames();
        out["trajectory_gsd_tail_crc64"] = gsdLastFrameChecksum(gsd->path(), gsd->frames());
    }
    return out;
}

nlohmann::json vec3Json(const Vec3& v) {
    return nlohmann::json::array({v.x(), v.y(), v.z()});
}

namespace {

/// Statistics that count things since the engine was built; the run reports their increase
/// over production. Everything else (sizes, settings, maxima) is reported as it stands at the end.
bool isCounter(const std::string& path) {
    static const std::set<std::string> counters = {
        "steps",        "neighbour_rebuilds", "pair_evaluations",   "cleanups",
        "stale_events", "stale_in_agendas",   "search_evaluations", "searches_screened",
        "resorts"};
    return path.rfind("events.", 0) == 0 || counters.count(path) > 0;
}

/// Statistics that are maxima over the engine's life: the largest of the stretches'.
bool isMaximum(const std::string& path) {
    return path.rfind("max_", 0) == 0;
}

/// Time spent per phase since the engine was built (SMD's phase_seconds): added up.
bool isDuration(const std::string& path) {
    return path.rfind("phase_seconds.", 0) == 0;
}

void addStretch(nlohmann::json& acc, const nlohmann::json& before, const nlohmann::json& after,
                const std::string& path) {
    if (after.is_object()) {
        if (!acc.is_object()) acc = nlohmann::json::object();
        static const nlohmann::json none;
        for (const auto& [key, value] : after.items()) {
            const std::string sub = path.empty() ? key : path + "." + key;
            addStretch(acc[key], before.is_object() && before.contains(key) ? before[key] : none,
                       value, sub);
        }
        return;
    }
    if (isCounter(path) && after.is_number_integer() && before.is_number_integer()) {
        const long long increase = after.get<long long>() - before.get<long long>();
        acc = (acc.is_number_integer() ? acc.get<long long>() : 0LL) + increase;
    } else if (isDuration(path) && after.is_number() && before.is_number()) {
        acc = (acc.is_number() ? acc.get<double>() : 0.0) + after.get<double>() -
              before.get<double>();
    } else if (isMaximum(path) && after.is_number() && acc.is_number()) {
        if (after.get<double>() > acc.get<double>()) acc = after;
    } else {
        acc = after;
    }
}

} // namespace

void accumulateStatistics(nlohmann::json& production, const nlohmann::json& start,
                          const nlohmann::json& end) {
    addStretch(production, start, end, "");
}

double collisionCount(const nlohmann::json& statistics) {
    if (!statistics.is_object() || !statistics.contains("events")) return 0.0;
    const auto& ev = statistics["events"];
    return ev.value("up", 0.0) + ev.value("down", 0.0) + ev.value("reflect", 0.0);
}

void addEngineStatistics(nlohmann::json& summary, const nlohmann::json& production,
                         double simulatedPs) {
    for (const auto& [key, value] : production.items())
        summary[key] = value;
    if (simulatedPs <= 0.0) return;
    // Collisions (up, down, reflect) are the dynamics; the other events (virtual, cell, relist,
    // sample, thermostat) are the engine's bookkeeping, about as many again: the rates of all
    // events say so in their names, so that neither is read for the other.
    if (production.contains("events")) {
        const double collisions = collisionCount(production);
        const double all = production["events"].value("total", 0.0);
        summary["collisions_per_ps"] = collisions / simulatedPs;
        summary["all_events_per_ps"] = all / simulatedPs;
        const double cpu = summary.value("cpu_seconds", 0.0);
        if (cpu > 0.0) {
            summary["collisions_per_cpu_second"] = collisions / cpu;
            summary["all_events_per_cpu_second"] = all / cpu;
        }
    }
    if (production.contains("steps"))
        summary["steps_per_ps"] = production["steps"].get<double>() / simulatedPs;
}

namespace {

nlohmann::json summaryOf(const Scene& scene, const RunRecord& run) {
    nlohmann::json summary;
    summary["engine"] = scene.engine;
    summary["scene"] = scene.name;
    summary["n_bodies"] = run.bodies;
    summary["interrupted"] = !run.interruptedBy.empty();
    if (!run.interruptedBy.empty()) {
        summary["interrupted_by"] = run.interruptedBy;
        summary["interrupted_in"] = run.interruptedIn;
    }
    if (!run.failure.empty()) summary["error"] = run.failure;
    summary["simulated_ps"] = run.simulatedPs;
    summary["sample_fs"] = units::toFs(run.sampleInterval);
    summary["samples"] = run.samples.count();
    summary["cpu_seconds"] = run.cpuSeconds;
    summary["cpu_seconds_equilibration"] = run.cpuEquilibration;
    summary["cpu_seconds_per_ps"] = run.simulatedPs > 0 ? run.cpuSeconds / run.simulatedPs : 0.0;
    summary["temperature_target_K"] = units::kelvin(run.kT);
    summary["warnings"] = run.warnings;
    if (!run.meltWarning.empty()) summary["warnings"].push_back(run.meltWarning);
    if (run.restartEveryPs > 0.0)
        summary["restarts"] = {{"every_ps", run.restartEveryPs},
                               {"written", run.restartsWritten},
                               {"continued", run.continuations}};
    // Of the whole process, at the end of the engine that held most (core/huge_pages.hpp).
    summary["memory_in_huge_pages_bytes"] = run.hugePageBytes;
    run.samples.summarise(summary, scene.potential.sigma, scene.potential.epsilon);
    if (run.heatBath) summary["heat_bath"] = heatBathSummary(scene, run.samples, run.dof);
    summary["momentum"] = {{"initial", vec3Json(run.momentumInitial / units::psPerTimeUnit)},
                           {"final", vec3Json(run.momentumFinal / units::psPerTimeUnit)},
                           {"units", "g/mol A/ps"}};
    addEngineStatistics(summary, run.production, run.simulatedPs);
    // The collision rate's block error, from the collisions between samples (DMD only).
    if (summary.contains("collisions_per_ps") && run.samples.count() >= 3)
        summary["collisions_per_ps_err"] =
            run.samples.collisionRateError(units::toPs(run.sampleInterval));
    return summary;
}

} // namespace

nlohmann::json writeSummaryAndAnalysis(const Scene& scene, RunRecord& run,
                                       const std::filesystem::path& dir,
                                       const InterruptGuard& interrupt, int tolerated,
                                       bool& analysed) {
    nlohmann::json summary = summaryOf(scene, run);
    summary["provenance"] = provenance(scene);
    // Under lj the results in reduced units beside the real ones (cli/reduced_summary.hpp);
    // under real the summary is as it always was.
    const auto addReduced = [&] {
        if (run.outputUnits.reduced())
            summary["reduced"] = reducedSummary(summary, run.outputUnits);
    };
    if (run.outputUnits.reduced()) summary["units"] = run.outputUnits.name();
    addReduced();
    analysed = !run.analysis || run.analysis->samples() < 4; // too few: nothing is due
    // Written before the analysis, so that a run killed during a long analysis keeps it.
    if (!analysed) summary["analysis"] = "not finished: the process ended during the analysis";
    summary["process_cpu_seconds"] = run.processCpu(); // everything the run spent
    writeFileAtomically(dir / "summary.json", summary.dump(2) + "\n");
    if (analysed) return summary;
    try {
        // A signal beyond those that stopped the run cancels the analysis.
        const analysis::ScopedCancellation hook([&] { return interrupt.count() > tolerated; });
        run.analysisClock.start();
        summary["analysis"] = run.analysis->write(dir, run.outputUnits);
        run.analysisClock.stop();
        summary["analysis_cpu_seconds"] = run.analysisClock.seconds();
        analysed = true;
    } catch (const analysis::Cancelled&) {
        summary["analysis"] = {{"error", "cancelled by a signal before it finished"}};
        if (run.interruptedBy.empty()) {
            run.interruptedBy = interrupt.signalName();
            run.interruptedIn = "analysis";
            summary["interrupted"] = true;
            summary["interrupted_by"] = run.interruptedBy;
            summary["interrupted_in"] = run.interruptedIn;
        }
    } catch (const IoError& e) {
        // A failed write is an error of the run: recorded in the summary if it can still be.
        summary["analysis"] = {{"error", e.what()}};
        summary["error"] = e.what();
        try {
            writeFileAtomically(dir / "summary.json", summary.dump(2) + "\n");
        } catch (const IoError&) {
        }
        throw;
    } catch (const std::exception& e) { // the run's own numbers stay worth keeping
        summary["analysis"] = {{"error", e.what()}};
        std::fprintf(stderr, "terrace: warning: analysis failed: %s\n", e.what());
    }
    addReduced();                                      // now with the analysis' diffusion
    summary["process_cpu_seconds"] = run.processCpu(); // now with the analysis
    writeFileAtomically(dir / "summary.json", summary.dump(2) + "\n");
    return summary;
}

namespace {

std::int64_t sizeOf(const std::filesystem::path& path) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    return ec ? -1 : std::int64_t(size);
}

} // namespace

RunPosition resumeRun(const nlohmann::json& r, const RunPlan& plan,
                      const std::filesystem::path& dir, RunRecord& run, RunFiles& files) {
    RunPosition at;
    std::int64_t trajectoryBytes = 0, thermoBytes = 0;
    std::uint64_t trajectoryTail = 0, thermoTail = 0;
    try {
        at.inProduction = r.at("phase") == "production";
        at.tick = r.at("tick").get<long>();
        at.sample = r.at("sample").get<long>();
        at.tStart = r.at("t_start").get<double>();
        at.cpuEquilibration = r.at("cpu_seconds_equilibration").get<double>();
        at.cpuProduction = r.at("cpu_seconds").get<double>();
        // A restart file from before it was kept: the engines' CPU, a lower bound.
        run.processCpuEarlier =
            r.value("process_cpu_seconds", at.cpuEquilibration + at.cpuProduction);
        run.production = r.at("production_statistics");
        const auto& p = r.at("momentum_initial");
        run.momentumInitial =
            Vec3(p.at(0).get<double>(), p.at(1).get<double>(), p.at(2).get<double>());
        run.restartsWritten = r.at("restarts_written").get<long>();
        run.continuations = r.at("continuations").get<int>() + 1;
        run.meltWarning = r.at("melt_warning").get<std::string>();
        trajectoryBytes = r.at("files").at("trajectory_bytes").get<std::int64_t>();
        thermoBytes = r.at("files").at("thermo_bytes").get<std::int64_t>();
        trajectoryTail = r.at("files").at("trajectory_tail_crc64").get<std::uint64_t>();
        thermoTail = r.at("files").at("thermo_tail_crc64").get<std::uint64_t>();
        run.sceneChecksum = r.at("identity").at("scene_crc64").get<std::uint64_t>();
    } catch (const nlohmann::json::exception& e) {
        throw damagedRestart(dir, e);
    }
    if (!at.inProduction) return at;
    const std::string restartPath = (dir / "restart.bin").string();
    // The statistics and the analysis' state first: a file that does not hold them cuts nothing.
    try {
        run.samples.restore(r.at("sample_statistics").get_binary());
        if (run.samples.count() != at.sample + 1)
            throw IoError(restartPath + ": damaged: its sample statistics hold " +
                          std::to_string(run.samples.count()) + " samples, its restart point " +
                          std::to_string(at.sample + 1));
        const auto row = recordsFromBinary(r.at("thermo_row"));
        if (row.size() != 1)
            throw IoError(restartPath + ": damaged: " + std::to_string(row.size()) +
                          " records of thermo.csv's last row");
        run.thermoRow = row.front();
        const auto& state = r.at("analysis");
        if (run.analysis) {
            run.analysis->restore(state.get_binary());
            if (run.analysis->samples() != at.sample + 1)
                throw IoError(restartPath + ": damaged: its analysis holds " +
                              std::to_string(run.analysis->samples()) +
                              " samples, its restart point " + std::to_string(at.sample + 1));
        } else if (!state.is_null())
            throw IoError(restartPath + ": damaged: an analysis' state for a run that plans none");
    } catch (const nlohmann::json::exception& e) {
        throw damagedRestart(dir, e);
    } catch (const IoError&) {
        throw;
    } catch (const std::invalid_argument& e) { // the analysis' or statistics' state does not fit
        throw IoError(restartPath + ": " + e.what());
    } catch (const std::runtime_error& e) { // the row's record is not whole
        throw IoError(restartPath + ": damaged: " + e.what());
    }
    // Every growing file is checked before any is cut back to its restart point.
    const bool withTrajectory = plan.trajectoryEvery > 0, withThermo = plan.thermoEvery > 0;
    struct Grown {
        std::string name;
        std::int64_t bytes;
        std::uint64_t tail;
    };
    for (const auto& [name, bytes, tail] :
         {Grown{"trajectory.xyz", withTrajectory && !plan.trajectoryGsd ? trajectoryBytes : 0,
                trajectoryTail},
          Grown{"thermo.csv", withThermo ? thermoBytes : 0, thermoTail}}) {
        const std::int64_t size = sizeOf(dir / name);
        if (bytes > 0 && size < bytes)
            throw IoError((dir / name).string() + " holds " +
                          std::to_string(std::max<std::int64_t>(size, 0)) +
                          " bytes, fewer than the " + std::to_string(bytes) +
                          " of its restart point: it was changed after restart.bin was written");
        // The tail before the restart point is the one restart.bin saw: not another run's file,
        // nor one changed since.
        if (bytes > 0 && tailChecksum(dir / name, bytes) != tail)
            throw IoError((dir / name).string() + ": its last " +
                          std::to_string(std::min(bytes, tailBytes)) +
                          " bytes before the restart point are not those restart.bin was written "
                          "with (checksum): the file is another run's, or was changed since");
    }
    if (withTrajectory && plan.trajectoryGsd) {
        const auto path = dir / "trajectory.gsd";
        std::uint64_t frames = 0, tail = 0;
        try {
            frames = r.at("files").at("trajectory_gsd_frames").get<std::uint64_t>();
            tail = r.at("files").at("trajectory_gsd_tail_crc64").get<std::uint64_t>();
        } catch (const nlohmann::json::exception& e) {
            throw damagedRestart(dir, e);
        }
        if (frames > 0 && gsdLastFrameChecksum(path, frames) != tail)
            throw IoError(path.string() + ": its frame " + std::to_string(frames - 1) +
                          " is not the one restart.bin was written with (checksum): the file is "
                          "another run's, or was changed since");
        files.gsd.emplace(path, hoomdChunkNames(), frames);
    } else if (withTrajectory)
        files.trajectory = AppendFile(dir / "trajectory.xyz", trajectoryBytes);
    if (withThermo) files.thermo = AppendFile(dir / "thermo.csv", thermoBytes);
    return at;
}

RunOutcome finishRun(const Scene& scene, RunRecord& run, const RunPosition& at,
                     const EngineEnd& last, const std::filesystem::path& dir,
                     const InterruptGuard& interrupt, bool stopped, bool restarts) {
    if (at.inProduction) {
        run.simulatedPs = units::toPs(last.time - at.tStart);
        run.momentumFinal = last.momentum;
    }
    run.cpuSeconds = at.cpuProduction;
    run.cpuEquilibration = at.cpuEquilibration;
    RunOutcome outcome;
    bool analysed = false;
    try {
        outcome.summary =
            writeSummaryAndAnalysis(scene, run, dir, interrupt, stopped ? 1 : 0, analysed);
    } catch (const std::exception&) {
        if (run.failure.empty()) throw;
        // The first error is the one to report; this one followed from it (e.g. a full disk).
    }
    if (!run.failure.empty())
        throw std::runtime_error(run.failure + " (output so far in " + dir.string() + ")");
    if (!run.interruptedBy.empty()) outcome.exitStatus = interrupt.exitStatus();
    // A run that went to its end and was analysed leaves nothing to continue. One whose analysis
    // a signal cancelled keeps its restart files: continuing redoes the last interval and the
    // analysis.
    if (restarts && !stopped && analysed) {
        std::error_code ec;
        std::filesystem::remove(dir / "restart.bin", ec);
    }
    return outcome;
}

} // namespace terrace::cli
