#pragma once
// The scene's `dmd` section: its keys, their defaults and their checks, read here and nowhere
// else (the scene carries the section as given, core/scene.hpp). Every bad value is a SceneError
// naming its key.
//   dV            terrace height in units of kT (levels (n − ½) dV kT), > 0
//   levels        explicit levels in kJ/mol, strictly increasing (override dV when given)
//   values        with levels: the terrace energies, one per terrace (default: midpoints)
//   terraces      a design (dmd/terrace_design.hpp): {levels, values, n}
//   queue         heap | bpq | tree (default tree: every choice gives the same trajectory)
//   invalidation  lazy | eager
//   horizon_fs    virtual-event horizon and largest search step, fs, >= minHorizonFs
//   model         smoothed (terrace g(r)·U, the model SMD integrates) | bare (the paper's U)
//   resort_cells  RMS displacement, in cell widths, after which a run renumbers the bodies
//                 afresh (0: only at the start and at restart points; auto, the default: 1 from
//                 prefetchFromBodies bodies on, 0 below)
// Keys that only served to measure are refused with a pointer to TERRACE_MEASURE
// (core/measure.hpp); docs/CHANGES.md lists them.
#include "core/initial_state.hpp"
#include "core/scene.hpp"
#include "core/scene_json.hpp"
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace terrace::dmd {

/// Below this the horizon buys nothing: a thermal pair moves ~1e-3 Å in it (~0.05 Å in the
/// paper's 4 fs), far below any terrace's width, and virtual events alone would stall the run.
inline constexpr double minHorizonFs = 0.1;
/// Uniform terraces (dV·kT) in the well, |U_min| / (dV·kT): beyond this a pair's events would
/// come at round-off spacing of U (terrace_levels' clearance is 1e-6 |U_min|).
inline constexpr double maxTerracesInWell = 1e5;
/// dmd.terraces.n for an optimal design: its levels in the well, of the 2500 it may have in all.
inline constexpr int maxOptimalWellLevels = 300;

struct DmdSection {
    double dV = 0.5;            // terrace height in units of kT
    std::vector<double> levels; // explicit levels U_k in kJ/mol (overrides dV when given)
    std::vector<double> values; // with levels: the terrace energies V_s, kJ/mol (default
                                // midpoints); levels.size() + 1 of them
    // A terrace design (dmd/terrace_design.hpp): level placement energy | distance | volume
    // | optimal, terrace values midpoint | volume | boltzmann | virial, and n levels in the
    // well (0: as many as uniform levels of height dV put there). The default, energy and
    // midpoint with n = 0, is the paper's uniform terracing.
    struct Terraces {
        std::string levels = "energy";
        std::string values = "midpoint";
        int n = 0;
        bool isDefault() const { return levels == "energy" && values == "midpoint" && n == 0; }
        bool operator==(const Terraces&) const = default;
    } terraces;
    // The calendar: the tournament tree over the bodies (dmd/tournament_queue.hpp) is the
    // fastest of the three from N 512 to 10^6 on the dense rods (docs/PERFORMANCE.md).
    std::string queue = "tree";
    std::string invalidation = "lazy";
    double horizon_fs = 4.0;
    std::string model = "smoothed";
    // With the bodies in Morton order (dmd/engine.hpp), renumber them afresh once their RMS
    // displacement since the last numbering reaches this many cell widths: the engine is rebuilt
    // from its checkpoint at that sample or thermostat tick, as at a restart point. Unset: auto.
    std::optional<double> resort_cells;
};

/// "" when uniform levels dV·kT leave at most maxTerracesInWell terraces in a well of depth
/// |uMin|, else "<key>: <why>", blaming state.temperature when even dV = 1 would be too fine, and
/// `wellKey` (the potential's key that sets the depth) when the well is so deep against ε that
/// even the default temperature (kTDefault) would be too cold for it.
inline std::string terraceCountProblem(double uMin, double dV, double kT, double kTDefault = 0.0,
                                       const std::string& wellKey = "") {
    const double count = std::abs(uMin) / (dV * kT);
    if (count <= maxTerracesInWell) return "";
    const bool cold = !(std::abs(uMin) / kT <= maxTerracesInWell);
    const bool deep =
        !wellKey.empty() && kTDefault > 0.0 && !(std::abs(uMin) / kTDefault <= maxTerracesInWell);
    if (cold && deep) {
        std::ostringstream o;
        o << wellKey << ": gives a well U_min = " << uMin << " kJ/mol deep, "
          << std::abs(uMin) / kTDefault << " kT even at the default temperature: more than the "
          << maxTerracesInWell
          << " terraces a run can represent would be needed (levels would crowd the minimum at "
             "round-off); choose a shallower well";
        return o.str();
    }
    const char* blamed = cold ? "state.temperature" : "dmd.dV";
    std::ostringstream o;
    o << blamed << ": kT = " << kT << " kJ/mol with dmd.dV = " << dV << " makes " << count
      << " terraces of " << dV * kT << " kJ/mol in the well (U_min = " << uMin
      << " kJ/mol), more than the " << maxTerracesInWell
      << " a run can represent (levels would crowd the minimum at round-off); raise " << blamed;
    if (cold)
        o << " at least " << count / maxTerracesInWell << "-fold";
    else
        o << " to at least " << std::abs(uMin) / (maxTerracesInWell * kT);
    return o.str();
}

namespace detail {

/// Keys that only served to measure, and where their switch lives now.
inline void refuseRemovedKeys(const JsonSection& d) {
    if (d.has("hold_screen"))
        d.fail("hold_screen", "has been removed from the scene (the hold-time screen is always "
                              "on): to measure without it, set TERRACE_MEASURE=no-hold-screen "
                              "in the environment");
    if (d.has("sort_bodies"))
        d.fail("sort_bodies", "has been removed from the scene (DMD always keeps its bodies in "
                              "the Morton order of their cells): to measure without it, set "
                              "TERRACE_MEASURE=no-sort-dmd in the environment");
    if (d.has("queue") && d.at("queue") == "auto")
        d.fail("queue", "\"auto\" has been removed: use \"tree\", the same queue (the default)");
}

inline void readLevels(const JsonSection& d, DmdSection& s) {
    if (d.has("levels")) {
        if (!d.at("levels").is_array() || d.at("levels").empty())
            d.fail("levels", "must be a non-empty array");
        s.levels = d.numbers("levels", "kJ/mol");
        for (std::size_t k = 1; k < s.levels.size(); ++k)
            if (!(s.levels[k] > s.levels[k - 1])) d.fail("levels", "must be strictly increasing");
    }
    if (!d.has("values")) return;
    if (!d.has("levels")) d.fail("values", "needs dmd.levels, the levels it fills");
    s.values = d.numbers("values", "kJ/mol");
    if (s.values.size() != s.levels.size() + 1)
        d.fail("values", "needs one value per terrace, " + std::to_string(s.levels.size() + 1) +
                             " for " + std::to_string(s.levels.size()) + " levels, got " +
                             std::to_string(s.values.size()));
}

inline void readTerraces(const JsonSection& d, DmdSection& s) {
    if (!d.has("terraces")) return;
    const JsonSection t = d.section("terraces");
    t.onlyKeys({"levels", "values", "n"});
    auto& design = s.terraces;
    design.levels = t.choice("levels", design.levels, {"distance", "energy", "optimal", "volume"});
    design.values = t.choice("values", design.levels == "optimal" ? "boltzmann" : design.values,
                             {"boltzmann", "midpoint", "virial", "volume"});
    if (design.levels == "optimal" && design.values != "boltzmann")
        t.fail("values", "levels \"optimal\" set their own values (the Boltzmann mean of each "
                         "terrace): give \"boltzmann\" or leave it out");
    // An optimal design iterates over all its levels until they settle; beyond a few hundred
    // in the well that takes longer than a run's start should (dmd/terrace_design.hpp,
    // maxOptimalLevels, which also bounds the levels up the wall).
    design.n = static_cast<int>(
        t.integer("n", design.n, 0, design.levels == "optimal" ? maxOptimalWellLevels : 100000));
    if (!s.levels.empty() && !design.isDefault())
        d.fail("terraces", "and dmd.levels both set the levels: give one of them");
}

} // namespace detail

/// The section read and checked on its own; `origin` names the scene in errors ("" for none).
inline DmdSection readDmdSection(const nlohmann::json& section, const std::string& origin = "") {
    const JsonSection d(section, "dmd", origin);
    if (section.is_object()) detail::refuseRemovedKeys(d);
    d.onlyKeys({"dV", "levels", "values", "terraces", "queue", "invalidation", "horizon_fs",
                "model", "resort_cells"});
    DmdSection s;
    s.model = d.choice("model", s.model, {"bare", "smoothed"});
    s.dV = d.number("dV", s.dV, 0.0, 1e6, true);
    detail::readLevels(d, s);
    detail::readTerraces(d, s);
    s.queue = d.choice("queue", s.queue, {"bpq", "heap", "tree"});
    s.invalidation = d.choice("invalidation", s.invalidation, {"eager", "lazy"});
    s.horizon_fs = d.number("horizon_fs", s.horizon_fs, 0.0, 1e6, true);
    if (s.horizon_fs < minHorizonFs)
        d.fail("horizon_fs", "must be >= " + showNumber(minHorizonFs) + " fs, got " +
                                 showNumber(s.horizon_fs) +
                                 ": a thermal pair moves ~1e-3 Å in 0.1 fs, so a shorter horizon "
                                 "only multiplies virtual events (the paper uses 4 fs)");
    if (d.has("resort_cells") && d.at("resort_cells") != "auto")
        s.resort_cells = d.number("resort_cells", 0.0, 0.0, 1e6);
    return s;
}

/// The section resolved, every key written out (optional ones only when set).
inline nlohmann::json toJson(const DmdSection& s) {
    nlohmann::json j = {{"dV", s.dV},
                        {"queue", s.queue},
                        {"invalidation", s.invalidation},
                        {"horizon_fs", s.horizon_fs},
                        {"model", s.model}};
    if (!s.levels.empty()) j["levels"] = s.levels;
    if (!s.values.empty()) j["values"] = s.values;
    if (s.resort_cells) j["resort_cells"] = *s.resort_cells;
    if (!s.terraces.isDefault())
        j["terraces"] = {
            {"levels", s.terraces.levels}, {"values", s.terraces.values}, {"n", s.terraces.n}};
    return j;
}

/// The section of `scene` read and checked against the rest of it, written back resolved, and
/// its warnings added to scene.warnings. The terrace count is checked for DMD runs only: an SMD
/// run has no terraces, though its dmd section must still be valid.
inline DmdSection resolveDmdSection(Scene& scene, const std::string& origin = "") {
    const DmdSection d = readDmdSection(scene.dmd, origin);
    const std::string prefix = origin.empty() ? "" : origin + ": ";
    if (scene.potential.kind == "steps") { // the table's steps are the levels (dmd/settings.hpp)
        if (!d.levels.empty() || !d.terraces.isDefault())
            throw SceneError(prefix + (d.levels.empty() ? "dmd.terraces" : "dmd.levels") +
                             ": potential.kind steps sets its own levels, one per step of its "
                             "table: leave it out");
        scene.dmd = toJson(d);
        return d;
    }
    if (scene.engine == "dmd" && d.levels.empty()) {
        const double uMin = sceneMinimumEnergy(scene);
        // The well's depth against ε is set by the anisotropy for Gay–Berne, by the sites'
        // parameters for a site-site molecule, and is of order ε otherwise.
        const std::string wellKey = scene.potential.kind == "gay-berne" ? "potential.kappa"
                                    : scene.potential.kind == "sites"   ? "body.sites"
                                                                        : "potential.epsilon";
        const double kTDefault = Scene{}.state.temperature * scene.potential.epsilon;
        const std::string problem = terraceCountProblem(uMin, d.dV, scene.kT(), kTDefault, wellKey);
        if (!problem.empty()) throw SceneError(prefix + problem);
        // Uniform levels sit at (n − ½)·dV·kT. With the first one below 0 under U_min no pair is
        // ever bound: the terraced potential is purely repulsive, a model the paper itself runs
        // (the rods at ΔV = 2 kT), so that is said, not refused. With the first one above 0 also
        // beyond every start's energy (maxStartEnergyInKT) no thermal pair ever meets a level:
        // the bodies pass through each other with U = 0 throughout, which no study wants.
        if (d.terraces.levels == "energy" && d.terraces.n == 0 && uMin < 0.0 &&
            !(0.5 * d.dV * scene.kT() < -uMin)) {
            std::ostringstream o;
            o << "dmd.dV: " << d.dV << " kT puts the first level at " << -0.5 * d.dV * scene.kT()
              << " kJ/mol, below the potential minimum U_min = " << uMin
              << " kJ/mol: no terrace lies in the well";
            if (0.5 * d.dV > terrace::detail::maxStartEnergyInKT) {
                o << ", and the first above 0, " << 0.5 * d.dV << " kT, lies beyond every "
                  << "start's energy (" << terrace::detail::maxStartEnergyInKT
                  << " kT): the bodies would pass through each other with U = 0 throughout; "
                     "give dmd.dV < "
                  << 2.0 * -uMin / scene.kT() << " for a well";
                throw SceneError(prefix + o.str());
            }
            o << ", so the terraced potential is purely repulsive (dmd.dV < "
              << 2.0 * -uMin / scene.kT() << " gives it a well)";
            scene.warnings.push_back(o.str());
        }
    }
    if (!d.levels.empty()) {
        const double uMin = sceneMinimumEnergy(scene);
        bool inWell = false;
        for (double level : d.levels)
            inWell = inWell || (level > uMin && level < 0.0);
        if (!inWell) {
            std::ostringstream o;
            o << "dmd.levels: no level lies between the potential minimum U_min = " << uMin
              << " kJ/mol and 0, so the terraced potential has no attractive well";
            scene.warnings.push_back(o.str());
        }
    }
    scene.dmd = toJson(d);
    return d;
}

} // namespace terrace::dmd
