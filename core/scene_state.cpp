// The state section: a lattice start (n, density, orientations) or explicit bodies, at a
// temperature; and what a run can represent of it (kT, thermal motion, explicit values).
#include "core/scene_sections.hpp"
#include "core/units.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace terrace::detail {

namespace {

/// An axis given beside an orientation must name the same axis, to well past round-off.
constexpr double axisAgreement = 1e-9;

std::optional<Quat> readOrientation(const JsonSection& p) {
    if (!p.has("orientation")) return std::nullopt;
    const auto& q = p.at("orientation");
    if (!q.is_array() || q.size() != 4 || !q[0].is_number() || !q[1].is_number() ||
        !q[2].is_number() || !q[3].is_number())
        p.fail("orientation", "must be a quaternion [w, x, y, z]");
    Quat quat(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(), q[3].get<double>());
    if (!std::isfinite(quat.norm()))
        p.fail("orientation",
               "is too large: its norm " + showNumber(quat.norm()) + " overflows a double");
    if (!(quat.norm() > 1e-12)) p.fail("orientation", "must be non-zero");
    return quat.normalized();
}

/// One body of state.particles; axis and orientation made to agree (core/scene.hpp ParticleSpec).
ParticleSpec readParticle(const JsonSection& p, const Scene& scene) {
    const std::string& kind = scene.body.kind;
    // Named before the other keys: a body of a scene without species is told where they go.
    if (scene.species.empty() && p.has("species"))
        p.fail("species", "only meaningful in a mixture (the top-level species)");
    if (scene.species.empty())
        p.onlyKeys({"r", "v", "axis", "orientation", "omega"});
    else
        p.onlyKeys({"r", "v", "axis", "orientation", "omega", "species"});
    if (kind == "sphere")
        for (const char* key : {"axis", "orientation", "omega"})
            if (p.has(key))
                p.fail(key, "a sphere has no orientation or rotation (body.kind is sphere)");
    ParticleSpec s;
    if (!scene.species.empty()) {
        if (!p.has("species") || !p.at("species").is_string())
            p.fail("species",
                   "each body of a mixture names its species (\"" + scene.species[0].name + "\")");
        const std::string name = p.at("species").get<std::string>();
        std::string names;
        for (std::size_t a = 0; a < scene.species.size(); ++a) {
            if (scene.species[a].name == name) s.species = static_cast<int>(a);
            names += (a ? ", " : "") + scene.species[a].name;
        }
        if (s.species < 0)
            p.fail("species", "no species \"" + name + "\" (the species are " + names + ")");
        // Rods among spheres: a sphere never turns (core/species_rotor.hpp).
        if (scene.species[s.species].kind == "sphere" && p.has("omega"))
            p.fail("omega", "a body of species " + name +
                                " (kind sphere) has no rotation: it never turns among the rods");
    }
    if (!p.has("r")) p.fail("r", "missing");
    s.r = p.vec3("r");
    if (p.has("v")) s.v = p.vec3("v");
    if (p.has("omega")) s.omega = p.vec3("omega");
    if (p.has("axis")) {
        s.axis = p.vec3("axis");
        if (s.axis.norm() < 1e-12) p.fail("axis", "must be non-zero");
        s.axis.normalize();
    }
    s.orientation = readOrientation(p);
    // One orientation per body: the axis is the image of the body z axis, q * ẑ (core/xyz.cpp).
    if (s.orientation) {
        const Vec3 image = *s.orientation * Vec3::UnitZ();
        if (p.has("axis") && !((image - s.axis).norm() <= axisAgreement)) {
            auto show = [](double x) { return std::abs(x) < 1e-12 ? 0.0 : x; }; // no -2e-16
            std::ostringstream o;
            o << "disagrees with " << p.name("orientation")
              << ", whose image of the body z axis is [" << show(image.x()) << ", "
              << show(image.y()) << ", " << show(image.z())
              << "]; give one of them, or both agreeing within " << axisAgreement;
            p.fail("axis", o.str());
        }
        s.axis = image;
    } else if (p.has("axis")) {
        // The spin of an asymmetric top about its axis changes its motion: it must be given.
        if (kind == "asymmetric")
            p.fail("axis", "an asymmetric top needs .orientation: an axis leaves its rotation "
                           "about that axis undetermined");
        // A symmetric top's turn about its unique axis is immaterial: take the least rotation.
        if (kind == "symmetric") s.orientation = Quat::FromTwoVectors(Vec3::UnitZ(), s.axis);
    }
    return s;
}

/// A mixture started from state.particles: each species' share is its bodies' (count / N), which
/// a fraction given beside them must agree with to half a body; every species needs a body.
void takeSharesFromParticles(const JsonSection& st, Scene& s) {
    const int n = static_cast<int>(s.state.particles.size());
    std::vector<int> counts(s.species.size(), 0);
    for (const auto& p : s.state.particles)
        ++counts[p.species];
    for (std::size_t a = 0; a < counts.size(); ++a) {
        auto& x = s.species[a];
        const double share = static_cast<double>(counts[a]) / n;
        const std::string given = std::to_string(counts[a]) + " of " + std::to_string(n);
        if (counts[a] == 0)
            st.fail("particles", "no body is of species " + x.name +
                                     ": give it one, or leave it out of species");
        if (!std::isnan(x.fraction) && std::abs(x.fraction - share) > 0.5 / n)
            st.fail("particles", "give species " + x.name + " a share of " + showNumber(share) +
                                     " (" + given + "), where species[" + std::to_string(a) +
                                     "].fraction says " + showNumber(x.fraction) +
                                     "; leave the fraction out, or make them agree");
        x.fraction = share;
    }
}

/// Refuse a body whose thermal motion is faster than the time grid resolves: `time` is the time
/// to cross σ (or turn a radian) in fs at the scene's kT, `timeAtDefault` the same at the default
/// temperature, which tells whether the temperature or the body is to blame.
void requireResolvedMotion(const JsonSection& top, const std::string& key, const std::string& what,
                           double value, double time, double timeAtDefault, double temperature) {
    if (time >= limits::minThermalTimeFs) return;
    const bool hot = timeAtDefault >= limits::minThermalTimeFs;
    top.refuse(hot ? "state.temperature" : key,
               (hot ? showNumber(temperature) + " with " + key + " = " + showNumber(value)
                    : showNumber(value) + " at state.temperature " + showNumber(temperature)) +
                   " makes a thermal body " + what + " in " + showNumber(time) +
                   " fs, faster than the " + showNumber(limits::minThermalTimeFs) +
                   " fs the time grid resolves");
}

} // namespace

