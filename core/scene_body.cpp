// The body and potential sections: the body kind and its inertia, the pair potential and its
// parameters, and the sites of a site-site molecule with the mass and moments they imply.
#include "core/initial_state.hpp"
#include "core/scene_sections.hpp"
#include "core/site_potential.hpp"
#include "core/step_table.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace terrace::detail {

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();
}

void readIdentity(const JsonSection& top, Scene& s) {
    if (top.has("name")) {
        if (!top.at("name").is_string()) top.fail("name", "must be a string");
        s.name = top.at("name").get<std::string>();
        // The name is written into scene.json and summary.json, which hold UTF-8 only.
        try {
            (void)top.at("name").dump();
        } catch (const nlohmann::json::type_error&) { // nlohmann refuses bytes that are not UTF-8
            top.fail("name", "must be valid UTF-8 text");
        }
    }
    s.seed = static_cast<std::uint64_t>(top.integer("seed", 1, 0, (1LL << 62)));
}

void readBody(const JsonSection& body, Scene& s) {
    body.onlyKeys({"kind", "mass", "inertia", "sites"});
    s.body.kind = body.choice("kind", s.body.kind, {"asymmetric", "linear", "sphere", "symmetric"});
    s.body.mass = body.number("mass", s.body.mass, 0.0, inf, true);
    if (body.has("inertia")) {
        s.body.inertia = body.vec3("inertia");
        if (s.body.inertia.minCoeff() < 0.0) body.fail("inertia", "moments must be >= 0");
    }
}

void checkInertia(const JsonSection& body, const Scene& s) {
    const Vec3& I = s.body.inertia;
    const std::string& kind = s.body.kind;
    // With sites the moments are theirs (readSites), and body.inertia may not be in the scene:
    // blame the sites' geometry.
    const bool fromSites = !s.body.sites.empty();
    const std::string key = fromSites ? "sites" : "inertia";
    const std::string given =
        fromSites ? "; the sites give principal moments (" + showNumber(I[0]) + ", " +
                        showNumber(I[1]) + ", " + showNumber(I[2]) +
                        ") g/mol Å²: place them off a single point (a linear molecule: two "
                        "or more sites apart on z)"
                  : "";
    if (kind == "linear" && !(I[0] > 0.0 && I[0] == I[1]))
        body.fail(key, "a linear rotor needs I1 = I2 > 0 (I3 is ignored)" + given);
    if (kind == "symmetric" && !(I.minCoeff() > 0.0 && I[0] == I[1]))
        body.fail(key, "a symmetric top needs I1 = I2 > 0 and I3 > 0" + given);
    if (kind == "asymmetric" && !(I.minCoeff() > 0.0))
        body.fail(key, "an asymmetric top needs three positive moments" + given);
}

namespace {

constexpr const char* stepKeys[] = {"steps",       "hard_core",        "lambda",
                                    "depth",       "attractive_steps", "range",
                                    "energy_rule", "core_energy"};

/// The keys a named table reads (the rest of stepKeys are refused with it).
std::vector<std::string> tableKeys(const std::string& name) {
    if (name == "square_well" || name == "square_shoulder") return {"lambda", "depth"};
    if (name == "lj") return {"attractive_steps", "range", "energy_rule", "core_energy"};
    if (name == "chapela_lj") return {};
    return {"hard_core"}; // an explicit table
}

/// potential.steps: an explicit table [[r, E], ...] with hard_core, or a ready-made one by name.
void readStepTable(const JsonSection& pot, Scene& s) {
    if (pot.has("cutoff"))
        pot.fail("cutoff", "a step table ends at its first radius: leave potential.cutoff out");
    if (!pot.has("steps"))
        pot.fail("steps", "potential.kind steps needs its table: [[r, E], ...] (σ, ε) with "
                          "hard_core, or one of \"square_well\", \"square_shoulder\", "
                          "\"chapela_lj\", \"lj\"");
    const nlohmann::json& given = pot.at("steps");
    StepTable t;
    std::string name;
    if (given.is_string()) {
        name = pot.choice("steps", "", {"chapela_lj", "lj", "square_shoulder", "square_well"});
        const double lambda = pot.number("lambda", 1.5, 1.0, 100.0, true);
        const double depth = pot.number("depth", 1.0, -1e6, 1e6);
        if (name == "square_well") t = steps::squareWell(lambda, depth);
        if (name == "square_shoulder") t = steps::squareShoulder(lambda, depth);
        if (name == "chapela_lj") t = steps::chapelaLJ();
        if (name == "lj") {
            const std::string rule = pot.choice("energy_rule", "volume", {"midpoint", "volume"});
            t = steps::lennardJones(pot.number("attractive_steps", 5.8, 0.0, 1000.0, true),
                                    pot.number("range", 3.0, std::pow(2.0, 1.0 / 6.0), 100.0, true),
                                    rule == "volume" ? steps::StepEnergyRule::Volume
                                                     : steps::StepEnergyRule::Midpoint,
                                    pot.number("core_energy", 100.0, 0.0, 1e6, true));
        }
    } else if (given.is_array()) {
        for (std::size_t k = 0; k < given.size(); ++k) {
            const auto& e = given[k];
            if (!e.is_array() || e.size() != 2 || !e[0].is_number() || !e[1].is_number())
                pot.fail("steps", "step " + std::to_string(k) +
                                      " must be [r, E], two numbers (σ, ε), got " + showJson(e));
            t.radii.push_back(e[0].get<double>());
            t.energies.push_back(e[1].get<double>());
        }
        t.hardCore = pot.number("hard_core", 0.0, 0.0, 1e6);
    } else {
        pot.fail("steps", "must be [[r, E], ...] or a table's name, got " + showJson(given));
    }
    const std::vector<std::string> used = tableKeys(name);
    for (const char* key : stepKeys)
        if (std::string(key) != "steps" && pot.has(key) &&
            std::find(used.begin(), used.end(), key) == used.end())
            pot.fail(key, name.empty() ? "only meaningful for a named table (potential.steps "
                                         "\"square_well\", ...)"
                                       : "not read by the table \"" + name + "\"");
    try {
        validateStepTable(t, pot.name("steps"));
    } catch (const SceneError& e) {
        throw SceneError((pot.origin().empty() ? "" : pot.origin() + ": ") + e.what());
    }
    s.potential.step_radii = t.radii;
    s.potential.step_energies = t.energies;
    s.potential.hard_core = t.hardCore;
}

} // namespace

