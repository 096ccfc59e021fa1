#include "cli/sweep_table.hpp"
#include "core/output_file.hpp"
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

namespace terrace::cli {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

/// A JSON file's content, or null when it is missing or not JSON.
json readJson(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return nullptr;
    try {
        const json j = json::parse(readWholeFile(path), nullptr, false);
        return j.is_discarded() ? json(nullptr) : j;
    } catch (const IoError&) {
        return nullptr;
    }
}

/// The last non-empty line of a run's log: a run that fails before it writes a summary (a scene
/// it refuses, memory it cannot have) says why there.
std::string lastLogLine(const fs::path& log) {
    std::string text;
    try {
        text = readWholeFile(log);
    } catch (const IoError&) {
        return "";
    }
    std::istringstream in(text);
    std::string line, last;
    while (std::getline(in, line))
        if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
    const std::string prefix = "terrace: ";
    return last.rfind(prefix, 0) == 0 ? last.substr(prefix.size()) : last;
}

std::string csvField(const std::string& s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
    std::string quoted = "\"";
    for (const char c : s) {
        if (c == '\n' || c == '\r') {
            quoted += ' ';
            continue;
        }
        if (c == '"') quoted += '"';
        quoted += c;
    }
    return quoted + "\"";
}

std::string number(double x) {
    if (!std::isfinite(x)) return "nan";
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", x);
    return text;
}

/// The summary's numbers the table carries, by JSON pointer.
struct Column {
    const char* header;
    const char* pointer;
};
constexpr Column summaryColumns[] = {
    {"n_bodies", "/n_bodies"},
    {"simulated_ps", "/simulated_ps"},
    {"temperature_K", "/temperature_K"},
    {"potential_energy_kJ_per_mol", "/potential_energy_mean"},
    {"potential_energy_std", "/potential_energy_std"},
    {"potential_energy_err", "/potential_energy_err"},
    {"temperature_err_K", "/temperature_err_K"},
    {"pressure_reduced", "/pressure/mean_reduced"},
    {"pressure_reduced_err", "/pressure/error_reduced"},
    {"pressure_bar", "/pressure/mean_bar"},
    {"pressure_bar_err", "/pressure/error_bar"},
    {"energy_rel_fluct", "/energy/rel_fluct"},
    {"energy_drift_per_ps", "/energy/drift_per_ps"},
    {"collisions_per_ps", "/collisions_per_ps"},
    {"collisions_per_ps_err", "/collisions_per_ps_err"},
    {"diffusion_einstein", "/analysis/diffusion/einstein_angstrom2_per_ps"},
    {"diffusion_einstein_err", "/analysis/diffusion/einstein_err"},
    {"diffusion_green_kubo", "/analysis/diffusion/green_kubo_angstrom2_per_ps"},
    {"diffusion_green_kubo_err", "/analysis/diffusion/green_kubo_err"},
    {"steps_per_ps", "/steps_per_ps"},
    // Costs last: the columns before them are the physics, the same wherever a run ran.
    {"cpu_seconds", "/cpu_seconds"},
    {"cpu_seconds_per_ps", "/cpu_seconds_per_ps"},
    {"collisions_per_cpu_second", "/collisions_per_cpu_second"},
    {"all_events_per_cpu_second", "/all_events_per_cpu_second"},
};

double at(const json& summary, const char* pointer) {
    if (!summary.is_object()) return NAN;
    const json::json_pointer p(pointer);
    return summary.contains(p) && summary.at(p).is_number() ? summary.at(p).get<double>() : NAN;
}

} // namespace

const char* statusName(RunStatus s) {
    switch (s) {
    case RunStatus::Pending:
        return "pending";
    case RunStatus::Ok:
        return "ok";
    case RunStatus::Failed:
        return "failed";
    case RunStatus::Interrupted:
        return "interrupted";
    }
    return "?";
}

bool completeSummary(const json& summary) {
    if (!summary.is_object() || !summary.contains("cpu_seconds")) return false;
    if (summary.value("interrupted", false) || summary.contains("error")) return false;
    return summary.contains("analysis") && summary["analysis"].is_object() &&
           !summary["analysis"].contains("error");
}

RunAction resumeAction(const fs::path& dir, const SweepRun& run, bool retryFailed,
                       SweepEntry& found) {
    const json scene = toJson(run.scene);
    const json failed = readJson(dir / failedFileName);
    if (!retryFailed && failed.is_object() && failed.value("scene", json()) == scene) {
        found = {RunStatus::Failed, failed.value("error", std::string("failed")), nullptr, -1.0,
                 true};
        return RunAction::Skip;
    }
    if (readJson(dir / "scene.json") != scene) return RunAction::Fresh;
    const json summary = readJson(dir / "summary.json");
    if (completeSummary(summary)) {
        found = {RunStatus::Ok, "", summary, -1.0, true};
        return RunAction::Skip;
    }
    std::error_code ec;
    return fs::is_regular_file(dir / "restart.bin", ec) ? RunAction::Continue : RunAction::Fresh;
}

SweepEntry finishedEntry(const fs::path& dir, const SweepRun& run, const ChildExit& exit) {
    SweepEntry e;
    e.summary = readJson(dir / "summary.json");
    if (!exit.signalled && exit.code == 0 && completeSummary(e.summary)) {
        e.status = RunStatus::Ok;
    } else if (!exit.signalled && exit.code > 128 && e.summary.is_object() &&
               e.summary.value("interrupted", false)) {
        e.status = RunStatus::Interrupted;
        e.message = "interrupted by " + e.summary.value("interrupted_by", std::string("a signal"));
    } else {
        e.status = RunStatus::Failed;
        if (exit.signalled)
            e.message =
                "killed by signal " + std::to_string(exit.code) + " (" + strsignal(exit.code) + ")";
        else if (e.summary.is_object() && e.summary.contains("error"))
            e.message = e.summary["error"].get<std::string>();
        else
            e.message = lastLogLine(dir / "run.log");
        if (e.message.empty()) e.message = "exit status " + std::to_string(exit.code);
        // Recorded with the scene it belongs to; the sweep does not try the same run again.
        writeFileAtomically(dir / failedFileName,
                            json{{"scene", toJson(run.scene)}, {"error", e.message}}.dump(2) +
                                "\n");
    }
    return e;
}

std::string sweepTable(const SweepPlan& plan, const std::vector<SweepEntry>& entries) {
    std::string out = "run";
    for (const auto& key : plan.axisKeys)
        out += "," + csvField(key);
    out += ",status";
    for (const auto& c : summaryColumns)
        out += std::string(",") + c.header;
    out += ",wall_seconds,message\n";
    for (std::size_t i = 0; i < plan.runs.size(); ++i) {
        const SweepRun& run = plan.runs[i];
        const SweepEntry& e = entries.at(i);
        out += csvField(run.name);
        for (const auto& key : plan.axisKeys) {
            std::string cell;
            for (const auto& [k, v] : run.overrides)
                if (k == key) cell = valueText(v);
            out += "," + csvField(cell);
        }
        out += std::string(",") + statusName(e.status);
        const bool numbers = e.status == RunStatus::Ok;
        for (const auto& c : summaryColumns)
            out += "," + number(numbers ? at(e.summary, c.pointer) : NAN);
        out += "," + number(e.wallSeconds >= 0.0 ? e.wallSeconds : NAN);
        out += "," + csvField(e.message) + "\n";
    }
    return out;
}

} // namespace terrace::cli
