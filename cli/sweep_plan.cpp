#include "cli/sweep_plan.hpp"
#include "cli/engine_keys.hpp"
#include "cli/output_dir.hpp"
#include "cli/scene_check.hpp"
#include "core/output_file.hpp"
#include "core/scene_json.hpp"
#include "core/suggest.hpp"
#include "core/utf8.hpp"
#include <algorithm>
#include <map>
#include <set>

namespace terrace::cli {

namespace {

using ordered = nlohmann::ordered_json;
using nlohmann::json;

/// Directory names stay well inside the 255 bytes a file name may take.
constexpr std::size_t maxRunNameLength = 200;

/// One value of one axis: the overrides it sets and, if the axis has labels, its label.
struct AxisValue {
    std::vector<Override> overrides;
    std::string label;
};

class SweepReader {
public:
    explicit SweepReader(std::string origin) : origin_(std::move(origin)) {}

    [[noreturn]] void fail(const std::string& where, const std::string& what) const {
        throw SceneError(origin_ + ": " + where + ": " + what);
    }

    static json plain(const ordered& v) { return json::parse(v.dump()); }

    void checkKey(const std::string& key, const std::string& where) const {
        if (key.empty() || key.front() == '.' || key.back() == '.' ||
            key.find("..") != std::string::npos)
            fail(where, "'" + key + "' is not a dotted scene key");
    }

    std::vector<AxisValue> axis(const ordered& a, const std::string& where) const {
        if (!a.is_object() || a.empty())
            fail(where, "an axis must be an object of key: [values], or {\"cases\": [...]}");
        std::vector<AxisValue> values;
        if (a.contains("cases")) {
            for (const auto& [k, v] : a.items())
                if (k != "cases" && k != "labels")
                    fail(where + "." + k, "an axis with cases takes no other key but labels");
            const auto& cases = a["cases"];
            if (!cases.is_array() || cases.empty())
                fail(where + ".cases", "must be a non-empty list of objects of overrides");
            for (std::size_t c = 0; c < cases.size(); ++c) {
                const std::string at = where + ".cases[" + std::to_string(c) + "]";
                if (!cases[c].is_object() || cases[c].empty())
                    fail(at, "must be a non-empty object of key: value overrides");
                AxisValue value;
                for (const auto& [k, v] : cases[c].items()) {
                    checkKey(k, at);
                    value.overrides.emplace_back(k, plain(v));
                }
                values.push_back(std::move(value));
            }
        } else {
            std::size_t length = 0;
            bool first = true;
            for (const auto& [k, v] : a.items()) {
                if (k == "labels") continue;
                checkKey(k, where);
                if (!v.is_array() || v.empty())
                    fail(where + "." + k, "must be a non-empty list of values");
                if (first) length = v.size(), values.resize(length);
                if (v.size() != length)
                    fail(where + "." + k,
                         "zipped keys need lists of one length: " + std::to_string(v.size()) +
                             " values against " + std::to_string(length));
                first = false;
                for (std::size_t i = 0; i < length; ++i)
                    values[i].overrides.emplace_back(k, plain(v[i]));
            }
            if (first) fail(where, "an axis needs at least one key");
        }
        if (a.contains("labels")) {
            const auto& labels = a["labels"];
            if (!labels.is_array() || labels.size() != values.size())
                fail(where + ".labels", "must be a list of " + std::to_string(values.size()) +
                                            " strings, one per value");
            std::set<std::string> seen;
            for (std::size_t i = 0; i < values.size(); ++i) {
                if (!labels[i].is_string() || labels[i].get<std::string>().empty())
                    fail(where + ".labels", "must be non-empty strings");
                values[i].label = labels[i].get<std::string>();
                if (!seen.insert(values[i].label).second)
                    fail(where + ".labels", "'" + values[i].label + "' is given twice");
            }
        }
        return values;
    }

private:
    std::string origin_;
};

std::string lastComponent(const std::string& key) {
    const auto dot = key.rfind('.');
    return dot == std::string::npos ? key : key.substr(dot + 1);
}

/// "key-value"; an object value (e.g. dmd.terraces) names itself by its own keys instead,
/// {"levels": "optimal", "n": 3} as levels-optimal_n-3.
std::string namePart(const std::string& key, const json& value) {
    if (!value.is_object() || value.empty()) return key + "-" + valueText(value);
    std::string part;
    for (const auto& [k, v] : value.items())
        part += (part.empty() ? "" : "_") + namePart(k, v);
    return part;
}

/// The common keys ("set", --set) of an engine that no run of the sweep has, one note each.
std::vector<std::string> ignoredCommonKeys(const SweepPlan& plan, const std::string& origin) {
    std::set<std::string> engines;
    for (const SweepRun& run : plan.runs)
        engines.insert(run.scene.engine);
    std::vector<std::string> notes;
    for (const Override& o : plan.common) {
        const std::string owner = engineOfKey(o.first);
        if (owner.empty() || engines.count(owner)) continue;
        notes.push_back(ignoredKeyNote(origin + ": " + overrideArgument(o) + " (for every run)",
                                       owner, "every run's engine, " + *engines.begin() + ","));
    }
    return notes;
}

/// An axis's keys of one engine's section on runs of the other, when the axis's value meant
/// them for that run: a value that also sets the run's engine (a case {"engine": "dmd",
/// "smd.dt_fs": 0.45}), or one of keys the run reads none of (a product of an engine axis and an
/// smd.dt_fs axis: the DMD runs along it repeat one another). A value that also sets a key the
/// run reads (smd.skin zipped with state.density, for runs of both engines) is meant for the
/// other engine's runs, and passes. Collected run by run, noted once a key.
class IgnoredAxisKeys {
public:
    void look(const AxisValue& value, const SweepRun& run) {
        const std::string& engine = run.scene.engine;
        bool setsEngine = false, readsAny = false;
        for (const auto& [key, v] : value.overrides) {
            setsEngine = setsEngine || key == "engine";
            const std::string owner = engineOfKey(key);
            readsAny = readsAny || owner.empty() || owner == engine;
        }
        if (!setsEngine && readsAny) return;
        for (const auto& [key, v] : value.overrides) {
            const std::string owner = engineOfKey(key);
            if (owner.empty() || owner == engine) continue;
            // By name: clang 14 cannot capture a structured binding.
            auto at = std::find_if(byKey_.begin(), byKey_.end(),
                                   [&name = key](const auto& k) { return k.key == name; });
            if (at == byKey_.end()) at = byKey_.insert(byKey_.end(), {key, engine, run.name, 0});
            ++at->runs;
        }
    }