void readPotential(const JsonSection& pot, Scene& s) {
    pot.onlyKeys({"kind", "epsilon", "sigma", "zeta", "cutoff", "kappa", "kappa_prime", "mu", "nu",
                  "steps", "hard_core", "lambda", "depth", "attractive_steps", "range",
                  "energy_rule", "core_energy", "pairs", "cutoff_per_pair"});
    auto& p = s.potential;
    p.kind = pot.choice("kind", p.kind, {"gay-berne", "lj", "rod-lj", "sites", "steps"});
    if (p.kind == "steps") readStepTable(pot, s);
    for (const char* key : stepKeys)
        if (p.kind != "steps" && pot.has(key)) pot.fail(key, "only meaningful for steps");
    p.epsilon = pot.number("epsilon", p.epsilon, 0, inf, true);
    p.sigma = pot.number("sigma", p.sigma, 0, inf, true);
    p.zeta = pot.number("zeta", p.zeta, 0, inf);
    if (pot.has("cutoff")) {
        const auto& c = pot.at("cutoff");
        if (!c.is_array() || c.size() != 2 || !c[0].is_number() || !c[1].is_number())
            pot.fail("cutoff", "must be [r_l, r_u], two numbers in σ, got " + showJson(c));
        p.r_l = c[0].get<double>();
        p.r_u = c[1].get<double>();
    }
    if (!(std::isfinite(p.r_l) && p.r_l > 0.0 && std::isfinite(p.r_u) && p.r_u > p.r_l &&
          p.r_u <= 100.0))
        pot.fail("cutoff", "must be [r_l, r_u] with 0 < r_l < r_u <= 100 (σ), got [" +
                               showNumber(p.r_l) + ", " + showNumber(p.r_u) + "]");
    p.cutoff_per_pair = pot.boolean("cutoff_per_pair", p.cutoff_per_pair);
    if (p.kind != "rod-lj" && pot.has("zeta")) pot.fail("zeta", "only meaningful for rod-lj");
    for (const char* key : {"kappa", "kappa_prime", "mu", "nu"})
        if (p.kind != "gay-berne" && pot.has(key)) pot.fail(key, "only meaningful for gay-berne");
    if (p.kind == "gay-berne") {
        p.kappa = pot.number("kappa", p.kappa, 0, 100, true);
        p.kappa_prime = pot.number("kappa_prime", p.kappa_prime, 0, 1e4, true);
        p.mu = pot.number("mu", p.mu, 0, 100);
        p.nu = pot.number("nu", p.nu, 0, 100);
        // An ellipsoid's torque is perpendicular to its axis: the spin about it is conserved and
        // decoupled, so the linear rotor is its exact kind (as for the paper's rods).
        if (s.body.kind != "linear")
            pot.refuse("body.kind", "gay-berne ellipsoids are uniaxial: set body.kind to linear");
    }
    if (p.kind == "steps" && s.body.kind != "sphere")
        pot.fail("kind", "a step table is a potential between spheres: set body.kind to sphere");
    if (p.kind == "lj" && s.body.kind != "sphere")
        pot.fail("kind", "lj is a potential between spheres: set body.kind to sphere");
    if (p.kind == "rod-lj" && s.body.kind == "sphere")
        pot.fail("kind", "rod-lj needs bodies with an axis (linear, symmetric, asymmetric)");
}

