// terrace export lammps (cli/lammps_deck.hpp, cli/lammps_table.hpp): the table holds terrace's
// U and F at its nodes and is read back as LAMMPS interpolates it; units converted; the state in
// the data file is terrace's initial state; LAMMPS's Gay–Berne form, written out here from its
// matrices, equals terrace's term for term; what LAMMPS cannot represent is refused.
#include "cli/lammps_deck.hpp"
#include "core/initial_state.hpp"
#include "core/linear_rotor.hpp"
#include "core/smoothed_potential.hpp"
#include "core/sphere.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <sstream>

namespace test_lammps_deck {

using namespace terrace;
using nlohmann::json;

namespace {

const json ljScene = {
    {"name", "lj"},
    {"body", {{"kind", "sphere"}, {"mass", 1.0}}},
    {"potential", {{"kind", "lj"}, {"epsilon", 1.0}, {"sigma", 1.0}, {"cutoff", {2.5, 3.0}}}},
    {"state", {{"n", 256}, {"density", 0.8}, {"temperature", 0.9}}},
    {"engine", "smd"},
    {"smd", {{"dt_fs", 0.5}, {"skin", 0.3}}},
    {"run", {{"equilibrate_ps", 0.9}, {"time_ps", 2.7}, {"sample_fs", 9.0}}}};

Scene scene(const json& j, const std::vector<std::string>& sets = {}) {
    return sceneFromJson(j, "test.json", sets);
}

/// The lines of a section of a LAMMPS data file, from the line after its header's blank line to
/// the next blank line.
std::vector<std::string> section(const std::string& data, const std::string& header) {
    std::istringstream in(data.substr(data.find("\n" + header) + header.size() + 1));
    std::string line;
    std::vector<std::string> lines;
    std::getline(in, line); // the header line's rest
    std::getline(in, line); // blank
    while (std::getline(in, line) && !line.empty())
        lines.push_back(line);
    return lines;
}

std::vector<double> numbers(const std::string& line) {
    std::istringstream in(line);
    std::vector<double> v;
    double x;
    while (in >> x)
        v.push_back(x);
    return v;
}

} // namespace

TEST(LammpsTable, NodesHoldTerracesSmoothedPotentialAndItsForce) {
    const Smoothed<LJPotential> model{LJPotential{1.3, 2.0}, SmoothedCutoff(5.0, 6.0)};
    const auto radial = [&](double r) {
        const PairForce f = model.evaluate(Vec3(r, 0, 0), Vec3::UnitZ(), Vec3::UnitZ());
        return std::pair{f.U, f.F.x()};
    };
    const cli::RadialTable t = cli::tabulate("K", radial, 1.0, 6.0, 1001);
    ASSERT_EQ(t.points(), 1001);
    EXPECT_DOUBLE_EQ(t.radius(0), 1.0);
    EXPECT_DOUBLE_EQ(t.radius(1000), 6.0);
    EXPECT_NEAR(t.radius(500) * t.radius(500), 0.5 * (1.0 + 36.0), 1e-12); // uniform in r²
    for (const int k : {0, 137, 500, 812, 900, 999, 1000}) {
        const double r = t.radius(k);
        EXPECT_EQ(t.u[k], model.energy(Vec3(0, r, 0), Vec3(), Vec3())) << r;
        // F = −dU/dr, by a central difference of terrace's energy (inside the switch too)
        const double h = 1e-6;
        const double slope = (model.energy(Vec3(r + h, 0, 0), Vec3(), Vec3()) -
                              model.energy(Vec3(r - h, 0, 0), Vec3(), Vec3())) /
                             (2 * h);
        EXPECT_NEAR(t.f[k], -slope, 1e-6 * (1.0 + std::abs(slope))) << r;
    }
    EXPECT_EQ(t.u[1000], 0.0);
    EXPECT_EQ(t.f[1000], 0.0);
}

TEST(LammpsTable, LookupInterpolatesLinearlyInRSquaredAsLammps) {
    const cli::RadialTable t = cli::tabulate(
        "K",
        [](double r) {
            return std::pair{1.0 / (r * r * r), 3.0 / (r * r * r * r)};
        },
        1.0, 3.0, 9);
    // nodes exactly, midpoints in r² the mean of their nodes
    for (int k = 0; k + 1 < t.points(); ++k) {
        const double s0 = t.radius(k) * t.radius(k), s1 = 1.0 + (k + 1) * t.spacing();
        EXPECT_NEAR(t.lookup(s0), t.u[k], 1e-15);
        EXPECT_NEAR(t.lookup(0.5 * (s0 + s1)), 0.5 * (t.u[k] + t.u[k + 1]), 1e-15);
    }
    EXPECT_EQ(t.lookup(9.0), 0.0);  // at the cutoff
    EXPECT_EQ(t.lookup(10.0), 0.0); // beyond
    EXPECT_THROW(t.lookup(0.99), std::domain_error);
}

TEST(LammpsTable, FileInKcalPerMol) {
    const cli::RadialTable t = cli::tabulate(
        "KEY",
        [](double r) {
            return std::pair{4.184 * r, -4.184};
        },
        1.0, 2.0, 3);
    const std::string text = cli::tableSection(t, "a test");
    EXPECT_NE(text.find("\nKEY\nN 3 RSQ 1 2\n\n"), std::string::npos) << text;
    std::istringstream in(text.substr(text.find("\n1 ")));
    std::string line;
    std::getline(in, line); // the newline before the first row
    for (int k = 0; k < 3; ++k) {
        std::getline(in, line);
        const std::vector<double> v = numbers(line);
        ASSERT_EQ(v.size(), 4u) << line;
        EXPECT_EQ(v[0], k + 1);
        EXPECT_DOUBLE_EQ(v[1], t.radius(k));
        EXPECT_DOUBLE_EQ(v[2], t.radius(k)); // 4.184 r kJ/mol = r kcal/mol
        EXPECT_DOUBLE_EQ(v[3], -1.0);
    }
}

TEST(LammpsDeck, LennardJonesSpheresCarryTerracesStateInRealUnits) {
    const Scene s = scene(ljScene);
    const cli::LammpsDeck deck = cli::lammpsDeck(s);
    const Smoothed<LJPotential> model{ljPotential(s), sceneCutoff(s)};
    const auto sys = buildInitialState<Sphere>(s, model);
    EXPECT_EQ(deck.atoms, 256);
    EXPECT_NE(deck.data.find("\n256 atoms\n1 atom types\n"), std::string::npos);
    const auto atoms = section(deck.data, "Atoms # atomic");
    const auto velocities = section(deck.data, "Velocities");
    ASSERT_EQ(atoms.size(), 256u);
    ASSERT_EQ(velocities.size(), 256u);
    const double L = sys.box.length;
    for (const int i : {0, 17, 255}) {
        const std::vector<double> a = numbers(atoms[i]), v = numbers(velocities[i]);
        ASSERT_EQ(a.size(), 8u); // id type x y z ix iy iz
        for (int c = 0; c < 3; ++c) {
            EXPECT_GE(a[2 + c], 0.0);
            EXPECT_LT(a[2 + c], L);
            // unwrapped by the image flags: terrace's position
            EXPECT_NEAR(a[2 + c] + a[5 + c] * L, sys.bodies[i].r[c], 1e-12 * L);
            // Å per 100 fs → Å/fs
            EXPECT_DOUBLE_EQ(v[1 + c], sys.bodies[i].v[c] / 100.0);
        }
    }
    // the table measured on the first frame: terrace's model and the interpolated one agree
    EXPECT_TRUE(std::isfinite(deck.energyTerrace));
    EXPECT_NEAR(deck.energyDeck, deck.energyTerrace, 1e-6 * std::abs(deck.energyTerrace));
    EXPECT_NE(deck.energyDeck, deck.energyTerrace); // a table is not the formula
    EXPECT_NE(deck.input.find("pair_style      table linear " + std::to_string(deck.tablePoints)),
              std::string::npos);
    EXPECT_NE(deck.input.find("pair_coeff      1 1 pair.table TERRACE_LJ 3\n"), std::string::npos);
    EXPECT_NE(deck.input.find("timestep        0.5\n"), std::string::npos);
    EXPECT_NE(deck.input.find("variable        steps index 5400\n"), std::string::npos);
    EXPECT_NE(deck.input.find("temp/rescale 18 "), std::string::npos); // every 9 fs of 0.5 fs
    EXPECT_NE(deck.table.find("N " + std::to_string(deck.tablePoints) + " RSQ 0.5 3\n"),
              std::string::npos);
    EXPECT_TRUE(deck.notes.empty()) << deck.notes.front(); // an SMD Verlet scene: nothing differs
}

TEST(LammpsDeck, EnergiesInKcalPerMolAndEpsilonScaled) {
    // ε = 4.184 kJ/mol is 1 kcal/mol: the table's well bottom is −1 at 2^(1/6) σ.
    json j = ljScene;
    j["potential"]["epsilon"] = 4.184;
    j["state"]["temperature"] = 0.9 / 4.184;
    const cli::LammpsDeck deck = cli::lammpsDeck(scene(j));
    double lowest = 0.0;
    std::istringstream in(deck.table.substr(deck.table.find("\n1 ")));
    std::string line;
    while (std::getline(in, line))
        if (const auto v = numbers(line); v.size() == 4) lowest = std::min(lowest, v[2]);
    EXPECT_NEAR(lowest, -1.0, 1e-6);
}

TEST(LammpsDeck, DmdAndOtherSchemesAreNamedAsDifferences) {
    const cli::LammpsDeck deck =
        cli::lammpsDeck(scene(ljScene, {"engine=dmd", "smd.scheme=omelyan"}));
    ASSERT_EQ(deck.notes.size(), 2u);
    EXPECT_NE(deck.notes[0].find("engine: the scene runs DMD"), std::string::npos);
    EXPECT_NE(deck.notes[1].find("smd.scheme: omelyan"), std::string::npos);
    for (const std::string& n : deck.notes)
        EXPECT_NE(deck.input.find("# Differs from terrace: " + n + "\n"), std::string::npos);
}

TEST(LammpsDeck, LengthsOffTheStepGridAreRoundedAndNamed) {
    // A DMD scene's lengths lie on no step grid: 2.7 ps at 0.7 fs is 3857.14 steps.
    const cli::LammpsDeck deck = cli::lammpsDeck(scene(ljScene, {"engine=dmd", "smd.dt_fs=0.7"}));
    EXPECT_NE(deck.input.find("variable        steps index 3857\n"), std::string::npos);
    bool named = false;
    for (const std::string& n : deck.notes)
        named = named || n.rfind("run.time_ps: 2700 fs is no whole number of steps", 0) == 0;
    EXPECT_TRUE(named);
}

TEST(LammpsDeck, RefusesWhatLammpsCannotRepresent) {
    const auto refusal = [](const json& j, const std::vector<std::string>& sets = {}) {
        try {
            cli::lammpsDeck(scene(j, sets));
        } catch (const cli::LammpsRefusal& e) {
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos); // one line
            return std::string(e.what());
        }
        return std::string("no refusal");
    };
    // the paper's rods (the built-in scene)
    EXPECT_EQ(refusal(json::object(), {"state.n=64", "state.density=0.1"})
                  .rfind("potential.kind: rod-lj", 0),
              0u);
    // a box narrower than twice the cutoff: LAMMPS would see a pair's images
    EXPECT_EQ(refusal(ljScene, {"state.n=64"}).rfind("state.density:", 0), 0u);
    // a massless site
    const json sites = {{"body",
                         {{"kind", "linear"},
                          {"sites",
                           {{{"r", {0, 0, 0.5}}, {"mass", 14.0}, {"epsilon", 0.3}, {"sigma", 3.3}},
                            {{"r", {0, 0, -0.5}}, {"mass", 14.0}, {"epsilon", 0.3}, {"sigma", 3.3}},
                            {{"r", {0, 0, 0}}, {"mass", 0.0}, {"epsilon", 0.1}, {"sigma", 1.0}}}}}},
                        {"potential", {{"kind", "sites"}, {"epsilon", 0.3}, {"sigma", 3.3}}},
                        {"state", {{"n", 256}, {"density", 0.3}, {"temperature", 2.0}}}};
    EXPECT_EQ(refusal(sites).rfind("body.sites[2].mass:", 0), 0u) << refusal(sites);
}

