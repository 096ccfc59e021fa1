#pragma once
// A sweep: one base scene, the runs that vary it, and the directory each run lands in. Read from
// a sweep file (JSON):
//   {
//     "scene": "dense-rods.json",       base scene, relative to the sweep file (default: built-in)
//     "set":   {"state.n": 216},        overrides every run gets
//     "axes":  [AXIS, ...],             the runs are the product of the axes, the first slowest
//     "seeds": [1, 2, 3]                innermost axis of the scene key `seed`
//   }
//   AXIS = {"state.density": [0.1, 0.3]}                      one key over a list of values
//        | {"dmd.dV": [2, 1], "run.time_ps": [0.9, 1.8]}      keys zipped: lists of one length
//        | {"cases": [{"engine": "dmd", "dmd.dV": 0.5},       alternatives, each a set of
//                     {"engine": "smd", "smd.dt_fs": 1.8}]}   overrides (ladders of two engines)
//   and any axis may carry "labels": ["a", "b"], one per value, naming its values in directory
//   names instead of the values themselves.
// Keys are the dotted scene keys of `terrace run --set`; values are JSON. A run's directory is
// named by its overrides, axis by axis, joined by '_': "<key>-<value>" with the key's last
// component (the whole dotted key where two of the sweep's keys share it), e.g.
// density-0.3_engine-dmd_dV-0.5_seed-2. A key of one engine's section set for runs of the other
// is noted (SweepPlan::ignoredKeys). Every run's scene is resolved and checked when the plan
// is made, so a bad sweep file fails with one line naming the run and the key before anything
// runs.
#include "core/scene.hpp"
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace terrace::cli {

using Override = std::pair<std::string, nlohmann::json>; // dotted scene key, value

struct SweepRun {
    std::string name;                // its directory under the sweep's output directory
    std::vector<Override> overrides; // what the axes set for this run, in axis order
    Scene scene;                     // resolved: base scene + common + overrides
};

struct SweepPlan {
    std::string origin;                // the sweep file, for messages
    std::filesystem::path scenePath;   // empty: the built-in default scene
    std::vector<Override> common;      // the file's "set", then the command line's --set
    std::vector<std::string> axisKeys; // every key an axis sets, in order of first appearance
    std::vector<SweepRun> runs;        // in sweep order
    // Keys set for runs whose engine does not read them (cli/engine_keys.hpp), one line each: an
    // axis's key of one engine's section on runs of the other, or a common key of an engine that
    // no run of the sweep has. Warnings (asWarning), or refused under --strict (refuseIgnoredKeys).
    std::vector<std::string> ignoredKeys;
};

/// Reads and checks a sweep file; `extraSets` ("key=value", as for terrace run) apply to every
/// run after the file's "set". Throws SceneError with one line naming the problem.
SweepPlan loadSweep(const std::filesystem::path& file, const std::vector<std::string>& extraSets);

/// The same from the file's JSON text (`origin` names it; relative scene paths resolve against
/// `baseDir`).
SweepPlan sweepFromJson(const std::string& text, const std::string& origin,
                        const std::filesystem::path& baseDir,
                        const std::vector<std::string>& extraSets);

/// Throws the first of plan.ignoredKeys as a SceneError, if there is one.
void refuseIgnoredKeys(const SweepPlan& plan);

/// "key=value" with the value as JSON, as `terrace run --set` takes it.
std::string overrideArgument(const Override& o);

/// A value as it reads in a directory name or a table cell: strings bare, others as JSON.
std::string valueText(const nlohmann::json& value);

} // namespace terrace::cli
