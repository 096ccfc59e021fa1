#pragma once
// The scene's `smd` section, read and checked here and nowhere else (the scene carries it as
// given, core/scene.hpp), and the SMD run parameters made from it before any work (DESIGN.md "Bad
// input"):
//   dt_fs   time step, fs, in (0, 1000]; under SMD every sample and thermostat interval is a
//           whole number of steps
//   skin    Verlet skin, σ, in [0, 10]
//   scheme  the splitting (smd/splitting.hpp): verlet (the paper's) | omelyan | yoshida4
// The cutoff r_u is the model's (potential.cutoff, core/smoothed_potential.hpp). The box must
// hold two cutoffs plus skins, L >= 2 (r_u + skin), so that a pair within reach has exactly one
// periodic image within reach. The bodies' cell order is a measurement switch
// (TERRACE_MEASURE=no-sort-smd, core/measure.hpp), not a key.
#include "core/heat_bath.hpp"
#include "core/measure.hpp"
#include "core/scene.hpp"
#include "core/scene_json.hpp"
#include "core/units.hpp"
#include "smd/splitting.hpp"
#include <cmath>
#include <string>

namespace terrace::smd {

struct SmdSection {
    double dt_fs = 1.8;
    double skin = 0.3; // σ
    std::string scheme = "verlet";
};

/// The section read and checked on its own; `origin` names the scene in errors ("" for none).
inline SmdSection readSmdSection(const nlohmann::json& section, const std::string& origin = "") {
    const JsonSection d(section, "smd", origin);
    // The cutoff belongs to the model both engines simulate, no longer to SMD alone.
    for (const char* moved : {"r_l", "r_u"})
        if (section.is_object() && d.has(moved))
            d.fail(moved, "has moved to potential.cutoff = [r_l, r_u] (σ), the cutoff of the model "
                          "both engines simulate");
    if (section.is_object() && d.has("sort_bodies"))
        d.fail("sort_bodies", "has been removed from the scene (SMD always keeps its bodies in "
                              "cell order): to measure without it, set "
                              "TERRACE_MEASURE=no-sort-smd in the environment");
    d.onlyKeys({"dt_fs", "skin", "scheme"});
    SmdSection s;
    s.dt_fs = d.number("dt_fs", s.dt_fs, 0.0, 1e3, true);
    s.skin = d.number("skin", s.skin, 0.0, 10.0);
    s.scheme = d.choice("scheme", s.scheme, {"omelyan", "verlet", "yoshida4"});
    return s;
}

inline nlohmann::json toJson(const SmdSection& s) {
    return {{"dt_fs", s.dt_fs}, {"skin", s.skin}, {"scheme", s.scheme}};
}

/// The section of `scene` read and checked against the run it belongs to, and written back
/// resolved. SMD advances in whole steps: under SMD no interval or run length may fall between
/// two.
inline SmdSection resolveSmdSection(Scene& scene, const std::string& origin = "") {
    const SmdSection s = readSmdSection(scene.smd, origin);
    scene.smd = toJson(s);
    if (scene.engine != "smd") return s;
    const JsonSection at(scene.smd, "smd", origin);
    const auto& run = scene.run;
    if (s.dt_fs > run.time_ps * 1000.0)
        at.fail("dt_fs", showNumber(s.dt_fs) + " fs is longer than run.time_ps = " +
                             showNumber(run.time_ps) + " ps: no step would be taken");
    requireOnGrid(at, "run.sample_fs", run.sample_fs, "fs", 1.0, "smd.dt_fs", s.dt_fs);
    requireOnGrid(at, "run.thermostat_fs", run.thermostat_fs, "fs", 1.0, "smd.dt_fs", s.dt_fs);
    // CSVR acts once a step (smd/engine.hpp): a relaxation within one step is not resolved.
    if (run.heat_bath.kind == "csvr" && run.heat_bath.tau_fs < s.dt_fs)
        at.refuse("run.heat_bath.tau_fs",
                  showNumber(run.heat_bath.tau_fs) +
                      " fs is shorter than smd.dt_fs = " + showNumber(s.dt_fs) +
                      " fs: the bath acts once a step, so it cannot relax the kinetic energy "
                      "faster; give tau_fs >= dt_fs (typically 100 dt or more)");
    // The run's lengths need not be whole intervals (the last one is cut short), but SMD cannot
    // stop between two steps.
    requireOnGrid(at, "run.time_ps", run.time_ps, "ps", 1000.0, "smd.dt_fs", s.dt_fs);
    if (run.equilibrate_ps > 0.0)
        requireOnGrid(at, "run.equilibrate_ps", run.equilibrate_ps, "ps", 1000.0, "smd.dt_fs",
                      s.dt_fs);
    return s;
}

struct Parameters {
    double dt = 0.0;   // time units (100 fs)
    double skin = 0.0; // Å
};

/// Validated SMD parameters for a box of edge boxLength (Å) and a model of range r_u (Å); throws
/// SceneError naming the key.
inline Parameters parameters(const Scene& scene, double boxLength, double range) {
    const SmdSection s = readSmdSection(scene.smd);
    const double sigma = scene.potential.sigma;
    if (!std::isfinite(range))
        throw SceneError("potential.cutoff: SMD needs a finite cutoff (the model has none)");
    if (!(std::isfinite(sigma) && sigma > 0.0))
        throw SceneError("potential.sigma: must be > 0 (got " + showNumber(sigma) + ")");
    Parameters p;
    p.dt = units::fromFs(s.dt_fs);
    p.skin = s.skin * sigma;
    const double needed = 2.0 * (range + p.skin);
    if (!(boxLength >= needed)) {
        // The box's volume is N/ρ: the same density needs N (needed/L)³ bodies, the same N a
        // density ρ (L/needed)³.
        const double grow = std::pow(needed / boxLength, 3);
        const int bodies =
            scene.state.particles.empty() ? scene.state.n : int(scene.state.particles.size());
        // Four significant digits, rounded down, so that the density named is one that fits.
        const double density = scene.state.density / grow;
        const double digit = std::pow(10.0, std::floor(std::log10(density)) - 3.0);
        throw SceneError("potential.cutoff: the box edge " + showNumber(boxLength) +
                         " Å is shorter than 2·(r_u + skin) = " + showNumber(needed) +
                         " Å; use state.n >= " +
                         std::to_string(static_cast<long long>(std::ceil(bodies * grow))) +
                         ", state.density <= " + showNumber(std::floor(density / digit) * digit) +
                         ", or a smaller r_u or smd.skin");
    }
    return p;
}

/// Everything the SMD engine takes from a scene, read and checked once: the step and skin, the
/// splitting, σ (the unit its statistics give the skin and cutoffs in) and whether it keeps its
/// bodies in cell order (TERRACE_MEASURE=no-sort-smd turns that off, to measure it).
struct SmdSettings {
    Parameters par;
    Splitting scheme;
    double sigma = 0.0; // Å
    bool sortBodies = true;
    HeatBath bath;          // run.heat_bath (core/heat_bath.hpp), applied after every step
    std::uint64_t seed = 1; // the scene's: the bath's stream
};

/// The SMD settings of `scene` for a box of edge boxLength (Å) and a model of range r_u (Å).
inline SmdSettings smdSettings(const Scene& scene, double boxLength, double range) {
    return {parameters(scene, boxLength, range),
            splitting(readSmdSection(scene.smd).scheme),
            scene.potential.sigma,
            measureSwitches().sortSmd,
            heatBathOf(scene),
            scene.seed};
}

} // namespace terrace::smd