namespace {

/// LAMMPS's Gay–Berne energy between ellipsoids of radii (a, a, c) with long axes ui, uj, written
/// from its matrix form (Brown et al., Comput. Phys. Commun. 180, 1101 (2009); LAMMPS's
/// pair_style gayberne documentation): with A the rotation lab → body,
///   G12 = A1ᵀ S² A1 + A2ᵀ S² A2,   σ12 = [½ r̂ᵀ G12⁻¹ r̂]^(−1/2),   h12 = r − σ12,
///   U_r = 4ε(ϱ¹² − ϱ⁶),   ϱ = σ/(h12 + γσ),
///   η12 = [2 s1 s2 / det G12]^(υ/2),   s = (ab + c²)√(ab),
///   χ12 = [2 r̂ᵀ B12⁻¹ r̂]^μ,   B12 = A1ᵀ E A1 + A2ᵀ E A2,   E = diag(ε_a, ε_b, ε_c)^(−1/μ),
///   U = U_r η12 χ12.
double lammpsGayBerne(const Vec3& rij, const Vec3& ui, const Vec3& uj, double eps, double sigma,
                      double a, double c, double gamma, double upsilon, double mu, double ea,
                      double ec) {
    const auto lab = [](const Vec3& u, const Vec3& diag) { // Aᵀ diag A, body z along u
        return Mat3(diag.x() * Mat3::Identity() + (diag.z() - diag.x()) * u * u.transpose());
    };
    const Vec3 shape2(a * a, a * a, c * c);
    const Mat3 g = lab(ui, shape2) + lab(uj, shape2);
    const double r = rij.norm();
    const Vec3 rHat = rij / r;
    const double sigma12 = std::pow(0.5 * rHat.dot(g.inverse() * rHat), -0.5);
    const double rho = sigma / (r - sigma12 + gamma * sigma);
    const double ur = 4.0 * eps * (std::pow(rho, 12) - std::pow(rho, 6));
    const double s = (a * a + c * c) * a;
    const double eta = std::pow(2.0 * s * s / g.determinant(), 0.5 * upsilon);
    const Vec3 well(std::pow(ea, -1.0 / mu), std::pow(ea, -1.0 / mu), std::pow(ec, -1.0 / mu));
    const Mat3 b = lab(ui, well) + lab(uj, well);
    const double chi = std::pow(2.0 * rHat.dot(b.inverse() * rHat), mu);
    return ur * eta * chi;
}

} // namespace

