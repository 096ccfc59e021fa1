// The scene as a whole: the top level's keys, the overrides and the order in which each section's
// reader (core/scene_sections.hpp) sees the sections it depends on; the file it comes from, and
// the resolved scene written back. The first problem found is reported as
// "<origin>: <dotted.key>: <problem>".
#include "core/scene.hpp"
#include "core/initial_state.hpp"
#include "core/scene_json.hpp"
#include "core/scene_sections.hpp"
#include "core/scene_units.hpp"
#include "core/thermo_interval.hpp"
#include "core/utf8.hpp"
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace terrace {

using nlohmann::json;

double Scene::boxLength() const {
    const int count = state.particles.empty() ? state.n : static_cast<int>(state.particles.size());
    return std::cbrt(count / state.density) * potential.sigma;
}

std::optional<std::pair<std::string, json>> parseOverride(const std::string& assignment) {
    const auto eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0) return std::nullopt;
    const std::string text = assignment.substr(eq + 1);
    json value = json::parse(text, nullptr, false);
    if (value.is_discarded()) value = text; // not JSON: a bare string such as smd or heap
    return std::make_pair(assignment.substr(0, eq), std::move(value));
}

Scene defaultScene() {
    Scene s;
    // As a scene file without the key resolves (core/scene_run.cpp readOutput).
    s.output.thermo_every_fs = defaultThermoEveryFs(s.run.time_ps, s.run.sample_fs);
    return s;
}

Scene sceneFromJson(const json& input, const std::string& origin,
                    const std::vector<std::string>& overrides) {
    json j = input;
    const JsonSection top(j, "", origin);
    if (!j.is_object()) top.refuse("<top>", "a scene must be a JSON object");
    std::vector<std::string> overridden;
    for (const auto& o : overrides) {
        applyOverride(j, o, origin);
        if (const auto parsed = parseOverride(o)) overridden.push_back(parsed->first);
    }
    top.onlyKeys({"name", "seed", "units", "body", "potential", "species", "state", "engine", "dmd",
                  "smd", "run", "output", "analysis"});
    Scene s;
    detail::readIdentity(top, s);
    s.units = top.choice("units", s.units, {"real", "lj"});
    if (s.units == "lj") keepOverriddenTwins(j, overridden); // --set run.time replaces time_ps
    const JsonSection body = top.section("body");
    detail::readBody(body, s);
    detail::readPotential(top.section("potential"), s);
    if (s.potential.kind == "sites")
        detail::readSites(body, s);
    else if (body.has("sites"))
        body.fail("sites", "only meaningful for potential.kind sites");
    detail::checkInertia(body, s);
    detail::readSpecies(top, s);
    // The model now gives the scale: every later key is converted to real units before its
    // reader sees it, so readers and engines never meet reduced numbers.
    const UnitSystem u = unitSystem(s);
    sceneKeysToReal(j, u, origin);
    try {
        detail::readState(top.section("state"), s);
        detail::checkRepresentable(top, s);
        s.engine = top.choice("engine", s.engine, {"dmd", "smd"});
        s.dmd = top.section("dmd").object(); // read by dmd/section.hpp
        s.smd = top.section("smd").object(); // read by smd/parameters.hpp
        detail::readRun(top.section("run"), s);
        detail::readOutput(top.section("output"), s);
        detail::readAnalysis(top.section("analysis"), s);
    } catch (const SceneError& e) {
        if (!u.reduced()) throw;
        throw SceneError(std::string(e.what()) + reducedNote(u)); // its numbers are converted
    }
    // A step's force is an impulse at one radius: there is nothing for a time step to integrate,
    // and no continuous potential the table stands for to integrate instead.
    if (s.potential.kind == "steps" && s.engine == "smd")
        top.fail("engine", "smd cannot integrate potential.kind steps (a step table's forces are "
                           "impulses at its radii): use engine dmd");
    return s;
}

Scene loadScene(const std::string& path, const std::vector<std::string>& overrides) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw SceneError(path + ": is a directory, not a scene file");
    errno = 0;
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw SceneError(
            path + ": cannot open the scene file: " + std::strerror(errno != 0 ? errno : ENOENT));
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad() || text.bad())
        throw SceneError(path + ": cannot read the scene file: " + std::strerror(errno));
    const std::string content = text.str();
    if (const auto bad = firstInvalidUtf8(content); bad != std::string::npos)
        throw SceneError(path + ": not UTF-8 text (" + placeOfByte(content, bad) +
                         "): a scene file is JSON, which is UTF-8");
    const std::string duplicate = firstDuplicateKey(content);
    if (!duplicate.empty()) throw SceneError(path + ": " + duplicate + ": duplicate key");
    json j = json::parse(content, nullptr, false);
    if (j.is_discarded()) throw SceneError(path + ": not valid JSON");
    return sceneFromJson(j, path, overrides);
}

