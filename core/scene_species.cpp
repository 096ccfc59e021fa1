// The species of a mixture of spheres (Scene::species) and their unlike pairs (potential.pairs):
// their reader, the bodies' counts and the potentials they make (core/lj_mixture.hpp,
// core/step_mixture.hpp).
#include "core/initial_state.hpp"
#include "core/lj_mixture.hpp"
#include "core/scene_sections.hpp"
#include "core/step_mixture.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>

namespace terrace {

namespace {

std::string speciesNames(const Scene& s) {
    std::string list;
    for (const auto& x : s.species)
        list += (list.empty() ? "" : ", ") + x.name;
    return list;
}

int speciesIndex(const Scene& s, const std::string& name) {
    for (std::size_t a = 0; a < s.species.size(); ++a)
        if (s.species[a].name == name) return static_cast<int>(a);
    return -1;
}

} // namespace

namespace detail {

void readSpecies(const JsonSection& top, Scene& s) {
    const JsonSection pot = top.section("potential");
    if (!top.has("species")) {
        if (pot.has("pairs")) pot.fail("pairs", "only meaningful with species");
        if (s.potential.cutoff_per_pair)
            pot.fail("cutoff_per_pair", "only meaningful with species (one kind of body has one "
                                        "pair, cut in potential.sigma)");
        return;
    }
    const auto& list = top.at("species");
    constexpr int most = LJMixture::maxSpecies;
    if (!list.is_array() || list.size() < 2 || list.size() > static_cast<std::size_t>(most))
        top.fail("species", "must be an array of 2 to " + std::to_string(most) +
                                " species: [{\"name\": \"A\", \"fraction\": 0.8, \"epsilon\": "
                                "1, \"sigma\": 1}, ...]");
    const bool rods = s.potential.kind == "rod-lj";
    if (!((s.potential.kind == "lj" || s.potential.kind == "steps") && s.body.kind == "sphere") &&
        !(rods && s.body.kind == "linear"))
        top.fail("species", "a mixture is of spheres with Lennard-Jones pairs or a step table "
                            "(body.kind sphere, potential.kind lj or steps) or of rods and spheres "
                            "(body.kind linear, potential.kind rod-lj)");
    const bool steps = s.potential.kind == "steps";
    if (steps && s.potential.cutoff_per_pair)
        pot.fail("cutoff_per_pair", "a step table ends at its first radius, which each pair of a "
                                    "mixture takes in its own sigma: leave cutoff_per_pair out");
    const bool explicitStart =
        top.has("state") && top.at("state").is_object() && top.at("state").contains("particles");
    double total = 0.0;
    for (std::size_t a = 0; a < list.size(); ++a) {
        const JsonSection e(list[a], top.name("species[" + std::to_string(a) + "]"), top.origin());
        if (rods)
            e.onlyKeys({"name", "fraction", "epsilon", "sigma", "mass", "kind", "inertia"});
        else
            e.onlyKeys({"name", "fraction", "epsilon", "sigma", "mass"});
        SpeciesSpec x;
        if (!e.has("name") || !e.at("name").is_string() || e.at("name").get<std::string>().empty())
            e.fail("name", "each species needs a name, a non-empty string (\"A\")");
        x.name = e.at("name").get<std::string>();
        if (x.name.find_first_of(" ,\t\n\"") != std::string::npos)
            e.fail("name", "must not hold spaces, commas or quotes (it names columns and atom "
                           "types), got \"" +
                               x.name + "\"");
        if (speciesIndex(s, x.name) >= 0) e.fail("name", "\"" + x.name + "\" is named twice");
        // An explicit start gives each body's species: the shares follow from it (readState).
        if (!e.has("fraction") && !explicitStart)
            e.fail("fraction", "missing: the species' share of state.n");
        x.fraction = e.has("fraction") ? e.number("fraction", 0.0, 0.0, 1.0, true)
                                       : std::numeric_limits<double>::quiet_NaN();
        x.epsilon = e.number("epsilon", 1.0, 0.0, 1e6, true);
        x.sigma = e.number("sigma", 1.0, 0.0, 1e3, true);
        x.mass = e.number("mass", 1.0, 0.0, 1e6, true);
        if (rods) {
            // A sphere of the mixture has no inertia to give: it never turns.
            x.kind = e.choice("kind", "linear", {"linear", "sphere"});
            if (x.kind == "sphere" && e.has("inertia"))
                e.fail("inertia", "a sphere of a mixture with rods never turns: leave it out");
            x.inertia = x.kind == "sphere" ? 0.0 : e.number("inertia", 1.0, 0.0, 1e6, true);
        }
        total += x.fraction;
        s.species.push_back(x);
    }
    if (!explicitStart && std::abs(total - 1.0) > 1e-9)
        top.fail("species", "the fractions add up to " + showNumber(total) + ", not 1");
    if (pot.has("pairs")) {
        const auto& pairs = pot.at("pairs");
        if (!pairs.is_array())
            pot.fail("pairs", "must be an array: [{\"between\": [\"A\", \"B\"], \"epsilon\": "
                              "1.5, \"sigma\": 0.8}, ...]");
        std::set<std::pair<int, int>> seen;
        for (std::size_t k = 0; k < pairs.size(); ++k) {
            const JsonSection e(pairs[k], pot.name("pairs[" + std::to_string(k) + "]"),
                                pot.origin());
            e.onlyKeys({"between", "epsilon", "sigma"});
            for (const char* key : {"between", "epsilon", "sigma"})
                if (!e.has(key)) e.fail(key, "missing");
            const auto& between = e.at("between");
            if (!between.is_array() || between.size() != 2 || !between[0].is_string() ||
                !between[1].is_string())
                e.fail("between", "must name two species: [\"A\", \"B\"]");
            SpeciesPairSpec p;
            p.first = between[0].get<std::string>();
            p.second = between[1].get<std::string>();
            const int a = speciesIndex(s, p.first), b = speciesIndex(s, p.second);
            for (const auto& [name, index] : {std::pair{p.first, a}, std::pair{p.second, b}})
                if (index < 0)
                    e.fail("between",
                           "no species \"" + name + "\" (the species are " + speciesNames(s) + ")");
            if (a == b)
                e.fail("between", "a like pair takes its species' own epsilon and sigma; give "
                                  "them there");
            if (!seen.insert({std::min(a, b), std::max(a, b)}).second)
                e.fail("between", "the pair " + p.first + "-" + p.second + " is given twice");
            p.epsilon = e.number("epsilon", 1.0, 0.0, 1e6, true);
            p.sigma = e.number("sigma", 1.0, 0.0, 1e3, true);
            s.potential.pairs.push_back(p);
        }
    }
}

} // namespace detail

std::vector<int> speciesCounts(const Scene& s, int n) {
    std::vector<int> counts;
    if (s.species.empty()) return counts;
    std::vector<double> rest;
    int given = 0;
    for (const auto& x : s.species) {
        const double share = x.fraction * n;
        counts.push_back(static_cast<int>(std::floor(share)));
        rest.push_back(share - counts.back());
        given += counts.back();
    }
    // The bodies left over go to the largest remainders, the first listed on a tie.
    std::vector<std::size_t> order(counts.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return rest[a] > rest[b]; });
    for (std::size_t k = 0; given < n; ++k, ++given)
        ++counts[order[k % order.size()]];
    return counts;
}

