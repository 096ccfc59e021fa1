#include "core/scene_units.hpp"
#include "core/scene_json.hpp"
#include <algorithm>
#include <array>
#include <utility>

namespace terrace {

using nlohmann::json;

UnitSystem unitSystem(const Scene& s) {
    if (s.units != "lj") return UnitSystem::real();
    return UnitSystem::lj(s.potential.sigma, s.potential.epsilon, s.body.mass);
}

const std::vector<UnitTwin>& unitTwins() {
    static const std::vector<UnitTwin> twins{
        {"run", "equilibrate_ps", "equilibrate", Dimension::TimePs},
        {"run", "time_ps", "time", Dimension::TimePs},
        {"run", "sample_fs", "sample", Dimension::TimeFs},
        {"run", "thermostat_fs", "thermostat", Dimension::TimeFs},
        {"output", "trajectory_every_fs", "trajectory_every", Dimension::TimeFs},
        {"output", "restart_every_ps", "restart_every", Dimension::TimePs},
        {"output", "thermo_every_fs", "thermo_every", Dimension::TimeFs},
        {"analysis", "max_lag_ps", "max_lag", Dimension::TimePs},
        {"analysis", "rdf_bin_angstrom", "rdf_bin", Dimension::Length},
        {"smd", "dt_fs", "dt", Dimension::TimeFs},
        {"dmd", "horizon_fs", "horizon", Dimension::TimeFs},
    };
    return twins;
}

namespace {

/// The keys without a unit in their names that carry one: read in the scene's units.
struct FreeKey {
    const char* section;
    const char* key;
    Dimension dimension;
};
constexpr std::array<FreeKey, 2> freeKeys{{
    {"dmd", "levels", Dimension::Energy},
    {"dmd", "values", Dimension::Energy},
}};
constexpr std::array<std::pair<const char*, Dimension>, 3> particleKeys{{
    {"r", Dimension::Length},
    {"v", Dimension::Velocity},
    {"omega", Dimension::AngularVelocity},
}};

/// A number, or each number of an array, converted by `f`; anything else left as it is.
template <class F> void convert(json& value, Dimension d, const F& f) {
    if (value.is_number())
        value = f(value.get<double>(), d);
    else if (value.is_array())
        for (auto& x : value)
            if (x.is_number()) x = f(x.get<double>(), d);
}

/// The object under `key` of `j`, or null when there is none.
json* objectAt(json& j, const char* key) {
    if (!j.is_object()) return nullptr;
    auto it = j.find(key);
    return it != j.end() && it->is_object() ? &*it : nullptr;
}

template <class F> void convertFreeKeys(json& scene, const F& f) {
    for (const auto& k : freeKeys)
        if (json* section = objectAt(scene, k.section))
            if (auto value = section->find(k.key); value != section->end())
                convert(*value, k.dimension, f);
    json* state = objectAt(scene, "state");
    if (!state) return;
    auto particles = state->find("particles");
    if (particles == state->end() || !particles->is_array()) return;
    for (auto& p : *particles) {
        if (!p.is_object()) continue;
        for (const auto& [key, d] : particleKeys)
            if (auto value = p.find(key); value != p.end()) convert(*value, d, f);
    }
}

} // namespace

void keepOverriddenTwins(json& scene, const std::vector<std::string>& overriddenKeys) {
    auto overridden = [&](const std::string& key) {
        return std::find(overriddenKeys.begin(), overriddenKeys.end(), key) != overriddenKeys.end();
    };
    for (const auto& t : unitTwins()) {
        json* section = objectAt(scene, t.section);
        if (!section || !section->contains(t.named) || !section->contains(t.free)) continue;
        const std::string prefix = std::string(t.section) + ".";
        const bool named = overridden(prefix + t.named), free = overridden(prefix + t.free);
        if (named != free) section->erase(named ? t.free : t.named);
    }
}

void sceneKeysToReal(json& scene, const UnitSystem& u, const std::string& origin) {
    if (!u.reduced()) return; // the twins are unknown keys to the readers
    for (const auto& t : unitTwins()) {
        json* section = objectAt(scene, t.section);
        if (!section || !section->contains(t.free)) continue;
        const JsonSection at(*section, t.section, origin);
        if (section->contains(t.named))
            at.fail(t.free, "and " + at.name(t.named) + " set the same value: give one of them");
        json value = (*section)[t.free];
        convert(value, t.dimension, [&](double x, Dimension d) { return u.toReal(x, d); });
        (*section)[t.named] = std::move(value); // a wrong type is the reader's to refuse
        section->erase(t.free);
    }
    if (u.reduced()) convertFreeKeys(scene, [&](double x, Dimension d) { return u.toReal(x, d); });
}

void sceneKeysFromReal(json& scene, const UnitSystem& u) {
    if (u.reduced())
        convertFreeKeys(scene, [&](double x, Dimension d) { return u.fromReal(x, d); });
}

std::string reducedNote(const UnitSystem& u) {
    return " (units lj: τ = " + showNumber(u.tauFs()) + " fs, σ = " + showNumber(u.sigma()) +
           " Å, ε = " + showNumber(u.epsilon()) +
           " kJ/mol; unit-free keys are quoted converted to the keys named in real units)";
}

} // namespace terrace