void readState(const JsonSection& st, Scene& s) {
    st.onlyKeys(
        {"n", "density", "temperature", "orientations", "lattice", "lattice_aspect", "particles"});
    auto& state = s.state;
    state.lattice = st.choice("lattice", state.lattice, {"sc", "fcc", "bcc"});
    state.lattice_aspect = st.number("lattice_aspect", state.lattice_aspect, 1.0, 100.0);
    // A stretched fcc or bcc cell is neither: its neighbour shells and reciprocal vectors (the
    // overlap check's, the melt check's) would be another lattice's.
    if (state.lattice != "sc" && state.lattice_aspect != 1.0)
        st.fail("lattice_aspect", showNumber(state.lattice_aspect) +
                                      " stretches the simple-cubic cell only; with "
                                      "state.lattice \"" +
                                      state.lattice + "\" give 1, or use state.lattice \"sc\"");
    state.n = static_cast<int>(st.integer("n", state.n, 2, 100000000));
    state.density = st.number("density", state.density, 0.0, 10.0, true);
    state.temperature = st.number("temperature", state.temperature, 0,
                                  std::numeric_limits<double>::infinity(), true);
    state.orientations = st.choice("orientations", state.orientations, {"aligned", "random"});
    if (!st.has("particles")) {
        const std::vector<int> counts = speciesCounts(s, state.n);
        for (std::size_t a = 0; a < counts.size(); ++a)
            if (counts[a] < 1)
                st.fail("n", std::to_string(state.n) + " bodies leave species " +
                                 s.species[a].name + " (fraction " +
                                 showNumber(s.species[a].fraction) + ") none: raise state.n");
        return;
    }
    const auto& list = st.at("particles");
    if (!list.is_array()) st.fail("particles", "must be an array");
    if (list.size() < 2) st.fail("particles", "needs at least 2 bodies");
    if (st.has("n") && st.at("n") != list.size())
        st.fail("n", "disagrees with the length of state.particles");
    if (st.has("orientations"))
        st.fail("orientations",
                "applies to lattice starts only: state.particles gives each orientation");
    for (const char* key : {"lattice", "lattice_aspect"})
        if (st.has(key))
            st.fail(key, "applies to lattice starts only: state.particles gives each position");
    for (std::size_t i = 0; i < list.size(); ++i) {
        const JsonSection p(list[i], st.name("particles[" + std::to_string(i) + "]"), st.origin());
        state.particles.push_back(readParticle(p, s));
    }
    state.n = static_cast<int>(list.size());
    if (!s.species.empty()) takeSharesFromParticles(st, s);
}

