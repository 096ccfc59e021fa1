// Mixtures of Lennard-Jones spheres (Scene::species, potential.pairs), and of rods among spheres:
// the scene's reading and refusals, the bodies' counts, Lorentz–Berthelot and explicit unlike pairs
// in the potential, the potential's bounds over its pairs, a lattice start that deals the species
// out with velocities at each species' mass, and a GSD trajectory with one type per species.
#include "core/gsd_file.hpp"
#include "core/gsd_frame.hpp"
#include "core/initial_state.hpp"
#include "core/lj_mixture.hpp"
#include "core/rod_mixture.hpp"
#include "core/rod_potential.hpp"
#include "core/scene.hpp"
#include "core/smoothed_potential.hpp"
#include "core/species_rotor.hpp"
#include "core/species_sphere.hpp"
#include "tests/core/scene_errors.hpp"
#include "tests/rods_among_spheres_scene.hpp"
#include <cstring>
#include <filesystem>
#include <gtest/gtest.h>
#include <unistd.h>

namespace test_species {

using namespace terrace;
using nlohmann::json;
using terrace::scene_tests::errorOf;

namespace {

/// The index entry of frame 0's chunk `name` (std::runtime_error where there is none).
GsdIndexEntry chunkNamed(const GsdContents& c, const std::string& name) {
    for (const auto& e : c.index)
        if (c.names.at(e.id) == name) return e;
    throw std::runtime_error("no chunk " + name);
}

/// Kob–Andersen's binary mixture (Phys. Rev. E 51, 4626 (1995)) in units of ε_AA and σ_AA.
json kobAndersen() {
    return {{"body", {{"kind", "sphere"}, {"mass", 1.0}}},
            {"potential",
             {{"kind", "lj"},
              {"epsilon", 2.0},
              {"sigma", 3.0},
              {"pairs", {{{"between", {"A", "B"}}, {"epsilon", 1.5}, {"sigma", 0.8}}}}}},
            {"species",
             {{{"name", "A"}, {"fraction", 0.8}, {"epsilon", 1.0}, {"sigma", 1.0}},
              {{"name", "B"}, {"fraction", 0.2}, {"epsilon", 0.5}, {"sigma", 0.88}}}},
            {"state", {{"n", 500}, {"density", 1.2}, {"temperature", 2.0}}}};
}

} // namespace

TEST(Species, KobAndersenPairsInTheScenesUnits) {
    const Scene s = sceneFromJson(kobAndersen(), "test.json");
    ASSERT_EQ(s.species.size(), 2u);
    const LJMixture m = ljMixture(s);
    EXPECT_EQ(m.species, 2);
    // Like pairs: the species' own ε, σ times potential.epsilon = 2, sigma = 3.
    EXPECT_DOUBLE_EQ(m.pairEpsilon(0, 0), 2.0);
    EXPECT_DOUBLE_EQ(m.pairSigma(0, 0), 3.0);
    EXPECT_DOUBLE_EQ(m.pairEpsilon(1, 1), 1.0);
    EXPECT_DOUBLE_EQ(m.pairSigma(1, 1), 0.88 * 3.0);
    // The unlike pair as given, not mixed, and symmetric.
    EXPECT_DOUBLE_EQ(m.pairEpsilon(0, 1), 3.0);
    EXPECT_DOUBLE_EQ(m.pairEpsilon(1, 0), 3.0);
    EXPECT_DOUBLE_EQ(m.pairSigma(1, 0), 0.8 * 3.0);
    EXPECT_DOUBLE_EQ(m.minimumEnergy(), -3.0);
    EXPECT_EQ(speciesCounts(s, 500), (std::vector<int>{400, 100}));
}

TEST(Species, LorentzBerthelotWhereNoPairIsGiven) {
    json j = kobAndersen();
    j["potential"].erase("pairs");
    const LJMixture m = ljMixture(sceneFromJson(j, "test.json"));
    EXPECT_DOUBLE_EQ(m.pairSigma(0, 1), 0.5 * (1.0 + 0.88) * 3.0);
    EXPECT_DOUBLE_EQ(m.pairEpsilon(0, 1), std::sqrt(1.0 * 0.5) * 2.0);
}

TEST(Species, TheResolvedSceneReadsBackTheSame) {
    const Scene s = sceneFromJson(kobAndersen(), "test.json");
    const Scene again = sceneFromJson(toJson(s), "scene.json");
    EXPECT_EQ(toJson(again), toJson(s));
    const LJMixture a = ljMixture(s), b = ljMixture(again);
    EXPECT_EQ(a.epsilon, b.epsilon);
    EXPECT_EQ(a.sigma, b.sigma);
}

TEST(Species, CountsByLargestRemainderAddUpToN) {
    json j = kobAndersen();
    j["species"][0]["fraction"] = 1.0 / 3.0;
    j["species"][1]["fraction"] = 2.0 / 3.0;
    const Scene s = sceneFromJson(j, "test.json");
    EXPECT_EQ(speciesCounts(s, 10), (std::vector<int>{3, 7})); // 3.33 | 6.67: the 7th to B
    EXPECT_EQ(speciesCounts(s, 11), (std::vector<int>{4, 7})); // 3.67 | 7.33: the 4th to A
    EXPECT_EQ(speciesCounts(s, 12), (std::vector<int>{4, 8}));
    EXPECT_TRUE(speciesCounts(Scene{}, 12).empty());
}

TEST(Species, RefusalsNameTheKeyAndTheCause) {
    json j = kobAndersen();
    j["species"][1]["fraction"] = 0.3;
    EXPECT_NE(errorOf(j).find("species: the fractions add up to 1.1, not 1"), std::string::npos)
        << errorOf(j);
    j = kobAndersen();
    j["species"][1]["name"] = "A";
    EXPECT_NE(errorOf(j).find("species[1].name: \"A\" is named twice"), std::string::npos)
        << errorOf(j);
    j = kobAndersen();
    j["potential"]["pairs"][0]["between"] = {"A", "C"};
    EXPECT_NE(errorOf(j).find("no species \"C\" (the species are A, B)"), std::string::npos)
        << errorOf(j);
    j = kobAndersen();
    j["potential"]["pairs"][0]["between"] = {"B", "B"};
    EXPECT_NE(errorOf(j).find("a like pair takes its species' own"), std::string::npos)
        << errorOf(j);
    j = kobAndersen();
    j["potential"]["pairs"].push_back(j["potential"]["pairs"][0]);
    j["potential"]["pairs"][1]["between"] = {"B", "A"};
    EXPECT_NE(errorOf(j).find("is given twice"), std::string::npos) << errorOf(j);
    j = kobAndersen();
    j["species"].erase(1);
    EXPECT_NE(errorOf(j).find("species: must be an array of 2 to 4 species"), std::string::npos)
        << errorOf(j);
    j = kobAndersen(); // a mixture of tops is not one yet
    j["body"] = {{"kind", "symmetric"}, {"mass", 1.0}, {"inertia", {1.0, 1.0, 0.5}}};
    j["potential"]["kind"] = "rod-lj";
    j["potential"].erase("pairs");
    EXPECT_NE(errorOf(j).find("species: a mixture is of spheres with Lennard-Jones pairs or a "
                              "step table"),
              std::string::npos)
        << errorOf(j);
    j = kobAndersen();
    j["species"].erase(0);
    j["species"].erase(0);
    j.erase("species");
    EXPECT_NE(errorOf(j).find("potential.pairs: only meaningful with species"), std::string::npos)
        << errorOf(j);
    j = kobAndersen();
    j["state"]["n"] = 4;
    j["species"][0]["fraction"] = 0.9;
    j["species"][1]["fraction"] = 0.1;
    EXPECT_NE(errorOf(j).find("state.n: 4 bodies leave species B (fraction 0.1) none"),
              std::string::npos)
        << errorOf(j);
    j = kobAndersen();
    j["speceis"] = j["species"];
    j.erase("species");
    j["potential"].erase("pairs");
    EXPECT_NE(errorOf(j).find("did you mean species?"), std::string::npos) << errorOf(j);
}

TEST(Species, ThePotentialsBoundsCoverEveryPair) {
    LJMixture m;
    m.species = 2;
    m.setPair(0, 0, 1.0, 1.0);
    m.setPair(1, 1, 0.5, 0.88);
    m.setPair(0, 1, 1.5, 0.8);
    const Vec3 r(1.1, 0.0, 0.0);
    EXPECT_DOUBLE_EQ(m.energy(r, 0, 1),
                     4.0 * 1.5 * (std::pow(0.8 / 1.1, 12) - std::pow(0.8 / 1.1, 6)));
    EXPECT_DOUBLE_EQ(m.energy(r, 0, 1), m.energy(r, 1, 0));
    // reachDistance: the farthest pair's root; lowestEnergyAt: the lowest pair's value.
    for (double u : {-0.2, -0.4, 0.5})
        EXPECT_DOUBLE_EQ(m.reachDistance(u), std::max({detail::lennardJonesRoot(u, 1.0, 1.0),
                                                       detail::lennardJonesRoot(u, 0.5, 0.88),
                                                       detail::lennardJonesRoot(u, 1.5, 0.8)}));
    for (double x : {0.85, 1.0, 1.3, 2.0})
        EXPECT_DOUBLE_EQ(m.lowestEnergyAt(x),
                         std::min({m.energy(Vec3(x, 0, 0), 0, 0), m.energy(Vec3(x, 0, 0), 1, 1),
                                   m.energy(Vec3(x, 0, 0), 0, 1)}));
    // energyRange holds U over every distance within the shift, and is reached.
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
            for (double r0 : {0.8, 0.95, 1.2, 2.0}) {
                const EnergyRange range = m.energyRange(Vec3(r0, 0, 0), a, b, 0.1, 0.0, 0.0);
                double lo = 1e300, hi = -1e300;
                for (int k = 0; k <= 1000; ++k) {
                    const double u = m.energy(Vec3(r0 - 0.1 + 0.2 * k / 1000, 0, 0), a, b);
                    lo = std::min(lo, u), hi = std::max(hi, u);
                }
                EXPECT_LE(range.lo, lo + 1e-12) << a << b << r0;
                EXPECT_GE(range.hi, hi - 1e-12) << a << b << r0;
                EXPECT_NEAR(range.lo, lo, 1e-4 * std::abs(lo) + 1e-9) << a << b << r0;
                EXPECT_NEAR(range.hi, hi, 1e-12 * std::abs(hi)) << a << b << r0;
            }
    // The force is minus the gradient of U (central difference).
    const Vec3 rij(0.7, -0.5, 0.6);
    const PairForce f = m.evaluate(rij, 1, 0);
    for (int c = 0; c < 3; ++c) {
        Vec3 d = Vec3::Zero();
        d[c] = 1e-6;
        EXPECT_NEAR(f.F[c], -(m.energy(rij + d, 1, 0) - m.energy(rij - d, 1, 0)) / 2e-6, 1e-6);
    }
}

// potential.cutoff_per_pair: each pair switched on [r_l σ_ab, r_u σ_ab] (Kob and Andersen cut at
// 2.5 σ_ab). The scene's envelope bounds the range; every answer of the model is the pair's own
// g_ab(r)·U_ab(r), its force minus that function's gradient, and the reach of a level the
// farthest pair's root of g_ab·U_ab = u.
TEST(Species, EachPairSwitchesOnItsOwnCutoffWhereTheSceneCutsPerPair) {
    json j = kobAndersen();
    j["potential"]["cutoff"] = {2.5, 3.0};
    j["potential"]["cutoff_per_pair"] = true;
    const Scene s = sceneFromJson(j, "test.json");
    EXPECT_TRUE(s.potential.cutoff_per_pair);
    EXPECT_EQ(toJson(sceneFromJson(toJson(s), "scene.json")), toJson(s));
    const Smoothed<LJMixture> model{ljMixture(s), sceneCutoff(s)};
    // σ_AA 3 Å, σ_AB 2.4 Å, σ_BB 2.64 Å: the envelope is [2.5 · 2.4, 3 · 3] Å.
    EXPECT_DOUBLE_EQ(model.cut.inner(), 2.5 * 0.8 * 3.0);
    EXPECT_DOUBLE_EQ(model.range(), 3.0 * 3.0);
    EXPECT_DOUBLE_EQ(model.cutOfPair(0, 1).inner(), 2.5 * 0.8 * 3.0);
    EXPECT_DOUBLE_EQ(model.cutOfPair(1, 0).outer(), 3.0 * 0.8 * 3.0);
    EXPECT_DOUBLE_EQ(model.cutOfPair(1, 1).outer(), 3.0 * 0.88 * 3.0);
    const auto switched = [](double r, double eps, double sig) { // g(r)·U(r), paper eq. 23
        const double rl = 2.5 * sig, ru = 3.0 * sig;
        const double g = r <= rl ? 1.0
                         : r >= ru
                             ? 0.0
                             : (ru - r) * (ru - r) * (ru - 3 * rl + 2 * r) / std::pow(ru - rl, 3);
        return g * 4.0 * eps * (std::pow(sig / r, 12) - std::pow(sig / r, 6));
    };
    const double eps[2][2] = {{2.0, 3.0}, {3.0, 1.0}}, sig[2][2] = {{3.0, 2.4}, {2.4, 2.64}};
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
            for (double r : {3.0, 6.2, 6.9, 7.5, 7.9, 8.5, 8.99}) {
                const Vec3 rij(0.6 * r, -0.8 * r, 0.0);
                EXPECT_NEAR(model.energy(rij, a, b), switched(r, eps[a][b], sig[a][b]),
                            1e-12 * std::abs(switched(r, eps[a][b], sig[a][b])) + 1e-15)
                    << a << b << " r " << r;
                EXPECT_DOUBLE_EQ(model.evaluate(rij, a, b).U, model.energy(rij, a, b));
                // dU/dt = −F·v for a pair moving apart at v.
                const Vec3 v(0.3, 0.1, -0.2);
                const EnergyRate e = model.energyRate(rij, v, a, Vec3::Zero(), b, Vec3::Zero());
                EXPECT_DOUBLE_EQ(e.U, model.energy(rij, a, b));
                EXPECT_NEAR(e.dUdt, -model.evaluate(rij, a, b).F.dot(v), 1e-12);
                for (int c = 0; c < 3; ++c) {
                    Vec3 d = Vec3::Zero();
                    d[c] = 1e-6;
                    EXPECT_NEAR(model.evaluate(rij, a, b).F[c],
                                -(model.energy(rij + d, a, b) - model.energy(rij - d, a, b)) / 2e-6,
                                1e-7)
                        << a << b << " r " << r << " component " << c;
                }
            }
    // The AB pair beyond its own r_u (7.2 Å) but inside the envelope has no energy, and no
    // range above or below 0 there.
    EXPECT_EQ(model.energy(Vec3(7.5, 0, 0), 0, 1), 0.0);
    EXPECT_LT(model.energy(Vec3(7.5, 0, 0), 0, 0), 0.0);
    const EnergyRange beyond = model.energyRange(Vec3(7.5, 0, 0), 0, 1, 0.2, 0.0, 0.0);
    EXPECT_EQ(beyond.lo, 0.0);
    EXPECT_EQ(beyond.hi, 0.0);
    // The reach of a level: the farthest pair's, each through its own switch; U_s reaches u there
    // and no pair reaches it beyond.
    for (double u : {-0.01, -0.05, -0.5, -2.5, 1.0}) {
        const double reach = model.reachDistance(u);
        double farthest = 0.0;
        for (int a = 0; a < 2; ++a)
            for (int b = a; b < 2; ++b)
                for (int k = 0; k <= 20000; ++k) {
                    const double r = 2.0 + 7.0 * k / 20000;
                    const double x = switched(r, eps[a][b], sig[a][b]);
                    if (u < 0.0 ? x <= u : x >= u) farthest = std::max(farthest, r);
                }
        EXPECT_GE(reach, farthest - 1e-9) << "u " << u;
        EXPECT_LT(reach, farthest + 7.0 / 20000 + 1e-9) << "u " << u;
    }
    // Without species the key means nothing.
    json one = kobAndersen();
    one.erase("species");
    one["potential"].erase("pairs");
    one["potential"]["cutoff_per_pair"] = true;
    EXPECT_NE(errorOf(one).find("potential.cutoff_per_pair: only meaningful with species"),
              std::string::npos)
        << errorOf(one);
}

TEST(Species, TheLatticeStartDealsOutTheCountsAtRandom) {
    Scene s = sceneFromJson(kobAndersen(), "test.json");
    const auto model = Smoothed<LJMixture>{ljMixture(s), sceneCutoff(s)};
    const auto sys = buildInitialState<SpeciesSphere>(s, model);
    std::vector<int> seen(2, 0);
    int firstHundredB = 0;
    for (int i = 0; i < sys.size(); ++i) {
        ++seen[sys.bodies[i].species];
        firstHundredB += i < 100 && sys.bodies[i].species == 1;
    }
    EXPECT_EQ(seen, (std::vector<int>{400, 100}));
    // Shuffled, not in blocks: ~20 of the first hundred are B (binomial σ 4).
    EXPECT_GT(firstHundredB, 5);
    EXPECT_LT(firstHundredB, 40);
    // Deterministic from the seed; another seed deals another order.
    const auto again = buildInitialState<SpeciesSphere>(s, model);
    s.seed = 2;
    const auto other = buildInitialState<SpeciesSphere>(s, model);
    int same = 0, differ = 0;
    for (int i = 0; i < sys.size(); ++i) {
        same += sys.bodies[i].species == again.bodies[i].species;
        differ += sys.bodies[i].species != other.bodies[i].species;
    }
    EXPECT_EQ(same, sys.size());
    EXPECT_GT(differ, 0);
}

TEST(Species, AGsdFrameHasOneTypePerSpeciesAndTheBodiesTypeid) {
    json j = kobAndersen();
    j["species"][1]["mass"] = 3.0;
    const Scene s = sceneFromJson(j, "test.json");
    const auto model = Smoothed<LJMixture>{ljMixture(s), sceneCutoff(s)};
    const auto sys = buildInitialState<SpeciesSphere>(s, model);
    const auto path = std::filesystem::temp_directory_path() /
                      ("terrace-species-" + std::to_string(::getpid()) + ".gsd");
    {
        GsdWriter w(path, "test", "hoomd", 1, 4, hoomdChunkNames());
        // In pieces smaller than N: the typeid is gathered piece by piece as the positions are.
        const Snapshot all = makeSnapshot(sys, 0.0);
        writeHoomdFrame(
            w, all.size(), 0.0, all.boxLength,
            [&](int begin, int end) {
                Snapshot piece = positionsOnly(0.0, all.boxLength, end - begin);
                for (int i = begin; i < end; ++i) {
                    piece.position.push_back(all.position[i]);
                    piece.velocity.push_back(all.velocity[i]);
                    piece.axis.push_back(all.axis[i]);
                    piece.omega.push_back(all.omega[i]);
                    piece.species.push_back(all.species[i]);
                }
                return piece;
            },
            gsdBodyType(s), 0, 64);
    }
    const GsdContents c = readGsdContents(path);
    const auto entry = [&](const std::string& name) { return chunkNamed(c, name); };
    const GsdIndexEntry types = entry("particles/types");
    EXPECT_EQ(types.n, 2u);
    const std::string typeBytes = readGsdChunk(path, types);
    EXPECT_STREQ(typeBytes.data(), "A");
    EXPECT_STREQ(typeBytes.data() + types.m, "B");
    const GsdIndexEntry typeid_ = entry("particles/typeid");
    ASSERT_EQ(typeid_.n, 500u);
    const std::string ids = readGsdChunk(path, typeid_);
    for (int i = 0; i < 500; ++i) {
        std::uint32_t id = 0;
        std::memcpy(&id, ids.data() + 4 * i, 4);
        ASSERT_EQ(id, static_cast<std::uint32_t>(sys.bodies[i].species)) << i;
    }
    // Each body's mass is its species': B given three times A's below.
    const GsdIndexEntry masses = entry("particles/mass");
    ASSERT_EQ(masses.n, 500u);
    const std::string massBytes = readGsdChunk(path, masses);
    for (int i = 0; i < 500; ++i) {
        float m = 0;
        std::memcpy(&m, massBytes.data() + 4 * i, 4);
        ASSERT_EQ(m, sys.bodies[i].species == 1 ? 3.0f : 1.0f) << i;
    }
    const std::string shapes = readGsdChunk(path, entry("particles/type_shapes"));
    EXPECT_EQ(nlohmann::json::parse(std::string(shapes.data() + entry("particles/type_shapes").m))
                  .at("diameter"),
              0.88 * 3.0);
    std::filesystem::remove(path);
}

TEST(Species, MassesInUnitsOfBodyMassDefaultOneAndReadBack) {
    json j = kobAndersen();
    j["body"]["mass"] = 20.0;
    j["species"][1]["mass"] = 2.5;
    const Scene s = sceneFromJson(j, "test.json");
    EXPECT_DOUBLE_EQ(s.species[0].mass, 1.0);
    EXPECT_DOUBLE_EQ(s.species[1].mass, 2.5);
    const BodyParams p = bodyParams(s);
    EXPECT_DOUBLE_EQ(p.speciesMass[0], 20.0);
    EXPECT_DOUBLE_EQ(p.speciesMass[1], 50.0);
    SpeciesSphere::State b;
    b.species = 1;
    EXPECT_DOUBLE_EQ(bodyMass<SpeciesSphere>(b, p), 50.0);
    b.v = Vec3(1, 2, 2);
    EXPECT_DOUBLE_EQ(kineticEnergy<SpeciesSphere>(b, p), 0.5 * 50.0 * 9.0);
    const Scene again = sceneFromJson(toJson(s), "scene.json");
    EXPECT_DOUBLE_EQ(again.species[1].mass, 2.5);
    EXPECT_EQ(toJson(again), toJson(s));
}

TEST(Species, AMassThatIsNotPositiveOrTooLightIsRefusedByItsKey) {
    json j = kobAndersen();
    j["species"][1]["mass"] = 0.0;
    EXPECT_NE(errorOf(j).find("species[1].mass"), std::string::npos) << errorOf(j);
    j["species"][1]["mass"] = -1.0;
    EXPECT_NE(errorOf(j).find("species[1].mass"), std::string::npos) << errorOf(j);
    // body.mass 1 g/mol, σ 3 Å, kT 4 kJ/mol cross σ in 150 fs: a species 10⁻⁸ as heavy in
    // 0.015 fs, below the time grid's 0.1 fs.
    j["species"][1]["mass"] = 1e-8;
    EXPECT_NE(errorOf(j).find("species[1].mass"), std::string::npos) << errorOf(j);
    EXPECT_NE(errorOf(j).find("faster than the"), std::string::npos) << errorOf(j);
}

// Each species' velocities are drawn at its own mass: ⟨m v²⟩ = 3kT for both (equipartition from
// the first step), and the centre of mass is at rest.
TEST(Species, TheLatticeStartGivesEachSpeciesItsTemperatureAtItsMass) {
    json j = kobAndersen();
    j["species"][1]["mass"] = 4.0;
    j["state"]["n"] = 4000;
    j["state"]["lattice"] = "fcc";
    const Scene s = sceneFromJson(j, "test.json");
    const auto sys =
        buildInitialState<SpeciesSphere>(s, Smoothed<LJMixture>{ljMixture(s), sceneCutoff(s)});
    double mv2[2] = {0, 0}, v2[2] = {0, 0};
    int count[2] = {0, 0};
    Vec3 momentum = Vec3::Zero();
    for (const auto& b : sys.bodies) {
        const double m = bodyMass<SpeciesSphere>(b, sys.body);
        mv2[b.species] += m * b.v.squaredNorm();
        v2[b.species] += b.v.squaredNorm();
        ++count[b.species];
        momentum += m * b.v;
    }
    ASSERT_EQ(count[0], 3200);
    ASSERT_EQ(count[1], 800);
    // The rescale to the target temperature is shared, so the two means are compared with each
    // other: each is 3kT with a relative spread of √(2/(3n)), 1.4 % and 2.9 % here.
    const double a = mv2[0] / count[0], b = mv2[1] / count[1];
    EXPECT_NEAR(a / b, 1.0, 4.0 * std::sqrt(2.0 / (3.0 * 3200) + 2.0 / (3.0 * 800)));
    // The whole at the target exactly: 3N − 3 degrees of freedom (the momentum is fixed).
    EXPECT_NEAR(mv2[0] + mv2[1], (3.0 * 4000 - 3.0) * sys.kT, 1e-9 * 3.0 * 4000 * sys.kT);
    // The heavy species moves at half the speed: ⟨v²⟩ 4 times smaller (a start that ignored the
    // masses gives 1).
    EXPECT_NEAR((v2[0] / count[0]) / (v2[1] / count[1]), 4.0, 0.4);
    EXPECT_LT(momentum.norm(), 1e-9 * std::sqrt(mv2[0] + mv2[1]));
}

namespace {

/// Kob–Andersen with an explicit start of four bodies: three A, one B.
json explicitMixture() {
    json j = kobAndersen();
    j["state"].erase("n");
    for (auto& x : j["species"])
        x.erase("fraction");
    j["state"]["particles"] = json::array();
    const char* names[] = {"A", "B", "A", "A"};
    for (int i = 0; i < 4; ++i)
        j["state"]["particles"].push_back(
            {{"r", {3.5 * i, 0.0, 0.0}}, {"v", {0.1 * i, 0.0, 0.0}}, {"species", names[i]}});
    return j;
}

} // namespace

// An explicit start names each body's species; the shares follow from the bodies and the
// resolved scene reads back the same.
TEST(Species, AnExplicitStartNamesEachBodysSpecies) {
    json j = explicitMixture();
    j["state"]["density"] = 0.01;
    j["species"][1]["mass"] = 2.0;
    const Scene s = sceneFromJson(j, "test.json");
    EXPECT_DOUBLE_EQ(s.species[0].fraction, 0.75);
    EXPECT_DOUBLE_EQ(s.species[1].fraction, 0.25);
    const auto sys =
        buildInitialState<SpeciesSphere>(s, Smoothed<LJMixture>{ljMixture(s), sceneCutoff(s)});
    ASSERT_EQ(sys.size(), 4);
    EXPECT_EQ(sys.bodies[0].species, 0);
    EXPECT_EQ(sys.bodies[1].species, 1);
    EXPECT_EQ(sys.bodies[3].species, 0);
    EXPECT_DOUBLE_EQ(bodyMass<SpeciesSphere>(sys.bodies[1], sys.body), 2.0);
    const Scene again = sceneFromJson(toJson(s), "scene.json");
    EXPECT_EQ(toJson(again), toJson(s));
    EXPECT_EQ(toJson(s)["state"]["particles"][1]["species"], "B");
    // A fraction given beside the bodies that agrees with them is taken.
    j["species"][0]["fraction"] = 0.75;
    EXPECT_DOUBLE_EQ(sceneFromJson(j, "test.json").species[0].fraction, 0.75);
}

TEST(Species, AnExplicitStartsSpeciesAreRefusedByTheirKeys) {
    json j = explicitMixture();
    j["state"]["particles"][2]["species"] = "C";
    EXPECT_NE(errorOf(j).find("state.particles[2].species: no species \"C\" (the species are A, "
                              "B)"),
              std::string::npos)
        << errorOf(j);
    j = explicitMixture();
    j["state"]["particles"][0].erase("species");
    EXPECT_NE(errorOf(j).find("state.particles[0].species: each body of a mixture names its "
                              "species"),
              std::string::npos)
        << errorOf(j);
    j = explicitMixture();
    j["state"]["particles"][1]["species"] = "A";
    EXPECT_NE(errorOf(j).find("no body is of species B"), std::string::npos) << errorOf(j);
    j = explicitMixture();
    j["species"][0]["fraction"] = 0.5; // two bodies, where the start gives three
    EXPECT_NE(errorOf(j).find("give species A a share of 0.75 (3 of 4), where "
                              "species[0].fraction says 0.5"),
              std::string::npos)
        << errorOf(j);
    // Without species, a body has none to name.
    json plain = explicitMixture();
    plain.erase("species");
    plain["potential"].erase("pairs");
    EXPECT_NE(errorOf(plain).find("state.particles[0].species: only meaningful in a mixture"),
              std::string::npos)
        << errorOf(plain);
}

// Rods among spheres (core/species_rotor.hpp): under rod-lj each species names its kind, a rod
// species its inertia in body.inertia's first moment; the pairs mix as for spheres, and only a
// pair of rods feels ζ.
namespace {
/// The tests' rods among spheres at N 64, the rods' inertia 1.5 times body.inertia's.
json rodsAmongSpheres() {
    json j = rod_mixture_tests::rodsAmongSpheresDocument(64, 0.5, 1.4);
    j["species"][0]["inertia"] = 1.5;
    return j;
}
} // namespace

TEST(Species, RodsAmongSpheresNameTheirKindsAndInertias) {
    const Scene s = sceneFromJson(rodsAmongSpheres(), "test.json");
    EXPECT_EQ(s.species[0].kind, "linear");
    EXPECT_EQ(s.species[1].kind, "sphere");
    const BodyParams p = bodyParams(s);
    EXPECT_DOUBLE_EQ(p.speciesInertia[0], 1.5 * 1.154);
    EXPECT_EQ(p.speciesInertia[1], 0.0);
    EXPECT_DOUBLE_EQ(p.speciesMass[1], 2.2 * 18.0);
    const RodMixture m = rodMixture(s);
    EXPECT_TRUE(m.rod[0]);
    EXPECT_FALSE(m.rod[1]);
    const Vec3 r(4.0, 0.5, -0.3), si = Vec3::UnitZ(), sj = Vec3(0.0, 0.6, 0.8);
    // The rod pair is the paper's pair; the rod–sphere pair LJ at σ 1.05 σ, ε √0.6 ε, no ζ.
    const RodPotential rodPair{3.0, 3.035, 1.0}, rodSphere{std::sqrt(0.6) * 3.0, 1.05 * 3.035, 0.0};
    const SpeciesAxis rodI{si, 0}, rodJ{sj, 0}, sphereJ{sj, 1};
    EXPECT_EQ(m.energy(r, rodI, rodJ), rodPair.energy(r, si, sj));
    EXPECT_DOUBLE_EQ(m.energy(r, rodI, sphereJ), rodSphere.energy(r, si, sj));
    EXPECT_NEAR(sceneMinimumEnergy(s), -3.0, 1e-12); // the rod pair's well, the deepest
    // Read back the same, and a mixture of spheres writes neither key (its bytes as before).
    EXPECT_EQ(toJson(sceneFromJson(toJson(s), "scene.json")), toJson(s));
    EXPECT_FALSE(toJson(sceneFromJson(kobAndersen(), "t.json"))["species"][0].contains("kind"));
    // A lattice start: 16 rods that spin, 48 spheres that do not.
    const auto sys = buildInitialState<SpeciesRotor>(s, m);
    int rods = 0;
    for (const auto& b : sys.bodies) {
        rods += b.species == 0;
        EXPECT_EQ(b.species == 1, b.w == Vec3::Zero());
    }
    EXPECT_EQ(rods, 16);
    EXPECT_EQ(degreesOfFreedom(sys), 3 * 64 + 2 * 16 - 3);
}

TEST(Species, RodsAmongSpheresRefusalsNameTheKey) {
    json j = rodsAmongSpheres();
    j["species"][1]["inertia"] = 1.0;
    EXPECT_NE(errorOf(j).find("species[1].inertia: a sphere of a mixture with rods never turns"),
              std::string::npos)
        << errorOf(j);
    // The paper's rods turn a radian in ~50 fs at this kT; a species 10⁻⁸ as stiff in 0.005 fs.
    j = rodsAmongSpheres();
    j["species"][0]["inertia"] = 1e-8;
    EXPECT_NE(errorOf(j).find("species[0].inertia"), std::string::npos) << errorOf(j);
    EXPECT_NE(errorOf(j).find("turn one radian"), std::string::npos) << errorOf(j);
    j["species"][0]["inertia"] = 0.0;
    EXPECT_NE(errorOf(j).find("species[0].inertia"), std::string::npos) << errorOf(j);
    // An explicit start may spin a rod, not a sphere.
    j = rodsAmongSpheres();
    j["species"][0].erase("fraction");
    j["species"][1].erase("fraction");
    j["state"] = {{"n", 2},
                  {"density", 0.01},
                  {"temperature", 1.4},
                  {"particles",
                   {{{"r", {0, 0, 0}}, {"species", "rod"}, {"omega", {0, 1, 0}}},
                    {{"r", {8, 0, 0}}, {"species", "solvent"}}}}};
    EXPECT_EQ(errorOf(j), "");
    j["state"]["particles"][1]["omega"] = {1, 0, 0};
    EXPECT_NE(errorOf(j).find("state.particles[1].omega: a body of species solvent (kind sphere) "
                              "has no rotation"),
              std::string::npos)
        << errorOf(j);
    j = rodsAmongSpheres();
    j["species"][1]["kind"] = "symmetric";
    EXPECT_NE(errorOf(j).find("species[1].kind"), std::string::npos) << errorOf(j);
    j = kobAndersen(); // a mixture of spheres has no kinds to choose
    j["species"][1]["kind"] = "sphere";
    EXPECT_NE(errorOf(j).find("species[1]"), std::string::npos) << errorOf(j);
    EXPECT_NE(errorOf(j).find("kind"), std::string::npos) << errorOf(j);
}

// A GSD frame of rods among spheres: a rod species drawn as the rods, a sphere species as a
// sphere; each body's moment of inertia its species' (a sphere's 0); read back, each rod's ω is
// its own, through its own inertia, and a sphere's is 0.
TEST(Species, AGsdFrameOfRodsAmongSpheresKeepsEachBodysInertiaAndSpin) {
    const Scene s = sceneFromJson(rodsAmongSpheres(), "test.json");
    const auto sys = buildInitialState<SpeciesRotor>(s, rodMixture(s));
    const Snapshot written = makeSnapshot(sys, 0.0);
    ASSERT_EQ(written.species.size(), 64u);
    const auto path = std::filesystem::temp_directory_path() /
                      ("terrace-rods-species-" + std::to_string(::getpid()) + ".gsd");
    {
        GsdWriter w(path, "test", "hoomd", 1, 4, hoomdChunkNames());
        writeHoomdFrame(w, written, gsdBodyType(s), 0);
    }
    const GsdContents c = readGsdContents(path);
    const auto entry = [&](const std::string& name) { return chunkNamed(c, name); };
    const GsdIndexEntry shapes = entry("particles/type_shapes");
    const std::string shapeBytes = readGsdChunk(path, shapes);
    EXPECT_EQ(nlohmann::json::parse(std::string(shapeBytes.data())).at("type"), "ConvexPolyhedron");
    EXPECT_EQ(nlohmann::json::parse(std::string(shapeBytes.data() + shapes.m)).at("type"),
              "Sphere");
    const GsdIndexEntry inertia = entry("particles/moment_inertia");
    ASSERT_EQ(inertia.n, 64u);
    const std::string inertiaBytes = readGsdChunk(path, inertia);
    for (int i = 0; i < 64; ++i) {
        float I = 0;
        std::memcpy(&I, inertiaBytes.data() + 12 * i, 4);
        ASSERT_EQ(I, sys.bodies[i].species == 0 ? float(1.5 * 1.154) : 0.0f) << i;
    }
    std::vector<Snapshot> read;
    forEachGsdFrame(path, [&](Snapshot&& f) { read.push_back(std::move(f)); });
    ASSERT_EQ(read.size(), 1u);
    for (int i = 0; i < 64; ++i)
        EXPECT_LT((read[0].omega[i] - written.omega[i]).norm(),
                  1e-5 * (1.0 + written.omega[i].norm()))
            << i;
    std::filesystem::remove(path);
}

} // namespace test_species
