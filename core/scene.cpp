// Scene parsing and validation. Every key is checked against the schema below; the first problem
// found is reported as "<origin>: <dotted.key>: <problem>".
#include "core/scene.hpp"
#include "core/initial_state.hpp"
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace terrace {

namespace {

using nlohmann::json;

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
    const auto eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0)
        rd.fail("--set " + assignment, "expected key.path=value");
    const std::string path = assignment.substr(0, eq);
    const std::string text = assignment.substr(eq + 1);
    json value = json::parse(text, nullptr, false);
    if (value.is_discarded()) value = text; // not JSON: a bare string such as smd or heap
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

ParticleSpec readParticle(const json& p, const std::string& name, const Reader& rd) {
    rd.onlyKeys(p, name, {"r", "v", "axis", "orientation", "omega"});
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
        if (!(quat.norm() > 1e-12)) rd.fail(name + ".orientation", "must be non-zero");
        s.orientation = quat.normalized();
    }
    return s;
}

} // namespace

double Scene::boxLength() const {
    const int count = state.particles.empty() ? state.n : static_cast<int>(state.particles.size());
    return std::cbrt(count / state.density) * potential.sigma;
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
    rd.onlyKeys(
        j, "",
        {"name", "seed", "body", "potential", "state", "engine", "dmd", "smd", "run", "output"});
    Scene s;
    const double inf = std::numeric_limits<double>::infinity();

    if (j.contains("name")) {
        if (!j["name"].is_string()) rd.fail("name", "must be a string");
        s.name = j["name"].get<std::string>();
    }
    s.seed = static_cast<std::uint64_t>(rd.integer(j, "", "seed", 1, 0, (1LL << 62)));

    const auto& body = rd.section(j, "body");
    rd.onlyKeys(body, "body", {"kind", "mass", "inertia"});
    s.body.kind = rd.choice(body, "body", "kind", s.body.kind,
                            {"sphere", "linear", "symmetric", "asymmetric"});
    s.body.mass = rd.number(body, "body", "mass", s.body.mass, 0.0, inf, true);
    if (body.contains("inertia")) {
        s.body.inertia = rd.vec3(body["inertia"], "body.inertia");
        if (s.body.inertia.minCoeff() < 0.0) rd.fail("body.inertia", "moments must be >= 0");
    }
    const Vec3& I = s.body.inertia;
    if (s.body.kind == "linear" && !(I[0] > 0.0 && I[0] == I[1]))
        rd.fail("body.inertia", "a linear rotor needs I1 = I2 > 0 (I3 is ignored)");
    if (s.body.kind == "symmetric" && !(I.minCoeff() > 0.0 && I[0] == I[1]))
        rd.fail("body.inertia", "a symmetric top needs I1 = I2 > 0 and I3 > 0");
    if (s.body.kind == "asymmetric" && !(I.minCoeff() > 0.0))
        rd.fail("body.inertia", "an asymmetric top needs three positive moments");

    const auto& pot = rd.section(j, "potential");
    rd.onlyKeys(pot, "potential", {"kind", "epsilon", "sigma", "zeta"});
    s.potential.kind = rd.choice(pot, "potential", "kind", s.potential.kind, {"rod-lj", "lj"});
    s.potential.epsilon = rd.number(pot, "potential", "epsilon", s.potential.epsilon, 0, inf, true);
    s.potential.sigma = rd.number(pot, "potential", "sigma", s.potential.sigma, 0, inf, true);
    s.potential.zeta = rd.number(pot, "potential", "zeta", s.potential.zeta, 0, inf);
    if (s.potential.kind == "lj" && pot.contains("zeta"))
        rd.fail("potential.zeta", "only meaningful for rod-lj");
    if (s.potential.kind == "lj" && s.body.kind != "sphere")
        rd.fail("potential.kind", "lj is a potential between spheres: set body.kind to sphere");
    if (s.potential.kind == "rod-lj" && s.body.kind == "sphere")
        rd.fail("potential.kind",
                "rod-lj needs bodies with an axis (linear, symmetric, asymmetric)");

    const auto& st = rd.section(j, "state");
    rd.onlyKeys(st, "state", {"n", "density", "temperature", "orientations", "particles"});
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
        for (std::size_t i = 0; i < list.size(); ++i)
            s.state.particles.push_back(
                readParticle(list[i], "state.particles[" + std::to_string(i) + "]", rd));
        s.state.n = static_cast<int>(list.size());
    }

    if (j.contains("engine")) s.engine = rd.choice(j, "", "engine", s.engine, {"dmd", "smd"});

    const auto& dmd = rd.section(j, "dmd");
    rd.onlyKeys(dmd, "dmd", {"dV", "levels", "queue", "invalidation", "horizon_fs"});
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
    s.dmd.queue = rd.choice(dmd, "dmd", "queue", s.dmd.queue, {"heap", "bpq"});
    s.dmd.invalidation =
        rd.choice(dmd, "dmd", "invalidation", s.dmd.invalidation, {"lazy", "eager"});
    s.dmd.horizon_fs = rd.number(dmd, "dmd", "horizon_fs", s.dmd.horizon_fs, 0.0, 1e6, true);

    const auto& smd = rd.section(j, "smd");
    rd.onlyKeys(smd, "smd", {"dt_fs", "skin", "r_l", "r_u"});
    s.smd.dt_fs = rd.number(smd, "smd", "dt_fs", s.smd.dt_fs, 0.0, 1e3, true);
    s.smd.skin = rd.number(smd, "smd", "skin", s.smd.skin, 0.0, 10.0);
    s.smd.r_l = rd.number(smd, "smd", "r_l", s.smd.r_l, 0.0, 100.0, true);
    s.smd.r_u = rd.number(smd, "smd", "r_u", s.smd.r_u, 0.0, 100.0, true);
    if (!(s.smd.r_u > s.smd.r_l)) rd.fail("smd.r_u", "must be larger than smd.r_l");

    const auto& run = rd.section(j, "run");
    rd.onlyKeys(run, "run", {"equilibrate_ps", "time_ps", "sample_fs"});
    s.run.equilibrate_ps = rd.number(run, "run", "equilibrate_ps", s.run.equilibrate_ps, 0, 1e9);
    s.run.time_ps = rd.number(run, "run", "time_ps", s.run.time_ps, 0, 1e9, true);
    s.run.sample_fs = rd.number(run, "run", "sample_fs", s.run.sample_fs, 0, 1e9, true);
    if (s.run.sample_fs / 1000.0 > s.run.time_ps)
        rd.fail("run.sample_fs", "is longer than run.time_ps: no sample would be taken");

    const auto& out = rd.section(j, "output");
    rd.onlyKeys(out, "output", {"trajectory_every_fs"});
    s.output.trajectory_every_fs =
        rd.number(out, "output", "trajectory_every_fs", s.output.trajectory_every_fs, 0, 1e9);
    return s;
}