TEST(LammpsDeck, LammpsGayBerneWithTheDecksParametersIsTerraces) {
    GayBernePotential gb;
    gb.epsilon = 2.0;
    gb.sigma = 3.0;
    gb.kappa = 3.0;
    gb.kappaPrime = 5.0;
    gb.mu = 2.0;
    gb.nu = 1.0;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> radius(3.2, 12.0);
    int compared = 0;
    for (int k = 0; k < 200; ++k) {
        const Vec3 ui = detail::randomUnitVector(rng), uj = detail::randomUnitVector(rng);
        const Vec3 rij = radius(rng) * detail::randomUnitVector(rng);
        const double terrace = gb.energy(rij, ui, uj);
        if (!std::isfinite(terrace)) continue; // overlapping cores
        const double lammps =
            lammpsGayBerne(rij, ui, uj, gb.epsilon, gb.sigma, 0.5 * gb.sigma,
                           0.5 * gb.kappa * gb.sigma, 1.0, gb.nu, gb.mu, 1.0, 1.0 / gb.kappaPrime);
        EXPECT_NEAR(lammps, terrace, 1e-10 * (1.0 + std::abs(terrace)))
            << rij.transpose() << " | " << ui.transpose() << " | " << uj.transpose();
        ++compared;
    }
    EXPECT_GT(compared, 150); // most pairs at 3.2-12 Å do not overlap
}