namespace {

/// Calls set(a, b, ε_ab, σ_ab) for every pair of species, a ≤ b, in kJ/mol and Å: Lorentz–
/// Berthelot (the arithmetic mean of the diameters, the geometric of the wells), then each pair
/// that potential.pairs gives its own.
template <class Set> void forEachSpeciesPair(const Scene& s, Set&& set) {
    const double eps = s.potential.epsilon, sig = s.potential.sigma;
    for (std::size_t a = 0; a < s.species.size(); ++a)
        for (std::size_t b = a; b < s.species.size(); ++b) {
            const auto &x = s.species[a], &y = s.species[b];
            set(int(a), int(b), std::sqrt(x.epsilon * y.epsilon) * eps,
                0.5 * (x.sigma + y.sigma) * sig);
        }
    for (const auto& p : s.potential.pairs)
        set(speciesIndex(s, p.first), speciesIndex(s, p.second), p.epsilon * eps, p.sigma * sig);
}

} // namespace

StepMixture stepMixture(const Scene& s) {
    StepMixture m;
    m.steps = stepPotential(s);
    m.species = static_cast<int>(s.species.size());
    forEachSpeciesPair(s, [&](int a, int b, double eps, double sig) { m.setPair(a, b, eps, sig); });
    return m;
}

RodMixture rodMixture(const Scene& s) {
    RodMixture m;
    m.species = static_cast<int>(s.species.size());
    for (int a = 0; a < m.species; ++a)
        m.rod[a] = s.species[a].kind != "sphere";
    forEachSpeciesPair(s, [&](int a, int b, double eps, double sig) {
        m.setPair(a, b, eps, sig, s.potential.zeta);
    });
    return m;
}

LJMixture ljMixture(const Scene& s) {
    LJMixture m;
    m.species = static_cast<int>(s.species.size());
    forEachSpeciesPair(s, [&](int a, int b, double eps, double sig) { m.setPair(a, b, eps, sig); });
    if (s.potential.cutoff_per_pair)
        for (int a = 0; a < m.species; ++a)
            for (int b = a; b < m.species; ++b)
                m.setPairCutoff(
                    a, b,
                    {s.potential.r_l * m.pairSigma(a, b), s.potential.r_u * m.pairSigma(a, b)});
    return m;
}

} // namespace terrace
