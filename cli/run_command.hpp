#pragma once
// `terrace run`: resolve the scene, build the initial state and the engine (all validation happens
// here, before anything is written), then drive the run into the output directory. A continued
// run takes its scene, bodies and engine checkpoint from the directory's restart file instead.
#include "cli/run_driver.hpp"
#include "core/scene.hpp"
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace terrace::cli {

struct RunRequest {
    std::string scenePath; // empty: the built-in default scene
    std::vector<std::string> overrides;
    bool quiet = false;
};

Scene resolveScene(const RunRequest& request);

/// The default output directory of a scene run with `overrides` (--set): out/<sanitised
/// name>-<engine>, followed by the overrides (overridesName: out/lj-liquid-smd-dt_fs=0.7).
std::filesystem::path defaultOutput(const Scene& scene, const std::vector<std::string>& overrides);

/// Runs the scene into target.dir (fresh or overwrite), once its memory and disk are checked
/// (cli/resource_check.hpp).
RunOutcome runScene(const Scene& scene, const RunTarget& target);
/// Continues the run whose restart file is in dir; returns its scene too.
RunOutcome continueRun(const std::filesystem::path& dir, bool quiet, Scene& scene);

// One translation unit per engine keeps compile times down; each instantiates its engine for
// every (body kind, potential) pair a scene may ask for. `target.resume`, when set, is the
// restart file the engine and its bodies come from (and are taken out of).
RunOutcome runSmd(const Scene& scene, const RunTarget& target);
RunOutcome runDmd(const Scene& scene, const RunTarget& target);

} // namespace terrace::cli
