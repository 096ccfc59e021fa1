// Scene parsing and validation. Every key is checked against the schema below; the first problem
// found is reported as "<origin>: <dotted.key>: <problem>".
#include "core/scene.hpp"
#include "core/initial_state.hpp"
#include "core/units.hpp"
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace terrace {

namespace {

using nlohmann::json;

/// An axis given beside an orientation must name the same axis, to well past round-off.
constexpr double axisAgreement = 1e-9;

class Reader {
public:
    explicit Reader(std::string origin) : origin_(std::move(origin)) {}

    [[noreturn]] void fail(const std::string& key, const std::string& what) const {
        throw SceneError(origin_ + ": " + key + ": " + what);
    }

    void onlyKeys(const json& obj, const std::string& path,
                  const std::set<std::string>& known) const {
        if (!obj.is_object()) fail(path.empty() ? "<top>" : path, "must be an object");
        for (const auto& [k, v] : obj.items()) {
            (void)v;
            if (!known.count(k)) fail(join(path, k), "unknown key");
        }
    }

    static std::string join(const std::string& path, const std::string& key) {
        return path.empty() ? key : path + "." + key;
    }

    double number(const json& obj, const std::string& path, const std::string& key, double def,
                  double lo, double hi, bool loOpen = false) const {
        if (!obj.contains(key)) return def;
        const auto& v = obj.at(key);
        const std::string name = join(path, key);
        if (!v.is_number()) fail(name, "must be a number, got " + v.dump());
        const double x = v.get<double>();
        if (!std::isfinite(x)) fail(name, "must be finite");
        if (loOpen ? !(x > lo) : !(x >= lo))
            fail(name,
                 "must be " + std::string(loOpen ? "> " : ">= ") + fmt(lo) + ", got " + fmt(x));
        if (!(x <= hi)) fail(name, "must be <= " + fmt(hi) + ", got " + fmt(x));
        return x;
    }

    long long integer(const json& obj, const std::string& path, const std::string& key,
                      long long def, long long lo, long long hi) const {
        if (!obj.contains(key)) return def;
        const auto& v = obj.at(key);
        const std::string name = join(path, key);
        if (!v.is_number_integer()) fail(name, "must be an integer, got " + v.dump());
        const long long x = v.get<long long>();
        if (x < lo || x > hi)
            fail(name, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                           std::to_string(x));
        return x;
    }

    std::string choice(const json& obj, const std::string& path, const std::string& key,
                       const std::string& def, const std::set<std::string>& allowed) const {
        if (!obj.contains(key)) return def;
        const auto& v = obj.at(key);
        const std::string name = join(path, key);
        if (!v.is_string()) fail(name, "must be a string, got " + v.dump());
        const auto s = v.get<std::string>();
        if (!allowed.count(s)) {
            std::string list;
            for (const auto& a : allowed)
                list += (list.empty() ? "" : " | ") + a;
            fail(name, "must be one of " + list + ", got \"" + s + "\"");
        }
        return s;
    }

    Vec3 vec3(const json& v, const std::string& name) const {
        if (!v.is_array() || v.size() != 3) fail(name, "must be an array of 3 numbers");
        Vec3 x;
        for (int a = 0; a < 3; ++a) {
            if (!v[a].is_number()) fail(name, "must be an array of 3 numbers");
            x[a] = v[a].get<double>();
            if (!std::isfinite(x[a])) fail(name, "must be finite");
        }
        // Finite elements are not enough: the length (and what is built from it) must be too.
        if (!std::isfinite(x.norm()))
            fail(name, "is too large: its length " + fmt(x.norm()) + " overflows a double");
        return x;
    }

    const json& section(const json& root, const std::string& key) const {
        static const json empty = json::object();
        if (!root.contains(key)) return empty;
        if (!root.at(key).is_object()) fail(key, "must be an object");
        return root.at(key);
    }

    static std::string fmt(double x) {
        std::ostringstream o;
        o << x;
        return o.str();
    }

private:
    std::string origin_;
};

void applyOverride(json& j, const std::string& assignment, const Reader& rd) {
    const auto parsed = parseOverride(assignment);
    if (!parsed) rd.fail("--set " + assignment, "expected key.path=value");
    const auto& [path, value] = *parsed;
    json* node = &j;
    std::size_t start = 0;
    while (true) {
        const auto dot = path.find('.', start);
        const std::string key = path.substr(start, dot - start);
        if (key.empty()) rd.fail(path, "empty key in --set");
        if (dot == std::string::npos) {
            (*node)[key] = value;
            return;
        }
        if (!node->contains(key)) (*node)[key] = json::object();
        node = &(*node)[key];
        if (!node->is_object()) rd.fail(path.substr(0, dot), "is not an object");
        start = dot + 1;
    }
}

/// body.sites (potential.kind sites): the sites, and the mass and principal moments they imply,
/// which body.mass and body.inertia, when given, must match. The sites must be given in the
/// principal frame: centre of mass at the origin, inertia tensor diagonal (the body frame of
/// the exact free motion); a linear molecule's on the body z axis.
void readSites(const json& body, Scene& s, const Reader& rd) {
    constexpr double frameTolerance = 1e-9; // relative: far above round-off, far below any design
    constexpr double momentTolerance = 1e-6;
    if (s.body.kind != "linear" && s.body.kind != "asymmetric")
        rd.fail("body.kind", "sites need linear (all sites on the body z axis) or asymmetric "
                             "(any rigid molecule; two equal moments are handled exactly)");
    if (!body.contains("sites"))
        rd.fail("body.sites", "potential.kind sites needs the molecule's sites: [{\"r\": [x, y, "
                              "z], \"mass\": m, \"epsilon\": ε, \"sigma\": σ}, ...]");
    const auto& list = body["sites"];
    const std::size_t most = SitePotential<AttitudeUse::Frame>::maxSites;
    if (!list.is_array() || list.empty() || list.size() > most)
        rd.fail("body.sites", "must be an array of 1 to " + std::to_string(most) + " sites");
    double mass = 0.0, extent = 0.0;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string name = "body.sites[" + std::to_string(i) + "]";
        const json& e = list[i];
        rd.onlyKeys(e, name, {"r", "mass", "epsilon", "sigma"});
        for (const char* key : {"r", "mass", "epsilon", "sigma"})
            if (!e.contains(key)) rd.fail(name + "." + key, "missing");
        SiteSpec site;
        site.r = rd.vec3(e["r"], name + ".r");
        site.mass = rd.number(e, name, "mass", 0.0, 0.0, 1e6);
        site.epsilon = rd.number(e, name, "epsilon", 0.0, 0.0, 1e6);
        site.sigma = rd.number(e, name, "sigma", 0.0, 0.0, 1e3, true);
        if (s.body.kind == "linear" && (site.r.x() != 0.0 || site.r.y() != 0.0))
            rd.fail(name + ".r", "a linear molecule's sites lie on the body z axis (x = y = 0)");
        mass += site.mass;
        extent = std::max(extent, site.r.norm());
        s.body.sites.push_back(site);
    }
    if (!(mass > 0.0)) rd.fail("body.sites", "the sites' masses must add up to more than 0");
    // core/site_potential.hpp's centre of mass and inertia tensor of the sites as point masses
    const std::vector<Site> sites = sceneSites(s);
    const Vec3 centre = siteCentreOfMass(sites);
    if (centre.norm() > frameTolerance * std::max(extent, 1.0))
        rd.fail("body.sites", "the sites' centre of mass is at (" + Reader::fmt(centre.x()) + ", " +
                                  Reader::fmt(centre.y()) + ", " + Reader::fmt(centre.z()) +
                                  ") Å: give the positions relative to it");
    Mat3 tensor = Mat3::Zero();
    for (const auto& site : s.body.sites)
        tensor +=
            site.mass * (site.r.squaredNorm() * Mat3::Identity() - site.r * site.r.transpose());
    const double offDiagonal =
        std::max({std::abs(tensor(0, 1)), std::abs(tensor(0, 2)), std::abs(tensor(1, 2))});
    if (offDiagonal > frameTolerance * tensor.trace())
        rd.fail("body.sites", "are not in the principal frame (off-diagonal moment " +
                                  Reader::fmt(offDiagonal) +
                                  " g/mol Å²): rotate them onto the principal axes");
    const Vec3 principal = tensor.diagonal();
    if (body.contains("mass") && std::abs(s.body.mass - mass) > frameTolerance * mass)
        rd.fail("body.mass", Reader::fmt(s.body.mass) + " disagrees with the sites' total mass " +
                                 Reader::fmt(mass) + " g/mol (leave it out to take theirs)");
    s.body.mass = mass;
    if (body.contains("inertia")) {
        const int used = s.body.kind == "linear" ? 2 : 3;
        for (int a = 0; a < used; ++a)
            if (std::abs(s.body.inertia[a] - principal[a]) > momentTolerance * principal.maxCoeff())
                rd.fail("body.inertia",
                        "disagrees with the sites' principal moments (" +
                            Reader::fmt(principal.x()) + ", " + Reader::fmt(principal.y()) + ", " +
                            Reader::fmt(principal.z()) + ") g/mol Å² (leave it out to take them)");
    }
    s.body.inertia = principal;
}

ParticleSpec readParticle(const json& p, const std::string& name, const Reader& rd,
                          const std::string& kind) {
    rd.onlyKeys(p, name, {"r", "v", "axis", "orientation", "omega"});
    if (kind == "sphere")
        for (const char* key : {"axis", "orientation", "omega"})
            if (p.contains(key))
                rd.fail(name + "." + key,
                        "a sphere has no orientation or rotation (body.kind is sphere)");
    ParticleSpec s;
    if (!p.contains("r")) rd.fail(name + ".r", "missing");
    s.r = rd.vec3(p.at("r"), name + ".r");
    if (p.contains("v")) s.v = rd.vec3(p.at("v"), name + ".v");
    if (p.contains("omega")) s.omega = rd.vec3(p.at("omega"), name + ".omega");
    if (p.contains("axis")) {
        s.axis = rd.vec3(p.at("axis"), name + ".axis");
        if (s.axis.norm() < 1e-12) rd.fail(name + ".axis", "must be non-zero");
        s.axis.normalize();
    }
    if (p.contains("orientation")) {
        const auto& q = p.at("orientation");
        if (!q.is_array() || q.size() != 4 || !q[0].is_number() || !q[1].is_number() ||
            !q[2].is_number() || !q[3].is_number())
            rd.fail(name + ".orientation", "must be a quaternion [w, x, y, z]");
        Quat quat(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(), q[3].get<double>());
        if (!std::isfinite(quat.norm()))
            rd.fail(name + ".orientation",
                    "is too large: its norm " + Reader::fmt(quat.norm()) + " overflows a double");
        if (!(quat.norm() > 1e-12)) rd.fail(name + ".orientation", "must be non-zero");
        s.orientation = quat.normalized();
    }
    // One orientation per body: the axis is the image of the body z axis, q * ẑ (core/xyz.cpp).
    if (s.orientation) {
        const Vec3 image = *s.orientation * Vec3::UnitZ();
        if (p.contains("axis") && !((image - s.axis).norm() <= axisAgreement)) {
            auto show = [](double x) { return std::abs(x) < 1e-12 ? 0.0 : x; }; // no -2e-16
            std::ostringstream o;
            o << "disagrees with " << name << ".orientation, whose image of the body z axis is ["
              << show(image.x()) << ", " << show(image.y()) << ", " << show(image.z())
              << "]; give one of them, or both agreeing within " << axisAgreement;
            rd.fail(name + ".axis", o.str());
        }
        s.axis = image;
    } else if (p.contains("axis")) {
        // The spin of an asymmetric top about its axis changes its motion: it must be given.
        if (kind == "asymmetric")
            rd.fail(name + ".axis",
                    "an asymmetric top needs .orientation: an axis leaves its rotation about that "
                    "axis undetermined");
        // A symmetric top's turn about its unique axis is immaterial: take the least rotation.
        if (kind == "symmetric") s.orientation = Quat::FromTwoVectors(Vec3::UnitZ(), s.axis);
    }
    return s;
}

/// Interval `value` (in `unit`, of fsPerUnit fs) must be a whole multiple k >= 1 of gridFs fs.
void requireOnGrid(const Reader& rd, const std::string& key, double value, const char* unit,
                   double fsPerUnit, const std::string& gridKey, double gridFs) {
    const double ratio = value * fsPerUnit / gridFs;
    const double k = std::round(ratio);
    if (k >= 1.0 && std::abs(ratio - k) <= limits::gridTolerance * k) return;
    const double below = std::floor(ratio), above = std::ceil(ratio);
    // Enough digits that the values named are valid (six would make 1000.008 ps "1000.01 ps").
    auto valid = [&](double k) {
        std::ostringstream o;
        o.precision(15);
        o << k * gridFs / fsPerUnit;
        return o.str();
    };
    std::string nearest;
    if (below >= 1.0) nearest = valid(below) + " or ";
    nearest += valid(above);
    rd.fail(key, "must be a whole multiple of " + gridKey + " = " + Reader::fmt(gridFs) +
                     " fs, got " + Reader::fmt(value) + " " + unit + "; nearest valid: " + nearest +
                     " " + unit);
}

/// Refuse a body whose thermal motion is faster than the time grid resolves: `time` is the time
/// to cross σ (or turn a radian) in fs at the scene's kT, `timeAtDefault` the same at the default
/// temperature, which tells whether the temperature or the body is to blame.
void requireResolvedMotion(const Reader& rd, const std::string& key, const std::string& what,
                           double value, double time, double timeAtDefault, double temperature) {
    if (time >= limits::minThermalTimeFs) return;
    const bool hot = timeAtDefault >= limits::minThermalTimeFs;
    rd.fail(hot ? "state.temperature" : key,
            (hot ? Reader::fmt(temperature) + " with " + key + " = " + Reader::fmt(value)
                 : Reader::fmt(value) + " at state.temperature " + Reader::fmt(temperature)) +
                " makes a thermal body " + what + " in " + Reader::fmt(time) +
                " fs, faster than the " + Reader::fmt(limits::minThermalTimeFs) +
                " fs the time grid resolves");
}

} // namespace

