#include "cli/tradeoff_plan.hpp"
#include "smd/parameters.hpp"
#include <cmath>
#include <cstdio>
#include <set>

namespace terrace::cli {

const char* observableName(Observable o) {
    switch (o) {
    case Observable::U:
        return "u";
    case Observable::P:
        return "p";
    case Observable::D:
        return "d";
    case Observable::G:
        return "g";
    case Observable::GPeak:
        return "g_peak";
    case Observable::TauV:
        return "tau_v";
    case Observable::TauO:
        return "tau_o";
    }
    return "?";
}

const char* observableMeaning(Observable o) {
    switch (o) {
    case Observable::U:
        return "<U>/(N eps)";
    case Observable::P:
        return "P* = P sigma^3/eps";
    case Observable::D:
        return "D, A^2/ps (Einstein)";
    case Observable::G:
        return "RMS of g(r) - g_ref(r), r <= rdf_max";
    case Observable::GPeak:
        return "height of g(r)'s highest peak";
    case Observable::TauV:
        return "integral of the VACF, ps";
    case Observable::TauO:
        return "integral of <s(0).s(t)>, ps";
    }
    return "?";
}

analysis::Tolerance defaultTolerance(Observable o) {
    switch (o) {
    // Half a percent of the cohesive energy: the accuracy asked of a liquid's energy when a
    // force field is fitted, and above what a few ps of a few hundred bodies resolve. Of
    // max(|U|, T*) per body (relativeScaleFloor), so that a gas's U is not asked to a fraction
    // of kT that no one would.
    case Observable::U:
        return {0.005, true};
    // Two percent of the pressure's scale, max(|P|, ρ*T*) (P of a liquid crosses zero, so the
    // ideal-gas term stands in for it there): an equation of state to 2 %.
    case Observable::P:
        return {0.02, true};
    // Three percent: what diffusion coefficients are usually quoted to, finite-size correction
    // apart.
    case Observable::D:
        return {0.03, true};
    // 0.02 in g: below the line width of a plotted g(r), about a percent of its first peak.
    case Observable::G:
        return {0.02, false};
    // One percent of the first peak's height (structure factors and coordination numbers follow
    // it).
    case Observable::GPeak:
        return {0.01, true};
    // Relaxation times to three percent, as D.
    case Observable::TauV:
    case Observable::TauO:
        return {0.03, true};
    }
    return {};
}

double relativeScaleFloor(Observable o, double density, double temperature) {
    switch (o) {
    case Observable::U:
        return temperature;
    case Observable::P:
        return density * temperature;
    default:
        return 0.0;
    }
}

std::pair<Observable, analysis::Tolerance> parseTolerance(const std::string& text) {
    const auto eq = text.find('=');
    const std::string where = "--tolerance " + text;
    if (eq == std::string::npos)
        throw SceneError(where + ": must be OBS=VALUE or OBS=VALUE% (OBS one of u, p, d, g, "
                                 "g_peak, tau_v, tau_o)");
    const std::string name = text.substr(0, eq);
    std::string value = text.substr(eq + 1);
    std::optional<Observable> obs;
    for (const Observable o : allObservables)
        if (name == observableName(o)) obs = o;
    if (!obs)
        throw SceneError(where + ": unknown observable '" + name +
                         "' (one of u, p, d, g, g_peak, tau_v, tau_o)");
    analysis::Tolerance t;
    if (!value.empty() && value.back() == '%') t.relative = true, value.pop_back();
    std::size_t used = 0;
    try {
        t.value = std::stod(value, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != value.size() || !(t.value > 0.0) || !std::isfinite(t.value))
        throw SceneError(where + ": the tolerance must be a positive number, or a percentage "
                                 "like 0.5%");
    if (t.relative) t.value /= 100.0;
    if (*obs == Observable::G && t.relative)
        throw SceneError(where + ": g's tolerance is an absolute RMS deviation of g(r) (e.g. "
                                 "g=0.02), not a percentage");
    return {*obs, t};
}

std::vector<std::string> commaList(const std::string& list) {
    std::vector<std::string> items;
    std::size_t at = 0;
    while (at <= list.size()) {
        const std::size_t comma = std::min(list.find(',', at), list.size());
        items.push_back(list.substr(at, comma - at));
        at = comma + 1;
    }
    return items;
}

bool stepsFitGrid(const Scene& scene, int k) {
    const double steps = scene.run.thermostat_fs * k / scene.run.sample_fs;
    return k >= 1 && std::abs(steps - std::round(steps)) < 1e-9 * steps;
}

std::vector<Observable> parseObservables(const std::string& list) {
    std::vector<Observable> out;
    for (const std::string& name : commaList(list)) {
        bool known = false;
        for (const Observable o : allObservables)
            if (name == observableName(o)) out.push_back(o), known = true;
        if (!known)
            throw SceneError("--observables: unknown observable '" + name +
                             "' (one of u, p, d, g, g_peak, tau_v, tau_o)");
    }
    return out;
}

namespace {

std::string number(double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", x);
    return b;
}

} // namespace

std::string Setting::label() const {
    if (engine == "dmd") return ladder + "-dV" + number(x);
    return ladder + "-dt" + number(x);
}

Setting dmdSetting(const std::string& ladder, double x) {
    Setting s;
    s.engine = "dmd";
    s.ladder = ladder;
    s.x = x;
    // DMD terraces the model SMD integrates (the smoothed cutoff), whatever the scene's own
    // dmd.model: a bare terracing would carry the cutoff's difference into every bias.
    s.overrides = {{"engine", "dmd"}, {"dmd.model", "smoothed"}, {"dmd.dV", x}};
    if (ladder == "dmd-optimal")
        s.overrides.emplace_back(
            "dmd.terraces",
            nlohmann::json{{"levels", "optimal"}, {"values", "boltzmann"}, {"n", 0}});
    return s;
}

Setting smdSetting(const std::string& scheme, double dtFs) {
    Setting s;
    s.engine = "smd";
    s.ladder = "smd-" + scheme;
    s.x = dtFs;
    s.overrides = {{"engine", "smd"}, {"smd.scheme", scheme}, {"smd.dt_fs", dtFs}};
    return s;
}

std::optional<double> knownOrder(const Setting& s) {
    if (s.engine != "smd") return std::nullopt;
    return s.ladder == "smd-yoshida4" ? 4.0 : 2.0;
}

TradeoffLadders tradeoffLadders(const Scene& scene, const TradeoffOptions& options) {
    TradeoffLadders out;
    const double sampleFs = scene.run.sample_fs;
    const double dtScene = smd::readSmdSection(scene.smd).dt_fs;
    const auto fits = [&](int k) { return stepsFitGrid(scene, k); };
    const int kScene = static_cast<int>(std::lround(sampleFs / dtScene));
    out.reference = smdSetting("yoshida4", sampleFs / (2 * kScene));
    out.reference.ladder = "reference";
    std::vector<int> ks;
    for (double k = kScene; k >= 1.0 && sampleFs / k <= 10.0 * dtScene + 1e-12; k /= 1.5) {
        int whole = static_cast<int>(std::floor(k + 1e-9));
        while (whole > 1 && !fits(whole))
            --whole;
        if (whole >= 1 && fits(whole) && (ks.empty() || whole < ks.back())) ks.push_back(whole);
    }
    for (const std::string& scheme : options.schemes) {
        std::vector<Setting> ladder;
        for (const int k : ks)
            ladder.push_back(smdSetting(scheme, sampleFs / k));
        out.ladders.push_back(std::move(ladder)); // smallest dt first: the most accurate
    }
    for (const std::string& name : options.designs) {
        const std::string design = "dmd-" + name;
        std::vector<Setting> ladder;
        std::set<double, std::greater<>> dVs(options.dVs.begin(), options.dVs.end());
        for (auto it = dVs.rbegin(); it != dVs.rend(); ++it) // smallest ΔV first
            ladder.push_back(dmdSetting(design, *it));
        out.ladders.push_back(std::move(ladder));
    }
    return out;
}

double lawCrossing(const std::vector<double>& x, const std::vector<LadderBiases>& observables,
                   std::optional<double> order) {
    double crossing = std::numeric_limits<double>::infinity();
    for (const LadderBiases& o : observables) {
        const auto law = analysis::fitPowerLaw(x, o.bias, order);
        if (!law.ok) continue;
        const double at = analysis::settingAtTolerance(law, o.tolerance).value;
        if (std::isfinite(at)) crossing = std::min(crossing, at);
    }
    return crossing;
}

std::optional<double> extensionBelow(double front, double crossing) {
    if (!(crossing < front)) return std::nullopt;
    const double x = crossing * extrapolationMargin;
    if (!(x >= front * extrapolationReach)) return std::nullopt;
    return x;
}

} // namespace terrace::cli