json toJson(const Scene& s) {
    auto v3 = [](const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); };
    json j;
    j["name"] = s.name;
    j["seed"] = s.seed;
    if (s.units != "real") j["units"] = s.units; // absent under real: scene.json as it was
    j["body"] = {{"kind", s.body.kind}, {"mass", s.body.mass}, {"inertia", v3(s.body.inertia)}};
    j["potential"] = {
        {"kind", s.potential.kind}, {"epsilon", s.potential.epsilon}, {"sigma", s.potential.sigma}};
    if (s.potential.kind == "rod-lj") j["potential"]["zeta"] = s.potential.zeta;
    if (s.potential.kind == "gay-berne") {
        j["potential"]["kappa"] = s.potential.kappa;
        j["potential"]["kappa_prime"] = s.potential.kappa_prime;
        j["potential"]["mu"] = s.potential.mu;
        j["potential"]["nu"] = s.potential.nu;
    }
    if (!s.body.sites.empty()) {
        json list = json::array();
        for (const auto& site : s.body.sites)
            list.push_back({{"r", v3(site.r)},
                            {"mass", site.mass},
                            {"epsilon", site.epsilon},
                            {"sigma", site.sigma}});
        j["body"]["sites"] = list;
    }
    if (s.potential.kind == "steps") {
        json table = json::array();
        for (std::size_t k = 0; k < s.potential.step_radii.size(); ++k)
            table.push_back(json::array({s.potential.step_radii[k], s.potential.step_energies[k]}));
        j["potential"]["steps"] = table;
        j["potential"]["hard_core"] = s.potential.hard_core;
    } else {
        j["potential"]["cutoff"] = json::array({s.potential.r_l, s.potential.r_u});
        // Written only where set: every other scene resolves to the same bytes as before.
        if (s.potential.cutoff_per_pair) j["potential"]["cutoff_per_pair"] = true;
    }
    // Written only for a mixture: any other scene resolves to the same bytes as before.
    if (!s.species.empty()) {
        json list = json::array();
        for (const auto& x : s.species) {
            list.push_back({{"name", x.name},
                            {"fraction", x.fraction},
                            {"epsilon", x.epsilon},
                            {"sigma", x.sigma},
                            {"mass", x.mass}});
            if (x.kind.empty()) continue; // a mixture of spheres: as before
            list.back()["kind"] = x.kind;
            if (x.kind != "sphere") list.back()["inertia"] = x.inertia;
        }
        j["species"] = list;
        json pairs = json::array();
        for (const auto& x : s.potential.pairs)
            pairs.push_back({{"between", json::array({x.first, x.second})},
                             {"epsilon", x.epsilon},
                             {"sigma", x.sigma}});
        j["potential"]["pairs"] = pairs;
    }
    j["state"] = {
        {"n", s.state.n}, {"density", s.state.density}, {"temperature", s.state.temperature}};
    if (s.state.particles.empty()) {
        j["state"]["orientations"] = s.state.orientations;
        // Written only when not the simple cubic: a scene that does not name its lattice
        // resolves to the same bytes as before the key existed (scene.json, its checksum).
        if (s.state.lattice != "sc") j["state"]["lattice"] = s.state.lattice;
        j["state"]["lattice_aspect"] = s.state.lattice_aspect;
    }
    if (!s.state.particles.empty()) {
        json list = json::array();
        for (const auto& p : s.state.particles) {
            json e = {{"r", v3(p.r)}, {"v", v3(p.v)}};
            if (s.body.kind != "sphere") { // a sphere has neither
                e["omega"] = v3(p.omega);
                e["axis"] = v3(p.axis);
            }
            if (p.orientation) {
                const auto& q = *p.orientation;
                e["orientation"] = json::array({q.w(), q.x(), q.y(), q.z()});
            }
            if (p.species >= 0) e["species"] = s.species[p.species].name;
            list.push_back(e);
        }
        j["state"]["particles"] = list;
    }
    j["engine"] = s.engine;
    j["dmd"] = s.dmd;
    j["smd"] = s.smd;
    j["run"] = {{"equilibrate_ps", s.run.equilibrate_ps},
                {"time_ps", s.run.time_ps},
                {"sample_fs", s.run.sample_fs},
                {"thermostat_fs", s.run.thermostat_fs}};
    // Written only when set: a scene without a bath resolves to the same bytes as before it
    // existed (scene.json, its checksum, the provenance).
    if (s.run.heat_bath.kind == "andersen")
        j["run"]["heat_bath"] = {{"kind", "andersen"},
                                 {"rate_per_ps", s.run.heat_bath.rate_per_ps}};
    else if (s.run.heat_bath.kind == "csvr")
        j["run"]["heat_bath"] = {{"kind", "csvr"}, {"tau_fs", s.run.heat_bath.tau_fs}};
    j["output"] = {{"trajectory_every_fs", s.output.trajectory_every_fs},
                   {"trajectory_format", s.output.trajectory_format},
                   {"restart_every_ps", s.output.restart_every_ps},
                   {"thermo_every_fs", s.output.thermo_every_fs}};
    j["analysis"] = {{"blocks", s.analysis.blocks},
                     {"max_lag_ps", s.analysis.max_lag_ps},
                     {"rdf_max", s.analysis.rdf_max},
                     {"rdf_bin_angstrom", s.analysis.rdf_bin_angstrom},
                     {"rdf_every", s.analysis.rdf_every},
                     {"follow_bodies", s.analysis.follow_bodies},
                     {"lags_per_level", s.analysis.lags_per_level}};
    sceneKeysFromReal(j, unitSystem(s));
    return j;
}