std::string limits::terraceCountProblem(double uMin, double dV, double kT) {
    const double count = std::abs(uMin) / (dV * kT);
    if (count <= maxTerracesInWell) return "";
    // Blame the temperature when even one terrace per kT would be too fine.
    const bool cold = !(std::abs(uMin) / kT <= maxTerracesInWell);
    std::ostringstream o;
    o << (cold ? "state.temperature" : "dmd.dV") << ": kT = " << kT
      << " kJ/mol with dmd.dV = " << dV << " makes " << count << " terraces of " << dV * kT
      << " kJ/mol in the well (U_min = " << uMin << " kJ/mol), more than the " << maxTerracesInWell
      << " a run can represent (levels would crowd the minimum at round-off); raise "
      << (cold ? "state.temperature" : "dmd.dV");
    return o.str();
}

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
    return Scene{};
}

Scene sceneFromJson(const json& input, const std::string& origin,
                    const std::vector<std::string>& overrides) {
    const Reader rd(origin);
    json j = input;
    if (!j.is_object()) rd.fail("<top>", "a scene must be a JSON object");
    for (const auto& o : overrides)
        applyOverride(j, o, rd);
    rd.onlyKeys(j, "",
                {"name", "seed", "body", "potential", "state", "engine", "dmd", "smd", "run",
                 "output", "analysis"});
    Scene s;
    const double inf = std::numeric_limits<double>::infinity();

    if (j.contains("name")) {
        if (!j["name"].is_string()) rd.fail("name", "must be a string");
        s.name = j["name"].get<std::string>();
        // The name is written into scene.json and summary.json, which hold UTF-8 only.
        try {
            (void)j["name"].dump();
        } catch (const json::type_error&) { // nlohmann refuses to write bytes that are not UTF-8
            rd.fail("name", "must be valid UTF-8 text");
        }
    }
    s.seed = static_cast<std::uint64_t>(rd.integer(j, "", "seed", 1, 0, (1LL << 62)));

    const auto& body = rd.section(j, "body");
    rd.onlyKeys(body, "body", {"kind", "mass", "inertia", "sites"});
    s.body.kind = rd.choice(body, "body", "kind", s.body.kind,
                            {"sphere", "linear", "symmetric", "asymmetric"});
    s.body.mass = rd.number(body, "body", "mass", s.body.mass, 0.0, inf, true);
    if (body.contains("inertia")) {
        s.body.inertia = rd.vec3(body["inertia"], "body.inertia");
        if (s.body.inertia.minCoeff() < 0.0) rd.fail("body.inertia", "moments must be >= 0");
    }
    const auto& pot = rd.section(j, "potential");
    s.potential.kind = rd.choice(pot, "potential", "kind", s.potential.kind,
                                 {"rod-lj", "lj", "gay-berne", "sites"});
    if (s.potential.kind == "sites")
        readSites(body, s, rd);
    else if (body.contains("sites"))
        rd.fail("body.sites", "only meaningful for potential.kind sites");
    const Vec3& I = s.body.inertia;
    if (s.body.kind == "linear" && !(I[0] > 0.0 && I[0] == I[1]))
        rd.fail("body.inertia", "a linear rotor needs I1 = I2 > 0 (I3 is ignored)");
    if (s.body.kind == "symmetric" && !(I.minCoeff() > 0.0 && I[0] == I[1]))
        rd.fail("body.inertia", "a symmetric top needs I1 = I2 > 0 and I3 > 0");
    if (s.body.kind == "asymmetric" && !(I.minCoeff() > 0.0))
        rd.fail("body.inertia", "an asymmetric top needs three positive moments");

    rd.onlyKeys(pot, "potential",
                {"kind", "epsilon", "sigma", "zeta", "cutoff", "kappa", "kappa_prime", "mu", "nu"});
    s.potential.epsilon = rd.number(pot, "potential", "epsilon", s.potential.epsilon, 0, inf, true);
    s.potential.sigma = rd.number(pot, "potential", "sigma", s.potential.sigma, 0, inf, true);
    s.potential.zeta = rd.number(pot, "potential", "zeta", s.potential.zeta, 0, inf);
    if (pot.contains("cutoff")) {
        const auto& c = pot.at("cutoff");
        if (!c.is_array() || c.size() != 2 || !c[0].is_number() || !c[1].is_number())
            rd.fail("potential.cutoff", "must be [r_l, r_u], two numbers in σ, got " + c.dump());
        s.potential.r_l = c[0].get<double>();
        s.potential.r_u = c[1].get<double>();
    }
    if (!(std::isfinite(s.potential.r_l) && s.potential.r_l > 0.0 &&
          std::isfinite(s.potential.r_u) && s.potential.r_u > s.potential.r_l &&
          s.potential.r_u <= 100.0))
        rd.fail("potential.cutoff", "must be [r_l, r_u] with 0 < r_l < r_u <= 100 (σ), got [" +
                                        Reader::fmt(s.potential.r_l) + ", " +
                                        Reader::fmt(s.potential.r_u) + "]");
    if (s.potential.kind != "rod-lj" && pot.contains("zeta"))
        rd.fail("potential.zeta", "only meaningful for rod-lj");
    for (const char* key : {"kappa", "kappa_prime", "mu", "nu"})
        if (s.potential.kind != "gay-berne" && pot.contains(key))
            rd.fail(std::string("potential.") + key, "only meaningful for gay-berne");
    if (s.potential.kind == "gay-berne") {
        s.potential.kappa = rd.number(pot, "potential", "kappa", s.potential.kappa, 0, 100, true);
        s.potential.kappa_prime =
            rd.number(pot, "potential", "kappa_prime", s.potential.kappa_prime, 0, 1e4, true);
        s.potential.mu = rd.number(pot, "potential", "mu", s.potential.mu, 0, 100);
        s.potential.nu = rd.number(pot, "potential", "nu", s.potential.nu, 0, 100);
        // An ellipsoid's torque is perpendicular to its axis: the spin about it is conserved and
        // decoupled, so the linear rotor is its exact kind (as for the paper's rods).
        if (s.body.kind != "linear")
            rd.fail("body.kind", "gay-berne ellipsoids are uniaxial: set body.kind to linear");
    }

    if (s.potential.kind == "lj" && s.body.kind != "sphere")
        rd.fail("potential.kind", "lj is a potential between spheres: set body.kind to sphere");
    if (s.potential.kind == "rod-lj" && s.body.kind == "sphere")
        rd.fail("potential.kind",
                "rod-lj needs bodies with an axis (linear, symmetric, asymmetric)");

    const auto& st = rd.section(j, "state");
    rd.onlyKeys(st, "state",
                {"n", "density", "temperature", "orientations", "lattice_aspect", "particles"});
    s.state.lattice_aspect =
        rd.number(st, "state", "lattice_aspect", s.state.lattice_aspect, 1.0, 100.0);
    s.state.n = static_cast<int>(rd.integer(st, "state", "n", s.state.n, 2, 100000000));
    s.state.density = rd.number(st, "state", "density", s.state.density, 0.0, 10.0, true);
    s.state.temperature = rd.number(st, "state", "temperature", s.state.temperature, 0, inf, true);
    s.state.orientations =
        rd.choice(st, "state", "orientations", s.state.orientations, {"random", "aligned"});
    if (st.contains("particles")) {
        const auto& list = st["particles"];
        if (!list.is_array()) rd.fail("state.particles", "must be an array");
        if (list.size() < 2) rd.fail("state.particles", "needs at least 2 bodies");
        if (st.contains("n") && st["n"] != list.size())
            rd.fail("state.n", "disagrees with the length of state.particles");
        if (st.contains("orientations"))
            rd.fail("state.orientations",
                    "applies to lattice starts only: state.particles gives each orientation");
        if (st.contains("lattice_aspect"))
            rd.fail("state.lattice_aspect",
                    "applies to lattice starts only: state.particles gives each position");
        for (std::size_t i = 0; i < list.size(); ++i)
            s.state.particles.push_back(readParticle(
                list[i], "state.particles[" + std::to_string(i) + "]", rd, s.body.kind));
        s.state.n = static_cast<int>(list.size());
    }

    // What a run can represent: kT itself, and thermal motion the time grid resolves.
    const double kT = s.kT();
    if (!(std::isfinite(kT) && kT > 0.0))
        rd.fail("state.temperature",
                "kT = T*·ε = " + Reader::fmt(kT) + " kJ/mol is not a positive finite number");
    {
        const double kTDefault = Scene{}.state.temperature * s.potential.epsilon;
        auto crossing = [&](double m, double e) {
            return units::toFs(s.potential.sigma * std::sqrt(m / e));
        };
        requireResolvedMotion(rd, "body.mass", "cross σ", s.body.mass, crossing(s.body.mass, kT),
                              crossing(s.body.mass, kTDefault), s.state.temperature);
        auto turning = [](double i, double e) { return units::toFs(std::sqrt(i / e)); };
        for (int a = 0; a < 3; ++a) {
            const bool used = s.body.kind == "symmetric" || s.body.kind == "asymmetric" ||
                              (s.body.kind == "linear" && a == 0);
            if (used)
                requireResolvedMotion(rd, "body.inertia", "turn one radian", I[a],
                                      turning(I[a], kT), turning(I[a], kTDefault),
                                      s.state.temperature);
        }
    }
    // Explicit bodies: positions that survive the wrap into the box, energies that are finite.
    for (std::size_t i = 0; i < s.state.particles.size(); ++i) {
        const auto& p = s.state.particles[i];
        const std::string name = "state.particles[" + std::to_string(i) + "]";
        const double reach = limits::maxPositionInBoxLengths * s.boxLength();
        if (!(p.r.norm() <= reach))
            rd.fail(name + ".r", "lies " + Reader::fmt(p.r.norm()) + " Å from the origin, beyond " +
                                     Reader::fmt(limits::maxPositionInBoxLengths) +
                                     " box lengths: the wrap into the box would lose its digits");
        const double kinetic = 0.5 * s.body.mass * (p.v * units::psPerTimeUnit).squaredNorm();
        if (!std::isfinite(kinetic))
            rd.fail(name + ".v", "its kinetic energy ½mv² overflows a double");
        const double spin = 0.5 * I.maxCoeff() * (p.omega * units::psPerTimeUnit).squaredNorm();
        if (!std::isfinite(spin))
            rd.fail(name + ".omega", "its rotational energy ½Iω² overflows a double");
    }

    if (j.contains("engine")) s.engine = rd.choice(j, "", "engine", s.engine, {"dmd", "smd"});

    const auto& dmd = rd.section(j, "dmd");
    rd.onlyKeys(dmd, "dmd",
                {"dV", "levels", "values", "terraces", "queue", "invalidation", "horizon_fs",
                 "model", "hold_screen", "sort_bodies", "resort_cells"});
    s.dmd.model = rd.choice(dmd, "dmd", "model", s.dmd.model, {"smoothed", "bare"});
    s.dmd.dV = rd.number(dmd, "dmd", "dV", s.dmd.dV, 0.0, 1e6, true);
    if (dmd.contains("levels")) {
        const auto& lv = dmd["levels"];
        if (!lv.is_array() || lv.empty()) rd.fail("dmd.levels", "must be a non-empty array");
        for (const auto& x : lv) {
            if (!x.is_number() || !std::isfinite(x.get<double>()))
                rd.fail("dmd.levels", "must hold finite numbers (kJ/mol)");
            s.dmd.levels.push_back(x.get<double>());
        }
        for (std::size_t k = 1; k < s.dmd.levels.size(); ++k)
            if (!(s.dmd.levels[k] > s.dmd.levels[k - 1]))
                rd.fail("dmd.levels", "must be strictly increasing");
    }
    if (dmd.contains("values")) {
        if (!dmd.contains("levels")) rd.fail("dmd.values", "needs dmd.levels, the levels it fills");
        const auto& vs = dmd["values"];
        if (!vs.is_array()) rd.fail("dmd.values", "must be an array");
        for (const auto& x : vs) {
            if (!x.is_number() || !std::isfinite(x.get<double>()))
                rd.fail("dmd.values", "must hold finite numbers (kJ/mol)");
            s.dmd.values.push_back(x.get<double>());
        }
        if (s.dmd.values.size() != s.dmd.levels.size() + 1)
            rd.fail("dmd.values", "needs one value per terrace, " +
                                      std::to_string(s.dmd.levels.size() + 1) + " for " +
                                      std::to_string(s.dmd.levels.size()) + " levels, got " +
                                      std::to_string(s.dmd.values.size()));
    }
    if (dmd.contains("terraces")) {
        const auto& t = rd.section(dmd, "terraces");
        rd.onlyKeys(t, "dmd.terraces", {"levels", "values", "n"});
        auto& d = s.dmd.terraces;
        d.levels = rd.choice(t, "dmd.terraces", "levels", d.levels,
                             {"energy", "distance", "volume", "optimal"});
        d.values = rd.choice(t, "dmd.terraces", "values",
                             d.levels == "optimal" ? std::string("boltzmann") : d.values,
                             {"midpoint", "volume", "boltzmann", "virial"});
        if (d.levels == "optimal" && d.values != "boltzmann")
            rd.fail("dmd.terraces.values",
                    "levels \"optimal\" set their own values (the Boltzmann mean of each "
                    "terrace): give \"boltzmann\" or leave it out");
        d.n = static_cast<int>(rd.integer(t, "dmd.terraces", "n", d.n, 0, 100000));
        if (!s.dmd.levels.empty() && !d.isDefault())
            rd.fail("dmd.terraces", "and dmd.levels both set the levels: give one of them");
    }
    s.dmd.queue = rd.choice(dmd, "dmd", "queue", s.dmd.queue, {"auto", "heap", "bpq", "tree"});
    s.dmd.invalidation =
        rd.choice(dmd, "dmd", "invalidation", s.dmd.invalidation, {"lazy", "eager"});
    s.dmd.horizon_fs = rd.number(dmd, "dmd", "horizon_fs", s.dmd.horizon_fs, 0.0, 1e6, true);
    if (dmd.contains("hold_screen")) {
        if (!dmd["hold_screen"].is_boolean())
            rd.fail("dmd.hold_screen", "must be true or false, got " + dmd["hold_screen"].dump());
        s.dmd.hold_screen = dmd["hold_screen"].get<bool>();
    }
    if (dmd.contains("sort_bodies")) {
        if (!dmd["sort_bodies"].is_boolean())
            rd.fail("dmd.sort_bodies", "must be true or false, got " + dmd["sort_bodies"].dump());
        s.dmd.sort_bodies = dmd["sort_bodies"].get<bool>();
    }
    if (dmd.contains("resort_cells") && dmd["resort_cells"] != "auto")
        s.dmd.resort_cells = rd.number(dmd, "dmd", "resort_cells", 0.0, 0.0, 1e6);
    if (s.dmd.horizon_fs < limits::minHorizonFs)
        rd.fail("dmd.horizon_fs",
                "must be >= " + Reader::fmt(limits::minHorizonFs) + " fs, got " +
                    Reader::fmt(s.dmd.horizon_fs) +
                    ": a thermal pair moves ~1e-3 Å in 0.1 fs, so a shorter horizon only "
                    "multiplies virtual events (the paper uses 4 fs)");
    if (s.engine == "dmd" && s.dmd.levels.empty()) {
        const double uMin = sceneMinimumEnergy(s);
        const std::string problem = limits::terraceCountProblem(uMin, s.dmd.dV, kT);
        if (!problem.empty()) throw SceneError(origin + ": " + problem);
    }

    const auto& smd = rd.section(j, "smd");
    // The cutoff belongs to the model both engines simulate, no longer to SMD alone.
    for (const char* moved : {"r_l", "r_u"})
        if (smd.contains(moved))
            rd.fail(std::string("smd.") + moved,
                    "has moved to potential.cutoff = [r_l, r_u] (σ), the cutoff of the model both "
                    "engines simulate");
    rd.onlyKeys(smd, "smd", {"dt_fs", "skin", "scheme", "sort_bodies"});
    s.smd.dt_fs = rd.number(smd, "smd", "dt_fs", s.smd.dt_fs, 0.0, 1e3, true);
    s.smd.skin = rd.number(smd, "smd", "skin", s.smd.skin, 0.0, 10.0);
    s.smd.scheme = rd.choice(smd, "smd", "scheme", s.smd.scheme, {"verlet", "omelyan", "yoshida4"});
    if (smd.contains("sort_bodies")) {
        if (!smd["sort_bodies"].is_boolean())
            rd.fail("smd.sort_bodies", "must be true or false, got " + smd["sort_bodies"].dump());
        s.smd.sort_bodies = smd["sort_bodies"].get<bool>();
    }

    const auto& run = rd.section(j, "run");
    rd.onlyKeys(run, "run", {"equilibrate_ps", "time_ps", "sample_fs", "thermostat_fs"});
    s.run.equilibrate_ps = rd.number(run, "run", "equilibrate_ps", s.run.equilibrate_ps, 0, 1e9);
    s.run.time_ps = rd.number(run, "run", "time_ps", s.run.time_ps, 0, 1e9, true);
    s.run.sample_fs = rd.number(run, "run", "sample_fs", s.run.sample_fs, 0, 1e9, true);
    s.run.thermostat_fs = rd.number(run, "run", "thermostat_fs", s.run.thermostat_fs, 0, 1e9, true);
    const double runFs = s.run.time_ps * 1000.0;
    const std::string runText =
        " is longer than run.time_ps = " + Reader::fmt(s.run.time_ps) + " ps";
    if (s.engine == "smd" && s.smd.dt_fs > runFs)
        rd.fail("smd.dt_fs",
                Reader::fmt(s.smd.dt_fs) + " fs" + runText + ": no step would be taken");
    for (const auto& [key, value] :
         {std::pair<std::string, double>{"run.sample_fs", s.run.sample_fs},
          {"run.thermostat_fs", s.run.thermostat_fs}})
        if (value < limits::minIntervalFs)
            rd.fail(key, "must be >= " + Reader::fmt(limits::minIntervalFs) + " fs, got " +
                             Reader::fmt(value) +
                             ": thermal motion hardly changes in so short an interval (bodies "
                             "take >= 0.1 fs to cross σ or turn a radian)");
    if (s.run.sample_fs > runFs)
        rd.fail("run.sample_fs",
                Reader::fmt(s.run.sample_fs) + " fs" + runText + ": no sample would be taken");
    if (s.run.equilibrate_ps > 0.0 && s.run.thermostat_fs > s.run.equilibrate_ps * 1000.0)
        rd.fail("run.thermostat_fs",
                Reader::fmt(s.run.thermostat_fs) + " fs is longer than run.equilibrate_ps = " +
                    Reader::fmt(s.run.equilibrate_ps) + " ps: equilibration would never rescale");
    if (s.engine == "smd") { // SMD advances in whole steps: no interval may fall between two
        requireOnGrid(rd, "run.sample_fs", s.run.sample_fs, "fs", 1.0, "smd.dt_fs", s.smd.dt_fs);
        requireOnGrid(rd, "run.thermostat_fs", s.run.thermostat_fs, "fs", 1.0, "smd.dt_fs",
                      s.smd.dt_fs);
    }
    // Run lengths are whole numbers of their intervals: equilibration (if any) ends on a rescale
    // and production on a sample, at the times asked for, not the last whole interval before.
    if (s.run.equilibrate_ps > 0.0)
        requireOnGrid(rd, "run.equilibrate_ps", s.run.equilibrate_ps, "ps", 1000.0,
                      "run.thermostat_fs", s.run.thermostat_fs);
    requireOnGrid(rd, "run.time_ps", s.run.time_ps, "ps", 1000.0, "run.sample_fs", s.run.sample_fs);

    const auto& out = rd.section(j, "output");
    rd.onlyKeys(out, "output", {"trajectory_every_fs", "restart_every_ps", "thermo_every_fs"});
    s.output.trajectory_every_fs =
        rd.number(out, "output", "trajectory_every_fs", s.output.trajectory_every_fs, 0, 1e9);
    s.output.restart_every_ps =
        rd.number(out, "output", "restart_every_ps", s.output.restart_every_ps, 0, 1e9);
    s.output.thermo_every_fs =
        rd.number(out, "output", "thermo_every_fs", s.output.thermo_every_fs, 0, 1e9);
    // Output is written at samples: its intervals are whole numbers of them within the run.
    if (s.output.trajectory_every_fs > 0.0) {
        if (s.output.trajectory_every_fs > runFs)
            rd.fail("output.trajectory_every_fs", Reader::fmt(s.output.trajectory_every_fs) +
                                                      " fs" + runText +
                                                      ": no frame would be written");
        requireOnGrid(rd, "output.trajectory_every_fs", s.output.trajectory_every_fs, "fs", 1.0,
                      "run.sample_fs", s.run.sample_fs);
    }
    if (s.output.thermo_every_fs > 0.0) {
        if (s.output.thermo_every_fs > runFs)
            rd.fail("output.thermo_every_fs", Reader::fmt(s.output.thermo_every_fs) + " fs" +
                                                  runText + ": no thermo row would be written");
        requireOnGrid(rd, "output.thermo_every_fs", s.output.thermo_every_fs, "fs", 1.0,
                      "run.sample_fs", s.run.sample_fs);
    }
    if (s.output.restart_every_ps > 0.0) {
        if (s.output.restart_every_ps > s.run.time_ps)
            rd.fail("output.restart_every_ps", Reader::fmt(s.output.restart_every_ps) + " ps" +
                                                   runText + ": no restart file would be written");
        requireOnGrid(rd, "output.restart_every_ps", s.output.restart_every_ps, "ps", 1000.0,
                      "run.sample_fs", s.run.sample_fs);
    }

    const auto& an = rd.section(j, "analysis");
    rd.onlyKeys(an, "analysis",
                {"blocks", "max_lag_ps", "rdf_max", "rdf_bin_angstrom", "rdf_every",
                 "follow_bodies", "lags_per_level"});
    auto& a = s.analysis;
    a.blocks = static_cast<int>(rd.integer(an, "analysis", "blocks", a.blocks, 2, 10000));
    a.max_lag_ps = rd.number(an, "analysis", "max_lag_ps", a.max_lag_ps, 0, 1e9);
    a.rdf_max = rd.number(an, "analysis", "rdf_max", a.rdf_max, 0, 1e6);
    a.rdf_bin_angstrom =
        rd.number(an, "analysis", "rdf_bin_angstrom", a.rdf_bin_angstrom, 1e-6, 1e6);
    if (!(a.rdf_bin_angstrom > 0.0)) rd.fail("analysis.rdf_bin_angstrom", "must be > 0");
    a.rdf_every =
        static_cast<int>(rd.integer(an, "analysis", "rdf_every", a.rdf_every, 1, 1 << 30));
    a.follow_bodies = static_cast<int>(
        rd.integer(an, "analysis", "follow_bodies", a.follow_bodies, 0, 100000000));
    a.lags_per_level =
        static_cast<int>(rd.integer(an, "analysis", "lags_per_level", a.lags_per_level, 4, 4096));
    if (a.lags_per_level % 2 != 0)
        rd.fail("analysis.lags_per_level", std::to_string(a.lags_per_level) +
                                               " is odd: each level adds the upper half of "
                                               "its lags, so the number must be even");
    const double halfBox = 0.5 * s.boxLength();
    if (a.rdf_bin_angstrom > halfBox)
        rd.fail("analysis.rdf_bin_angstrom", Reader::fmt(a.rdf_bin_angstrom) +
                                                 " Å is wider than half the box, " +
                                                 Reader::fmt(halfBox) + " Å: g(r) has no bin");
    return s;
}