TEST(LammpsDeck, GayBerneDeckWritesEllipsoidsAndTheirParameters) {
    const json j = {{"body", {{"kind", "linear"}, {"mass", 40.0}, {"inertia", {100.0, 100.0, 0}}}},
                    {"potential",
                     {{"kind", "gay-berne"},
                      {"epsilon", 2.0},
                      {"sigma", 3.0},
                      {"kappa", 3.0},
                      {"kappa_prime", 5.0},
                      {"mu", 2.0},
                      {"nu", 1.0},
                      {"cutoff", {3.5, 4.0}}}},
                    {"state", {{"n", 256}, {"density", 0.02}, {"temperature", 2.0}}},
                    {"engine", "smd"}};
    const Scene s = scene(j);
    const cli::LammpsDeck deck = cli::lammpsDeck(s);
    EXPECT_NE(deck.input.find("pair_style      gayberne 1.0 1 2 12\n"), std::string::npos)
        << deck.input;
    const std::size_t coeff = deck.input.find("pair_coeff      1 1 ");
    ASSERT_NE(coeff, std::string::npos);
    const std::vector<double> c =
        numbers(deck.input.substr(coeff + 20, deck.input.find('\n', coeff) - coeff - 20));
    const std::vector<double> expected = {2.0 / 4.184, 3.0, 1, 1, 0.2, 1, 1, 0.2};
    ASSERT_EQ(c.size(), expected.size());
    for (std::size_t k = 0; k < c.size(); ++k)
        EXPECT_DOUBLE_EQ(c[k], expected[k]) << k;
    EXPECT_NE(deck.input.find("fix             nve all nve/asphere\n"), std::string::npos);
    const auto ellipsoids = section(deck.data, "Ellipsoids");
    const auto velocities = section(deck.data, "Velocities");
    ASSERT_EQ(ellipsoids.size(), 256u);
    const Smoothed<GayBernePotential> model{gayBernePotential(s), sceneCutoff(s)};
    const auto sys = buildInitialState<LinearRotor>(s, model);
    const double inertia = 40.0 * (1.5 * 1.5 + 4.5 * 4.5) / 5.0; // LAMMPS's solid ellipsoid
    for (const int i : {0, 100, 255}) {
        const std::vector<double> e = numbers(ellipsoids[i]), v = numbers(velocities[i]);
        ASSERT_EQ(e.size(), 8u);
        EXPECT_EQ(e[1], 3.0);
        EXPECT_EQ(e[2], 3.0);
        EXPECT_EQ(e[3], 9.0);
        const Quat q(e[4], e[5], e[6], e[7]);
        EXPECT_NEAR(q.norm(), 1.0, 1e-12);
        EXPECT_NEAR((q * Vec3::UnitZ() - sys.bodies[i].s).norm(), 0.0, 1e-12); // the long axis
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(v[4 + c], inertia * sys.bodies[i].w[c] / 100.0, 1e-12 * inertia);
    }
    // a moment of inertia other than the solid ellipsoid's is named; the cutoff's form always
    bool inertiaNamed = false, cutoffNamed = false;
    for (const std::string& n : deck.notes) {
        inertiaNamed = inertiaNamed || n.rfind("body.inertia:", 0) == 0;
        cutoffNamed = cutoffNamed || n.rfind("cutoff:", 0) == 0;
    }
    EXPECT_TRUE(inertiaNamed);
    EXPECT_TRUE(cutoffNamed);
    // the deck's model is the bare U cut at r_u, terrace's the switched one
    double bare = 0.0;
    for (int i = 0; i < sys.size(); ++i)
        for (int k = i + 1; k < sys.size(); ++k) {
            const Vec3 rij = sys.box.minimumImage(sys.bodies[i].r - sys.bodies[k].r);
            if (rij.norm() < 12.0) bare += model.bare.energy(rij, sys.bodies[i].s, sys.bodies[k].s);
        }
    EXPECT_NEAR(deck.energyDeck, bare, 1e-12 * std::abs(bare));
}