void checkRepresentable(const JsonSection& top, const Scene& s) {
    const double kT = s.kT();
    if (!(std::isfinite(kT) && kT > 0.0))
        top.refuse("state.temperature",
                   "kT = T*·ε = " + showNumber(kT) + " kJ/mol is not a positive finite number");
    const double kTDefault = Scene{}.state.temperature * s.potential.epsilon;
    auto crossing = [&](double m, double e) {
        return units::toFs(s.potential.sigma * std::sqrt(m / e));
    };
    // A σ far below the default's makes the crossing short at any mass: blame it, not the mass.
    const Scene defaults;
    const double crossingTime = crossing(s.body.mass, kT);
    const bool narrow = crossingTime < limits::minThermalTimeFs &&
                        crossing(s.body.mass, kTDefault) < limits::minThermalTimeFs &&
                        units::toFs(defaults.potential.sigma *
                                    std::sqrt(s.body.mass / kTDefault)) >= limits::minThermalTimeFs;
    if (narrow)
        top.refuse("potential.sigma",
                   showNumber(s.potential.sigma) + " Å with body.mass " + showNumber(s.body.mass) +
                       " makes a thermal body cross σ in " + showNumber(crossingTime) +
                       " fs, faster than the " + showNumber(limits::minThermalTimeFs) +
                       " fs the time grid resolves");
    requireResolvedMotion(top, "body.mass", "cross σ", s.body.mass, crossingTime,
                          crossing(s.body.mass, kTDefault), s.state.temperature);
    // A mixture's lighter species cross faster than body.mass says.
    for (std::size_t a = 0; a < s.species.size(); ++a) {
        const double m = s.species[a].mass * s.body.mass;
        requireResolvedMotion(top, "species[" + std::to_string(a) + "].mass", "cross σ",
                              s.species[a].mass, crossing(m, kT), crossing(m, kTDefault),
                              s.state.temperature);
    }
    const Vec3& I = s.body.inertia;
    auto turning = [](double i, double e) { return units::toFs(std::sqrt(i / e)); };
    for (int a = 0; a < 3; ++a) {
        const bool used = s.body.kind == "symmetric" || s.body.kind == "asymmetric" ||
                          (s.body.kind == "linear" && a == 0);
        if (used)
            requireResolvedMotion(top, "body.inertia", "turn one radian", I[a], turning(I[a], kT),
                                  turning(I[a], kTDefault), s.state.temperature);
    }
    // Rods among spheres: a rod species of a smaller inertia turns faster than body.inertia says.
    for (std::size_t a = 0; a < s.species.size(); ++a) {
        if (s.species[a].kind != "linear") continue;
        const double i = s.species[a].inertia * I[0];
        requireResolvedMotion(top, "species[" + std::to_string(a) + "].inertia", "turn one radian",
                              s.species[a].inertia, turning(i, kT), turning(i, kTDefault),
                              s.state.temperature);
    }
    // A body longer than half the box meets its own images: the nearest-image convention, on
    // which every pair sum and neighbour list rests, no longer picks one image per pair.
    double span = 0.0;
    for (const auto& a : s.body.sites)
        for (const auto& b : s.body.sites)
            span = std::max(span, (a.r - b.r).norm());
    const double edge = s.boxLength();
    if (span > 0.5 * edge)
        top.refuse("body.sites",
                   "span " + showNumber(span) + " Å, more than half the box edge " +
                       showNumber(edge) +
                       " Å (set by state.n and state.density): a body may reach at most "
                       "L/2; use more bodies, a lower density or a smaller molecule");
    // Explicit bodies: positions that survive the wrap into the box, energies that are finite.
    const double reach = limits::maxPositionInBoxLengths * s.boxLength();
    for (std::size_t i = 0; i < s.state.particles.size(); ++i) {
        const auto& p = s.state.particles[i];
        const std::string name = "state.particles[" + std::to_string(i) + "]";
        if (!(p.r.norm() <= reach))
            top.refuse(name + ".r",
                       "lies " + showNumber(p.r.norm()) + " Å from the origin, beyond " +
                           showNumber(limits::maxPositionInBoxLengths) +
                           " box lengths: the wrap into the box would lose its digits");
        const double mass = s.body.mass * (p.species >= 0 ? s.species[p.species].mass : 1.0);
        const double kinetic = 0.5 * mass * (p.v * units::psPerTimeUnit).squaredNorm();
        if (!std::isfinite(kinetic))
            top.refuse(name + ".v", "its kinetic energy ½mv² overflows a double");
        const double spin = 0.5 * I.maxCoeff() * (p.omega * units::psPerTimeUnit).squaredNorm();
        if (!std::isfinite(spin))
            top.refuse(name + ".omega", "its rotational energy ½Iω² overflows a double");
    }
}

} // namespace terrace::detail