namespace {

/// SAX pass that finds the first repeated key of any object (json::parse keeps the last value
/// silently) and names it by its dotted path, state.particles[3].r style.
class DuplicateKeyFinder : public nlohmann::json_sax<json> {
public:
    std::string duplicate; // dotted path of the first repeated key, empty if none

    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override {
        value();
        frames_.push_back({true, {}, {}, -1});
        return true;
    }
    bool key(string_t& k) override {
        auto& f = frames_.back();
        f.key = k;
        if (f.keys.insert(k).second) return true;
        duplicate = path();
        return false; // stop: the first duplicate is the one reported
    }
    bool end_object() override {
        frames_.pop_back();
        return true;
    }
    bool start_array(std::size_t) override {
        value();
        frames_.push_back({false, {}, {}, -1});
        return true;
    }
    bool end_array() override {
        frames_.pop_back();
        return true;
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;
    }

private:
    struct Frame {
        bool object;
        std::set<std::string> keys;
        std::string key; // object: the key being read
        long index;      // array: the element being read
    };

    bool value() {
        if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
        return true;
    }

    std::string path() const {
        std::string p;
        for (const auto& f : frames_)
            p += f.object ? (p.empty() ? "" : ".") + f.key : "[" + std::to_string(f.index) + "]";
        return p;
    }

