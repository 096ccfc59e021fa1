#pragma once
// `terrace run`: resolve the scene, build the initial state and the engine (all validation happens
// here, before anything is written), then drive the run into the output directory.
#include "core/scene.hpp"
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace terrace::cli {

struct RunRequest {
    std::string scenePath; // empty: the built-in default scene
    std::vector<std::string> overrides;
    std::filesystem::path outDir; // empty: out/<scene name>-<engine>
    bool quiet = false;
};

Scene resolveScene(const RunRequest& request);

/// Runs and returns summary.json's content.
nlohmann::json runScene(const Scene& scene, const std::filesystem::path& outDir, bool quiet);

// One translation unit per engine keeps compile times down; each instantiates its engine for
// every (body kind, potential) pair a scene may ask for.
nlohmann::json runSmd(const Scene& scene, const std::filesystem::path& outDir, bool quiet);
nlohmann::json runDmd(const Scene& scene, const std::filesystem::path& outDir, bool quiet);

/// Creates the output directory and writes the resolved scene and the initial state into it.
void prepareOutput(const std::filesystem::path& dir, const Scene& scene);

} // namespace terrace::cli
