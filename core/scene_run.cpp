// The run, output and analysis sections: run lengths and intervals, what is written when, and
// the analysis accumulated as the run goes. Each interval fits in the run and lies on its grid
// (core/scene.hpp Scene::Run); SMD's own grid, smd.dt_fs, is checked by smd/parameters.hpp.
#include "core/scene_sections.hpp"
#include "core/thermo_interval.hpp"
#include "core/whole_intervals.hpp"
#include <cmath>

namespace terrace::detail {

namespace {

std::string longerThanTheRun(const Scene& s) {
    return " is longer than run.time_ps = " + showNumber(s.run.time_ps) + " ps";
}

/// An output interval (in `unit`, fsPerUnit fs each) of 0 (none) or whole samples within the run.
void requireOutputInterval(const JsonSection& out, const std::string& key, double value,
                           const char* unit, double fsPerUnit, const std::string& what,
                           const Scene& s) {
    if (!(value > 0.0)) return;
    if (value * fsPerUnit > s.run.time_ps * 1000.0)
        out.fail(key, showNumber(value) + " " + unit + longerThanTheRun(s) + ": no " + what +
                          " would be written");
    requireOnGrid(out, out.name(key), value, unit, fsPerUnit, "run.sample_fs", s.run.sample_fs);
}

/// run.heat_bath: "none", or an object of a kind and that kind's one parameter.
void readHeatBath(const JsonSection& run, Scene& s) {
    auto& h = s.run.heat_bath;
    if (!run.has("heat_bath")) return;
    const auto& value = run.at("heat_bath");
    const std::string example = "; give {\"kind\": \"andersen\", \"rate_per_ps\": ν} or "
                                "{\"kind\": \"csvr\", \"tau_fs\": τ}";
    if (value.is_string()) {
        h.kind = run.choice("heat_bath", "none", {"none", "andersen", "csvr"});
        if (h.kind != "none")
            run.fail("heat_bath", "\"" + h.kind + "\" needs its parameter" + example);
        return;
    }
    if (!value.is_object())
        run.fail("heat_bath", "must be \"none\" or an object, got " + showJson(value) + example);
    const JsonSection bath = run.section("heat_bath");
    bath.onlyKeys({"kind", "rate_per_ps", "tau_fs"});
    if (!bath.has("kind")) bath.fail("kind", "is missing: none | andersen | csvr");
    h.kind = bath.choice("kind", h.kind, {"none", "andersen", "csvr"});
    const char* needed = h.kind == "andersen" ? "rate_per_ps" : h.kind == "csvr" ? "tau_fs" : "";
    for (const char* key : {"rate_per_ps", "tau_fs"})
        if (bath.has(key) && std::string(key) != needed)
            bath.fail(key, "is not read by heat_bath.kind " + h.kind +
                               (*needed ? std::string(" (its parameter is ") + needed + ")" : ""));
    if (*needed && !bath.has(needed)) bath.fail(needed, "is missing for kind " + h.kind);
    // A collision per body every 1e-6 ps or oftener, or a relaxation within minIntervalFs, is
    // faster than any thermal motion the run resolves: the dynamics would be the bath's alone.
    if (h.kind == "andersen")
        h.rate_per_ps = bath.number("rate_per_ps", 0.0, 0.0, 1e3 / limits::minIntervalFs, true);
    if (h.kind == "csvr") {
        h.tau_fs = bath.number("tau_fs", 0.0, 0.0, 1e12, true);
        if (h.tau_fs < limits::minIntervalFs)
            bath.fail("tau_fs", "must be >= " + showNumber(limits::minIntervalFs) + " fs, got " +
                                    showNumber(h.tau_fs) +
                                    ": the bath would fix the kinetic energy faster than any "
                                    "motion the run resolves");
    }
}

} // namespace

void readRun(const JsonSection& run, Scene& s) {
    // run.thermostat is the unit-free twin of run.thermostat_fs (core/scene_units.hpp); a kind of
    // bath given there is pointed to its own key.
    if (run.has("thermostat") &&
        (run.at("thermostat").is_string() || run.at("thermostat").is_object()))
        run.fail("thermostat", "the kind of heat bath is run.heat_bath (\"none\", "
                               "{\"kind\": \"andersen\", \"rate_per_ps\": ν} or {\"kind\": "
                               "\"csvr\", \"tau_fs\": τ}); run.thermostat_fs is the "
                               "equilibration's rescale interval");
    run.onlyKeys({"equilibrate_ps", "time_ps", "sample_fs", "thermostat_fs", "heat_bath"});
    readHeatBath(run, s);
    auto& r = s.run;
    r.equilibrate_ps = run.number("equilibrate_ps", r.equilibrate_ps, 0, 1e9);
    r.time_ps = run.number("time_ps", r.time_ps, 0, 1e9, true);
    r.sample_fs = run.number("sample_fs", r.sample_fs, 0, 1e9, true);
    r.thermostat_fs = run.number("thermostat_fs", r.thermostat_fs, 0, 1e9, true);
    for (const char* key : {"sample_fs", "thermostat_fs"}) {
        const double value = key == std::string("sample_fs") ? r.sample_fs : r.thermostat_fs;
        if (value < limits::minIntervalFs)
            run.fail(key, "must be >= " + showNumber(limits::minIntervalFs) + " fs, got " +
                              showNumber(value) +
                              ": thermal motion hardly changes in so short an interval (bodies "
                              "take >= 0.1 fs to cross σ or turn a radian)");
    }
    if (r.sample_fs > r.time_ps * 1000.0)
        run.fail("sample_fs", showNumber(r.sample_fs) + " fs" + longerThanTheRun(s) +
                                  ": no sample would be taken");
    // Run lengths are honoured as typed, whatever the intervals (cli/run_driver.cpp planRun):
    // equilibration's last thermostat interval is cut short to end on a rescale at
    // run.equilibrate_ps, and production runs on, unsampled, from its last whole sample to
    // run.time_ps. Under SMD both lengths are whole steps (smd/parameters.hpp).
}

void readOutput(const JsonSection& out, Scene& s) {
    out.onlyKeys(
        {"trajectory_every_fs", "trajectory_format", "restart_every_ps", "thermo_every_fs"});
    auto& o = s.output;
    o.trajectory_format = out.choice("trajectory_format", o.trajectory_format, {"xyz", "gsd"});
    o.trajectory_every_fs = out.number("trajectory_every_fs", o.trajectory_every_fs, 0, 1e9);
    o.restart_every_ps = out.number("restart_every_ps", o.restart_every_ps, 0, 1e9);
    o.thermo_every_fs = out.has("thermo_every_fs")
                            ? out.number("thermo_every_fs", 0.0, 0, 1e9)
                            : defaultThermoEveryFs(s.run.time_ps, s.run.sample_fs);
    // Output is written at samples: its intervals are whole numbers of them within the run.
    requireOutputInterval(out, "trajectory_every_fs", o.trajectory_every_fs, "fs", 1.0, "frame", s);
    requireOutputInterval(out, "thermo_every_fs", o.thermo_every_fs, "fs", 1.0, "thermo row", s);
    requireOutputInterval(out, "restart_every_ps", o.restart_every_ps, "ps", 1000.0, "restart file",
                          s);
}

void readAnalysis(const JsonSection& an, Scene& s) {
    an.onlyKeys({"blocks", "max_lag_ps", "rdf_max", "rdf_bin_angstrom", "rdf_every",
                 "follow_bodies", "lags_per_level"});
    auto& a = s.analysis;
    // g(r) reaches L/2 at most: beyond, a pair's nearest image is no longer the only one.
    const double halfBox = 0.5 * s.boxLength(), halfBoxSigma = halfBox / s.potential.sigma;
    a.blocks = static_cast<int>(an.integer("blocks", a.blocks, 2, 10000));
    // A block needs two samples (analysis/run_analysis.cpp): more blocks than that are cut to
    // what the run's samples allow. Said when asked for explicitly; the default is cut quietly.
    // The tail past the last whole sample is not sampled.
    const long samples = wholeIntervals(s.run.time_ps * 1000.0 / s.run.sample_fs);
    if (an.has("blocks") && a.blocks > samples / 2)
        s.warnings.push_back(
            "analysis.blocks: " + std::to_string(a.blocks) + " asked for, but " +
            std::to_string(samples) + " samples (run.time_ps / run.sample_fs) make at most " +
            std::to_string(samples / 2) + " blocks of two samples: " + std::to_string(samples / 2) +
            " are used");
    a.max_lag_ps = an.number("max_lag_ps", a.max_lag_ps, 0, 1e9);
    a.rdf_max = an.number("rdf_max", std::min(a.rdf_max, halfBoxSigma), 0, 1e6);
    if (a.rdf_max > halfBoxSigma)
        an.fail("rdf_max", showNumber(a.rdf_max) +
                               " σ reaches past half the box, L/2 = " + showNumber(halfBoxSigma) +
                               " σ (" + showNumber(halfBox) + " Å): give at most " +
                               showNumber(std::floor(halfBoxSigma * 1e4) / 1e4) + ", or 0 for L/2");
    a.rdf_bin_angstrom = an.number("rdf_bin_angstrom", a.rdf_bin_angstrom, 1e-6, 1e6);
    a.rdf_every = static_cast<int>(an.integer("rdf_every", a.rdf_every, 1, 1 << 30));
    a.follow_bodies = static_cast<int>(an.integer("follow_bodies", a.follow_bodies, 0, 100000000));
    a.lags_per_level = static_cast<int>(an.integer("lags_per_level", a.lags_per_level, 4, 4096));
    if (a.lags_per_level % 2 != 0)
        an.fail("lags_per_level", std::to_string(a.lags_per_level) +
                                      " is odd: each level adds the upper half of its lags, so "
                                      "the number must be even");
    if (a.rdf_bin_angstrom > halfBox)
        an.fail("rdf_bin_angstrom", showNumber(a.rdf_bin_angstrom) +
                                        " Å is wider than half the box, " + showNumber(halfBox) +
                                        " Å: g(r) has no bin");
}

} // namespace terrace::detail