    std::vector<Frame> frames_;
};

} // namespace

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
    DuplicateKeyFinder finder;
    json::sax_parse(content, &finder);
    if (!finder.duplicate.empty())
        throw SceneError(path + ": " + finder.duplicate + ": duplicate key");
    json j = json::parse(content, nullptr, false);
    if (j.is_discarded()) throw SceneError(path + ": not valid JSON");
    return sceneFromJson(j, path, overrides);
}

json toJson(const Scene& s) {
    auto v3 = [](const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); };
    json j;
    j["name"] = s.name;
    j["seed"] = s.seed;
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
    j["potential"]["cutoff"] = json::array({s.potential.r_l, s.potential.r_u});
    j["state"] = {
        {"n", s.state.n}, {"density", s.state.density}, {"temperature", s.state.temperature}};
    if (s.state.particles.empty()) {
        j["state"]["orientations"] = s.state.orientations;
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
            list.push_back(e);
        }
        j["state"]["particles"] = list;
    }
    j["engine"] = s.engine;
    j["dmd"] = {{"dV", s.dmd.dV},
                {"queue", s.dmd.queue},
                {"invalidation", s.dmd.invalidation},
                {"horizon_fs", s.dmd.horizon_fs},
                {"model", s.dmd.model}};
    if (!s.dmd.levels.empty()) j["dmd"]["levels"] = s.dmd.levels;
    if (!s.dmd.values.empty()) j["dmd"]["values"] = s.dmd.values;
    // Written only when off, so that the resolved scenes of earlier runs are unchanged.
    if (!s.dmd.hold_screen) j["dmd"]["hold_screen"] = false;
    if (!s.dmd.sort_bodies) j["dmd"]["sort_bodies"] = false;
    if (s.dmd.resort_cells) j["dmd"]["resort_cells"] = *s.dmd.resort_cells;
    if (!s.dmd.terraces.isDefault())
        j["dmd"]["terraces"] = {{"levels", s.dmd.terraces.levels},
                                {"values", s.dmd.terraces.values},
                                {"n", s.dmd.terraces.n}};
    j["smd"] = {{"dt_fs", s.smd.dt_fs}, {"skin", s.smd.skin}, {"scheme", s.smd.scheme}};
    if (!s.smd.sort_bodies) j["smd"]["sort_bodies"] = false;
    j["run"] = {{"equilibrate_ps", s.run.equilibrate_ps},
                {"time_ps", s.run.time_ps},
                {"sample_fs", s.run.sample_fs},
                {"thermostat_fs", s.run.thermostat_fs}};
    j["output"] = {{"trajectory_every_fs", s.output.trajectory_every_fs},
                   {"restart_every_ps", s.output.restart_every_ps},
                   {"thermo_every_fs", s.output.thermo_every_fs}};
    j["analysis"] = {{"blocks", s.analysis.blocks},
                     {"max_lag_ps", s.analysis.max_lag_ps},
                     {"rdf_max", s.analysis.rdf_max},
                     {"rdf_bin_angstrom", s.analysis.rdf_bin_angstrom},
                     {"rdf_every", s.analysis.rdf_every},
                     {"follow_bodies", s.analysis.follow_bodies},
                     {"lags_per_level", s.analysis.lags_per_level}};
    return j;
}

