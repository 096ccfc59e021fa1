#include "experiments/tools/summaries.hpp"
#include "core/units.hpp"
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

namespace terrace::experiments {
namespace {

struct Quantity {
    const char* column;
    double (*read)(const nlohmann::json&);
};

double number(const nlohmann::json& j, const char* key) {
    return j.contains(key) && j[key].is_number() ? j[key].get<double>() : 0.0;
}

const Quantity quantities[] = {
    {"cpu_s_per_ps", [](const nlohmann::json& s) { return number(s, "cpu_seconds_per_ps"); }},
    {"collisions_per_ps", [](const nlohmann::json& s) { return number(s, "collisions_per_ps"); }},
    {"events_per_ps",
     [](const nlohmann::json& s) {
         const double ps = number(s, "simulated_ps");
         return s.contains("events") && ps > 0 ? number(s["events"], "total") / ps : 0.0;
     }},
    {"energy_rel_fluct", [](const nlohmann::json& s) { return number(s["energy"], "rel_fluct"); }},
    {"energy_drift_per_ps",
     [](const nlohmann::json& s) { return number(s["energy"], "drift_per_ps"); }},
    {"temperature_K", [](const nlohmann::json& s) { return number(s, "temperature_K"); }},
};

/// The value at a dotted key ("energy.drift_per_ps"), or null where the path does not exist.
const nlohmann::json* dotted(const nlohmann::json& j, const std::string& key) {
    const nlohmann::json* v = &j;
    std::stringstream path(key);
    for (std::string part; v && std::getline(path, part, '.');)
        v = v->is_object() && v->contains(part) ? &(*v)[part] : nullptr;
    return v;
}

nlohmann::json readSummary(const std::filesystem::path& dir) {
    std::ifstream in(dir / "summary.json");
    if (!in) throw std::runtime_error(dir.string() + ": no summary.json (did the run fail?)");
    nlohmann::json s;
    try {
        in >> s;
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(dir.string() + "/summary.json: " + e.what());
    }
    if (!s.contains("energy") || !s.contains("engine"))
        throw std::runtime_error(dir.string() + "/summary.json: not a run summary");
    return s;
}

} // namespace

std::string summaryHeader() {
    std::string h = "label,engine,runs,simulated_ps";
    for (const auto& q : quantities)
        h += std::string(",") + q.column + "," + q.column + "_err";
    return h;
}

std::string summaryRow(const std::string& label, const std::vector<std::filesystem::path>& dirs) {
    if (dirs.empty()) throw std::runtime_error(label + ": no runs given");
    std::vector<nlohmann::json> runs;
    for (const auto& d : dirs)
        runs.push_back(readSummary(d));
    const double R = double(runs.size());
    std::ostringstream row;
    row.precision(6);
    double ps = 0.0;
    for (const auto& s : runs)
        ps += number(s, "simulated_ps") / R;
    row << label << ',' << runs.front()["engine"].get<std::string>() << ',' << runs.size() << ','
        << ps;
    for (const auto& q : quantities) {
        double sum = 0.0, ss = 0.0;
        for (const auto& s : runs)
            sum += q.read(s);
        const double mean = sum / R;
        for (const auto& s : runs)
            ss += (q.read(s) - mean) * (q.read(s) - mean);
        // One run has no spread to estimate: its error is unknown, written as nan, never 0.
        const double err = runs.size() > 1 ? std::sqrt(ss / (R * (R - 1.0))) : NAN;
        row << ',' << mean << ',' << err;
    }
    return row.str();
}

SummaryScale summaryScale(const std::string& name) {
    if (name == "total") return SummaryScale::total;
    if (name == "per-body") return SummaryScale::perBody;
    if (name == "abs-per-nkt") return SummaryScale::magnitudePerNkT;
    throw std::invalid_argument("unknown scale '" + name + "' (total, per-body or abs-per-nkt)");
}

double replicaValue(const std::filesystem::path& dir, const std::string& key, SummaryScale scale) {
    const nlohmann::json s = readSummary(dir);
    const nlohmann::json* v = dotted(s, key);
    if (!v || !v->is_number()) return NAN;
    const double x = v->get<double>(), n = number(s, "n_bodies");
    switch (scale) {
    case SummaryScale::total:
        return x;
    case SummaryScale::perBody:
        return x / n;
    case SummaryScale::magnitudePerNkT:
        return std::abs(x) / (n * units::kB * number(s, "temperature_target_K"));
    }
    return NAN;
}

std::string jsonValues(const std::filesystem::path& file, const std::vector<std::string>& keys) {
    std::ifstream in(file);
    if (!in) throw std::runtime_error(file.string() + ": cannot read");
    nlohmann::json j;
    in >> j;
    std::ostringstream out;
    out.precision(8);
    for (std::size_t k = 0; k < keys.size(); ++k) {
        const nlohmann::json* v = dotted(j, keys[k]);
        if (k > 0) out << ',';
        if (v && v->is_boolean())
            out << (v->get<bool>() ? 1 : 0);
        else if (v && v->is_number())
            out << v->get<double>();
        else
            out << "nan";
    }
    return out.str();
}

} // namespace terrace::experiments