namespace {

SiteSpec readSite(const JsonSection& e, const std::string& kind) {
    e.onlyKeys({"r", "mass", "epsilon", "sigma"});
    for (const char* key : {"r", "mass", "epsilon", "sigma"})
        if (!e.has(key)) e.fail(key, "missing");
    SiteSpec site;
    site.r = e.vec3("r");
    site.mass = e.number("mass", 0.0, 0.0, 1e6);
    site.epsilon = e.number("epsilon", 0.0, 0.0, 1e6);
    site.sigma = e.number("sigma", 0.0, 0.0, 1e3, true);
    if (kind == "linear" && (site.r.x() != 0.0 || site.r.y() != 0.0))
        e.fail("r", "a linear molecule's sites lie on the body z axis (x = y = 0)");
    return site;
}

std::string showVec(const Vec3& v) {
    return showNumber(v.x()) + ", " + showNumber(v.y()) + ", " + showNumber(v.z());
}

} // namespace

/// The sites must be given in the principal frame: centre of mass at the origin, inertia tensor
/// diagonal (the body frame of the exact free motion); body.mass and body.inertia, when given,
/// must match what the sites imply.
void readSites(const JsonSection& body, Scene& s) {
    constexpr double frameTolerance = 1e-9; // relative: far above round-off, far below any design
    constexpr double momentTolerance = 1e-6;
    if (s.body.kind != "linear" && s.body.kind != "asymmetric")
        body.fail("kind", "sites need linear (all sites on the body z axis) or asymmetric "
                          "(any rigid molecule; two equal moments are handled exactly)");
    if (!body.has("sites"))
        body.fail("sites", "potential.kind sites needs the molecule's sites: [{\"r\": [x, y, "
                           "z], \"mass\": m, \"epsilon\": ε, \"sigma\": σ}, ...]");
    const auto& list = body.at("sites");
    const std::size_t most = SitePotential<AttitudeUse::Frame>::maxSites;
    if (!list.is_array() || list.empty() || list.size() > most)
        body.fail("sites", "must be an array of 1 to " + std::to_string(most) + " sites");
    double mass = 0.0, extent = 0.0;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const JsonSection e(list[i], body.name("sites[" + std::to_string(i) + "]"), body.origin());
        s.body.sites.push_back(readSite(e, s.body.kind));
        mass += s.body.sites.back().mass;
        extent = std::max(extent, s.body.sites.back().r.norm());
    }
    if (!(mass > 0.0)) body.fail("sites", "the sites' masses must add up to more than 0");
    const Vec3 centre = siteCentreOfMass(sceneSites(s));
    if (centre.norm() > frameTolerance * std::max(extent, 1.0))
        body.fail("sites", "the sites' centre of mass is at (" + showVec(centre) +
                               ") Å: give the positions relative to it");
    Mat3 tensor = Mat3::Zero();
    for (const auto& site : s.body.sites)
        tensor +=
            site.mass * (site.r.squaredNorm() * Mat3::Identity() - site.r * site.r.transpose());
    const double offDiagonal =
        std::max({std::abs(tensor(0, 1)), std::abs(tensor(0, 2)), std::abs(tensor(1, 2))});
    if (offDiagonal > frameTolerance * tensor.trace())
        body.fail("sites", "are not in the principal frame (off-diagonal moment " +
                               showNumber(offDiagonal) +
                               " g/mol Å²): rotate them onto the principal axes");
    const Vec3 principal = tensor.diagonal();
    if (body.has("mass") && std::abs(s.body.mass - mass) > frameTolerance * mass)
        body.fail("mass", showNumber(s.body.mass) + " disagrees with the sites' total mass " +
                              showNumber(mass) + " g/mol (leave it out to take theirs)");
    s.body.mass = mass;
    const int used = s.body.kind == "linear" ? 2 : 3;
    for (int a = 0; body.has("inertia") && a < used; ++a)
        if (std::abs(s.body.inertia[a] - principal[a]) > momentTolerance * principal.maxCoeff())
            body.fail("inertia", "disagrees with the sites' principal moments (" +
                                     showVec(principal) + ") g/mol Å² (leave it out to take them)");
    s.body.inertia = principal;
}

} // namespace terrace::detail