std::vector<std::string> sceneWarnings(const Scene& s) {
    std::vector<std::string> out;
    if (!s.dmd.levels.empty()) {
        const double uMin = sceneMinimumEnergy(s);
        bool inWell = false;
        for (double level : s.dmd.levels)
            inWell = inWell || (level > uMin && level < 0.0);
        if (!inWell) {
            std::ostringstream o;
            o << "dmd.levels: no level lies between the potential minimum U_min = " << uMin
              << " kJ/mol and 0, so the terraced potential has no attractive well";
            out.push_back(o.str());
        }
    }
    return out;
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
double sceneMinimumEnergy(const Scene& s) {
    if (s.potential.kind == "lj") return ljPotential(s).minimumEnergy();
    if (s.potential.kind == "gay-berne") return gayBernePotential(s).minimumEnergy();
    if (s.potential.kind == "sites")
        return SitePotential<AttitudeUse::Frame>::fromSites(sceneSites(s)).minimumEnergy();
    return rodPotential(s).minimumEnergy();
}
SmoothedCutoff sceneCutoff(const Scene& s) {
    return {s.potential.r_l * s.potential.sigma, s.potential.r_u * s.potential.sigma};
}
BodyParams bodyParams(const Scene& s) {
    return BodyParams{s.body.mass, s.body.inertia};
}

} // namespace terrace