std::vector<std::string> sceneWarnings(const Scene& s) {
    return s.warnings;
}

RodPotential rodPotential(const Scene& s) {
    return RodPotential{s.potential.epsilon, s.potential.sigma, s.potential.zeta};
}
LJPotential ljPotential(const Scene& s) {
    return LJPotential{s.potential.epsilon, s.potential.sigma};
}
GayBernePotential gayBernePotential(const Scene& s) {
    GayBernePotential p;
    p.epsilon = s.potential.epsilon;
    p.sigma = s.potential.sigma;
    p.kappa = s.potential.kappa;
    p.kappaPrime = s.potential.kappa_prime;
    p.mu = s.potential.mu;
    p.nu = s.potential.nu;
    return p;
}
std::vector<Site> sceneSites(const Scene& s) {
    std::vector<Site> sites;
    for (const auto& x : s.body.sites)
        sites.push_back(Site{x.r, x.epsilon, x.sigma, x.mass});
    return sites;
}
StepPotential stepPotential(const Scene& s) {
    StepPotential p;
    p.epsilon = s.potential.epsilon;
    p.sigma = s.potential.sigma;
    p.table = StepTable{s.potential.step_radii, s.potential.step_energies, s.potential.hard_core};
    return p;
}
double sceneMinimumEnergy(const Scene& s) {
    if (s.potential.kind == "steps")
        return stepPotential(s).table.minimumEnergy() * s.potential.epsilon;
    if (s.potential.kind == "lj")
        return s.species.empty() ? ljPotential(s).minimumEnergy() : ljMixture(s).minimumEnergy();
    if (s.potential.kind == "gay-berne") return gayBernePotential(s).minimumEnergy();
    if (s.potential.kind == "sites")
        return SitePotential<AttitudeUse::Frame>::fromSites(sceneSites(s)).minimumEnergy();
    if (!s.species.empty()) return rodMixture(s).minimumEnergy();
    return rodPotential(s).minimumEnergy();
}
SmoothedCutoff sceneCutoff(const Scene& s) {
    if (s.potential.cutoff_per_pair && !s.species.empty()) {
        // The envelope of the pairs' own switches (core/smoothed_potential.hpp).
        const LJMixture m = ljMixture(s);
        double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
        for (int a = 0; a < m.species; ++a)
            for (int b = a; b < m.species; ++b) {
                lo = std::min(lo, m.cutoffOf(a, b).inner());
                hi = std::max(hi, m.cutoffOf(a, b).outer());
            }
        return {lo, hi};
    }
    return {s.potential.r_l * s.potential.sigma, s.potential.r_u * s.potential.sigma};
}
BodyParams bodyParams(const Scene& s) {
    BodyParams p{s.body.mass, s.body.inertia};
    for (std::size_t a = 0; a < s.species.size() && a < p.speciesMass.size(); ++a) {
        p.speciesMass[a] = s.species[a].mass * s.body.mass;
        // Rods among spheres: a sphere's inertia is 0 (core/species_rotor.hpp).
        p.speciesInertia[a] = s.species[a].inertia * s.body.inertia[0];
        if (s.species[a].kind == "sphere") p.speciesInertia[a] = 0.0;
    }
    return p;
}

} // namespace terrace