    std::vector<std::string> notes(const std::string& origin) const {
        std::vector<std::string> out;
        for (const Ignored& k : byKey_)
            out.push_back(ignoredKeyNote(origin + ": axes set " + k.key + " for " +
                                             std::to_string(k.runs) + " run" +
                                             (k.runs == 1 ? "" : "s") + " of engine " + k.engine +
                                             " (first: " + k.firstRun + ")",
                                         engineOfKey(k.key), "their engine, " + k.engine + ","));
        return out;
    }

private:
    struct Ignored {
        std::string key, engine, firstRun;
        int runs;
    };
    std::vector<Ignored> byKey_; // in order of first appearance
};

} // namespace

void refuseIgnoredKeys(const SweepPlan& plan) {
    if (!plan.ignoredKeys.empty()) throw SceneError(asRefusal(plan.ignoredKeys.front()));
}

std::string valueText(const json& value) {
    return value.is_string() ? value.get<std::string>() : value.dump();
}

std::string overrideArgument(const Override& o) {
    return o.first + "=" + o.second.dump();
}

SweepPlan sweepFromJson(const std::string& text, const std::string& origin,
                        const std::filesystem::path& baseDir,
                        const std::vector<std::string>& extraSets) {
    const SweepReader rd(origin);
    if (const auto bad = firstInvalidUtf8(text); bad != std::string::npos)
        rd.fail(placeOfByte(text, bad), "not UTF-8 text: a sweep file is JSON, which is UTF-8");
    // As in a scene: a repeated key would otherwise be silently last-wins.
    const std::string duplicate = firstDuplicateKey(text);
    if (!duplicate.empty()) rd.fail(duplicate, "duplicate key");
    const ordered file = ordered::parse(text, nullptr, false);
    if (file.is_discarded()) rd.fail("<top>", "not valid JSON");
    if (!file.is_object()) rd.fail("<top>", "a sweep must be a JSON object");
    const std::vector<std::string> sweepKeys = {"scene", "set", "axes", "seeds"};
    for (const auto& [k, v] : file.items())
        if (std::find(sweepKeys.begin(), sweepKeys.end(), k) == sweepKeys.end()) {
            const std::string near = nearestName(k, sweepKeys);
            rd.fail(k, "unknown key" + (near.empty() ? "" : "; did you mean " + near + "?") +
                           " (a sweep has scene, set, axes and seeds)");
        }

    SweepPlan plan;
    plan.origin = origin;
    if (file.contains("scene")) {
        if (!file["scene"].is_string() || file["scene"].get<std::string>().empty())
            rd.fail("scene", "must be the path of a scene file");
        const std::filesystem::path p = file["scene"].get<std::string>();
        plan.scenePath = p.is_absolute() ? p : baseDir / p;
    }
    if (file.contains("set")) {
        if (!file["set"].is_object()) rd.fail("set", "must be an object of key: value overrides");
        for (const auto& [k, v] : file["set"].items()) {
            rd.checkKey(k, "set");
            plan.common.emplace_back(k, SweepReader::plain(v));
        }
    }
    for (const auto& s : extraSets) { // the same rules as terrace run --set
        if (const auto bad = firstInvalidUtf8(s); bad != std::string::npos)
            rd.fail("--set " + printableBytes(s), utf8Problem(s, bad));
        auto parsed = parseOverride(s);
        if (!parsed) rd.fail("--set " + s, "expected key.path=value");
        rd.checkKey(parsed->first, "--set");
        plan.common.push_back(std::move(*parsed));
    }

    std::vector<std::vector<AxisValue>> axes;
    if (file.contains("axes")) {
        if (!file["axes"].is_array()) rd.fail("axes", "must be a list of axes");
        for (std::size_t a = 0; a < file["axes"].size(); ++a)
            axes.push_back(rd.axis(file["axes"][a], "axes[" + std::to_string(a) + "]"));
    }
    if (file.contains("seeds")) {
        const auto& seeds = file["seeds"];
        if (!seeds.is_array() || seeds.empty()) rd.fail("seeds", "must be a non-empty list");
        std::vector<AxisValue> values;
        for (const auto& s : seeds) {
            if (!s.is_number_integer()) rd.fail("seeds", "must be integers, got " + s.dump());
            values.push_back({{{"seed", SweepReader::plain(s)}}, ""});
        }
        axes.push_back(std::move(values));
    }

    // Short names: a key's last component, unless two of the sweep's keys share it.
    std::map<std::string, std::set<std::string>> byComponent;
    for (const auto& axis : axes)
        for (const auto& value : axis)
            for (const auto& [key, v] : value.overrides) {
                byComponent[lastComponent(key)].insert(key);
                if (std::find(plan.axisKeys.begin(), plan.axisKeys.end(), key) ==
                    plan.axisKeys.end())
                    plan.axisKeys.push_back(key);
            }
    auto shortKey = [&](const std::string& key) {
        return byComponent[lastComponent(key)].size() > 1 ? key : lastComponent(key);
    };

    IgnoredAxisKeys ignoredAxisKeys;
    // The product of the axes, the last fastest (an odometer over the axes' indices).
    std::vector<std::size_t> index(axes.size(), 0);
    std::set<std::string> names;
    std::vector<std::string> commonSets;
    for (const auto& o : plan.common)
        commonSets.push_back(overrideArgument(o));
    while (true) {
        SweepRun run;
        for (std::size_t a = 0; a < axes.size(); ++a) {
            const AxisValue& value = axes[a][index[a]];
            std::string part = value.label;
            for (const auto& o : value.overrides) {
                run.overrides.push_back(o);
                if (value.label.empty())
                    part += (part.empty() ? "" : "_") + namePart(shortKey(o.first), o.second);
            }
            run.name += (run.name.empty() ? "" : "_") + part;
        }
        if (run.name.empty()) run.name = "run";
        run.name = sanitisedName(run.name);
        if (run.name.size() > maxRunNameLength)
            rd.fail("axes", "run name '" + run.name.substr(0, 60) +
                                "...' is too long for a directory: give the axes labels");
        if (!names.insert(run.name).second)
            rd.fail("axes", "two runs are both named '" + run.name +
                                "' (a value given twice, or labels that collide)");
        std::vector<std::string> sets = commonSets;
        for (const auto& o : run.overrides)
            sets.push_back(overrideArgument(o));
        try {
            const std::string origin =
                plan.scenePath.empty() ? "<built-in default scene>" : plan.scenePath.string();
            // The built-in scene as `terrace run` reads it (cli/run_command.cpp): no key at all.
            run.scene = plan.scenePath.empty() ? sceneFromJson(json::object(), origin, sets)
                                               : loadScene(plan.scenePath.string(), sets);
            resolveEngineSections(run.scene, origin); // as `terrace run` will: fail now, not then
        } catch (const SceneError& e) {
            rd.fail("run " + run.name, e.what());
        }
        for (std::size_t a = 0; a < axes.size(); ++a)
            ignoredAxisKeys.look(axes[a][index[a]], run);
        plan.runs.push_back(std::move(run));

        std::size_t a = axes.size();
        while (a > 0 && ++index[a - 1] == axes[a - 1].size())
            index[--a] = 0;
        if (a == 0) break;
    }
    plan.ignoredKeys = ignoredCommonKeys(plan, origin);
    for (std::string& note : ignoredAxisKeys.notes(origin))
        plan.ignoredKeys.push_back(std::move(note));
    return plan;
}

SweepPlan loadSweep(const std::filesystem::path& file, const std::vector<std::string>& extraSets) {
    std::string text;
    try {
        text = readWholeFile(file);
    } catch (const IoError& e) {
        throw SceneError(e.what());
    }
    return sweepFromJson(text, file.string(), file.parent_path(), extraSets);
}

} // namespace terrace::cli