TEST(LammpsDeck, SiteMoleculesAreRigidBodiesOfSiteAtoms) {
    const json j = {
        {"body",
         {{"kind", "linear"},
          {"sites",
           {{{"r", {0, 0, 0.547}}, {"mass", 14.007}, {"epsilon", 0.3101}, {"sigma", 3.31}},
            {{"r", {0, 0, -0.547}}, {"mass", 14.007}, {"epsilon", 0.3101}, {"sigma", 3.31}}}}}},
        {"potential", {{"kind", "sites"}, {"epsilon", 0.3101}, {"sigma", 3.31}}},
        {"state", {{"n", 256}, {"density", 0.5}, {"temperature", 2.0}}},
        {"engine", "smd"}};
    const Scene s = scene(j);
    const cli::LammpsDeck deck = cli::lammpsDeck(s);
    EXPECT_EQ(deck.atoms, 512);
    EXPECT_NE(deck.input.find("fix             rigid all rigid/small molecule\n"),
              std::string::npos);
    EXPECT_NE(deck.input.find("neigh_modify    exclude molecule/intra all\n"), std::string::npos);
    EXPECT_NE(deck.table.find("\nSITES_1_2\n"), std::string::npos);
    const auto atoms = section(deck.data, "Atoms # molecular");
    const auto velocities = section(deck.data, "Velocities");
    ASSERT_EQ(atoms.size(), 512u);
    const auto model = Smoothed<SitePotential<AttitudeUse::Axis>>{
        SitePotential<AttitudeUse::Axis>::fromSites(sceneSites(s)), sceneCutoff(s)};
    const auto sys = buildInitialState<LinearRotor>(s, model);
    const double L = sys.box.length;
    for (const int i : {0, 99, 255}) {
        const auto a = numbers(atoms[2 * i]), b = numbers(atoms[2 * i + 1]);
        EXPECT_EQ(a[1], i + 1); // molecule id
        EXPECT_EQ(b[1], i + 1);
        Vec3 pa, pb;
        for (int c = 0; c < 3; ++c) {
            pa[c] = a[3 + c] + a[6 + c] * L; // unwrapped by the image flags
            pb[c] = b[3 + c] + b[6 + c] * L;
        }
        EXPECT_NEAR((0.5 * (pa + pb) - sys.bodies[i].r).norm(), 0.0, 1e-12 * L);
        EXPECT_NEAR((pa - pb - 1.094 * sys.bodies[i].s).norm(), 0.0, 1e-12 * L);
        // the centre's velocity is the mean of the sites', the spin their difference
        const auto va = numbers(velocities[2 * i]), vb = numbers(velocities[2 * i + 1]);
        const Vec3 vA(va[1], va[2], va[3]), vB(vb[1], vb[2], vb[3]);
        EXPECT_NEAR((0.5 * (vA + vB) - sys.bodies[i].v / 100.0).norm(), 0.0, 1e-15);
        EXPECT_NEAR((vA - vB - sys.bodies[i].w.cross(1.094 * sys.bodies[i].s) / 100.0).norm(), 0.0,
                    1e-15);
    }
    // the site-distance switch is not terrace's centre-distance one: named, and measured
    EXPECT_EQ(deck.notes.front().rfind("cutoff:", 0), 0u);
    EXPECT_TRUE(std::isfinite(deck.energyDeck));
}

} // namespace test_lammps_deck
