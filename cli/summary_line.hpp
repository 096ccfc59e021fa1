#pragma once
// What `terrace run` prints when a run ends: the engine, N, simulated and CPU time; temperature
// and target, ⟨U⟩ per body beside the system's total, the energy's fluctuation and drift; the
// pressure; DMD's collision rate. In the scene's units: real (K, kJ/mol, ps, bar and P*) or lj
// (T*, ε, τ, P*, read from summary.json's "reduced" entry, cli/reduced_summary.hpp).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace terrace::cli {

/// The lines (each ending in '\n') for the run named `name` whose summary.json is `summary`,
/// written into `out`.
std::string runSummaryText(const std::string& name, const nlohmann::json& summary,
                           const std::filesystem::path& out);

} // namespace terrace::cli