Scene loadScene(const std::string& path, const std::vector<std::string>& overrides) {
    std::ifstream in(path);
    if (!in) throw SceneError(path + ": cannot open the scene file");
    json j = json::parse(in, nullptr, false);
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
    j["state"] = {{"n", s.state.n},
                  {"density", s.state.density},
                  {"temperature", s.state.temperature},
                  {"orientations", s.state.orientations}};
    if (!s.state.particles.empty()) {
        json list = json::array();
        for (const auto& p : s.state.particles) {
            json e = {{"r", v3(p.r)}, {"v", v3(p.v)}, {"omega", v3(p.omega)}, {"axis", v3(p.axis)}};
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
                {"horizon_fs", s.dmd.horizon_fs}};
    if (!s.dmd.levels.empty()) j["dmd"]["levels"] = s.dmd.levels;
    j["smd"] = {
        {"dt_fs", s.smd.dt_fs}, {"skin", s.smd.skin}, {"r_l", s.smd.r_l}, {"r_u", s.smd.r_u}};
    j["run"] = {{"equilibrate_ps", s.run.equilibrate_ps},
                {"time_ps", s.run.time_ps},
                {"sample_fs", s.run.sample_fs}};
    j["output"] = {{"trajectory_every_fs", s.output.trajectory_every_fs}};
    return j;
}

RodPotential rodPotential(const Scene& s) {
    return RodPotential{s.potential.epsilon, s.potential.sigma, s.potential.zeta};
}
LJPotential ljPotential(const Scene& s) {
    return LJPotential{s.potential.epsilon, s.potential.sigma};
}
BodyParams bodyParams(const Scene& s) {
    return BodyParams{s.body.mass, s.body.inertia};
}

} // namespace terrace
