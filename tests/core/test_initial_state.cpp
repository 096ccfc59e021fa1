// Initial states: lattice at the asked density, exact temperature, zero momentum, deterministic
// from the seed, clear errors for what cannot be built.
#include "core/asymmetric_top.hpp"
#include "core/gay_berne_potential.hpp"
#include "core/initial_state.hpp"
#include "core/linear_rotor.hpp"
#include "core/sphere.hpp"
#include "core/symmetric_top.hpp"
#include <gtest/gtest.h>

namespace test_initial_state {

using namespace terrace;

namespace {
constexpr double roundOff = 1e-10;   // relative: sums over 512 bodies of O(1) numbers
constexpr double densityTol = 1e-12; // ρ* from the box the scene's density set: one cube root
constexpr double unitTol = 1e-14;    // a normalised axis, a few ulp from unit length
constexpr double perpendicularTol = 1e-12; // ω·s of ω projected off s, rad per time unit
constexpr double latticeTol = 1e-9;        // Å: positions on the lattice, to the box's round-off
// One start's split of kT between translation and rotation is a sample: at N = 4096 its error
// is ~sqrt(2/(2N)) ≈ 0.016 per degree of freedom, so 0.05 is about three standard errors.
constexpr double equipartitionTol = 0.05;
constexpr double orthonormalTol = 1e-13; // |A Aᵀ − 1| of an attitude built from a quaternion
constexpr double axisTol = 1e-15;        // an explicit axis taken as given, to an ulp

template <class K, class P> void checkThermal(const System<K, P>& sys) {
    const double kin = totalKinetic(sys);
    EXPECT_NEAR(kin / (0.5 * degreesOfFreedom<K>(sys.size()) * sys.kT), 1.0, roundOff);
    EXPECT_LT(totalMomentum(sys).norm(), roundOff * sys.body.mass);
}
} // namespace

TEST(InitialState, DenseRodsAtTheStatePoint) {
    const Scene scene = defaultScene();
    const auto sys = buildInitialState<LinearRotor>(scene, rodPotential(scene));
    ASSERT_EQ(sys.size(), 512);
    EXPECT_NEAR(sys.size() * std::pow(scene.potential.sigma, 3) / sys.box.volume(), 0.5,
                densityTol);
    checkThermal(sys);
    double minDistance = 1e300;
    for (int i = 0; i < sys.size(); ++i) {
        EXPECT_NEAR(sys.bodies[i].s.norm(), 1.0, unitTol);
        EXPECT_NEAR(sys.bodies[i].w.dot(sys.bodies[i].s), 0.0, perpendicularTol);
        for (int j = i + 1; j < sys.size(); ++j)
            minDistance = std::min(minDistance,
                                   sys.box.minimumImage(sys.bodies[i].r - sys.bodies[j].r).norm());
    }
    EXPECT_NEAR(minDistance, sys.box.length / 8, latticeTol); // 8³ simple cubic lattice
}

TEST(InitialState, EquipartitionOverManyBodies) {
    Scene scene = defaultScene();
    scene.state.n = 4096;
    const auto sys = buildInitialState<LinearRotor>(scene, rodPotential(scene));
    double trans = 0, rot = 0;
    for (const auto& b : sys.bodies) {
        trans += 0.5 * sys.body.mass * b.v.squaredNorm();
        rot += LinearRotor::rotationalKinetic(b, sys.body);
    }
    // per degree of freedom, 3 translational and 2 rotational; statistical error ~ sqrt(2/(2N))
    EXPECT_NEAR(trans / (3.0 * sys.size()) / (0.5 * sys.kT), 1.0, equipartitionTol);
    EXPECT_NEAR(rot / (2.0 * sys.size()) / (0.5 * sys.kT), 1.0, equipartitionTol);
}

TEST(InitialState, EveryBodyKind) {
    Scene scene = defaultScene();
    scene.state.n = 100; // not a cube: the lattice is filled partly
    scene.body.inertia = Vec3(1.0, 1.0, 0.5);
    checkThermal(buildInitialState<SymmetricTop>(scene, rodPotential(scene)));
    scene.body.inertia = Vec3(1.0, 2.0, 3.0);
    const auto asym = buildInitialState<AsymmetricTop>(scene, rodPotential(scene));
    checkThermal(asym);
    for (const auto& b : asym.bodies)
        EXPECT_LT((b.A * b.A.transpose() - Mat3::Identity()).norm(), orthonormalTol);
    scene.potential.kind = "lj";
    scene.body.kind = "sphere";
    checkThermal(buildInitialState<Sphere>(scene, ljPotential(scene)));
}

TEST(InitialState, DeterministicFromTheSeed) {
    Scene scene = defaultScene();
    const auto a = buildInitialState<LinearRotor>(scene, rodPotential(scene));
    const auto b = buildInitialState<LinearRotor>(scene, rodPotential(scene));
    scene.seed = 2;
    const auto c = buildInitialState<LinearRotor>(scene, rodPotential(scene));
    for (int i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a.bodies[i].v, b.bodies[i].v);
        EXPECT_EQ(a.bodies[i].s, b.bodies[i].s);
    }
    EXPECT_NE(a.bodies[0].v, c.bodies[0].v);
}

TEST(InitialState, AlignedOrientations) {
    Scene scene = defaultScene();
    scene.state.orientations = "aligned";
    const auto sys = buildInitialState<LinearRotor>(scene, rodPotential(scene));
    for (const auto& b : sys.bodies)
        EXPECT_EQ(b.s, Vec3::UnitZ());
}

TEST(InitialState, OverlapAtImpossibleDensityIsAnError) {
    Scene scene = defaultScene();
    scene.state.density = 3.0;
    try {
        buildInitialState<LinearRotor>(scene, rodPotential(scene));
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("state.density"), std::string::npos);
    }
    scene.state.density = 0.8; // the densest state point of the extremes table still builds
    EXPECT_NO_THROW(buildInitialState<LinearRotor>(scene, rodPotential(scene)));
}

TEST(InitialState, ExplicitParticlesInPsUnits) {
    Scene scene = defaultScene();
    ParticleSpec a, b;
    a.r = Vec3(1, 2, 3);
    a.v = Vec3(10, 0, 0); // Å/ps
    a.axis = Vec3(0, 0, 1);
    a.omega = Vec3(5, 0, 1); // rad/ps; the part along the axis is dropped for rods
    b.r = Vec3(5, 2, 3);
    scene.state.particles = {a, b};
    const auto sys = buildInitialState<LinearRotor>(scene, rodPotential(scene));
    EXPECT_DOUBLE_EQ(sys.bodies[0].v.x(), 1.0); // 10 Å/ps = 1 Å per 100 fs
    EXPECT_DOUBLE_EQ(sys.bodies[0].w.x(), 0.5);
    EXPECT_DOUBLE_EQ(sys.bodies[0].w.z(), 0.0);
}

TEST(InitialState, ExplicitOrientationsAreHonoured) {
    Scene scene = defaultScene();
    ParticleSpec a, b;
    a.orientation = Quat(std::sqrt(0.5), std::sqrt(0.5), 0, 0); // 90° about x: ẑ -> -ŷ
    b.r = Vec3(5, 0, 0);
    b.axis = Vec3(1, 0, 0);
    scene.state.particles = {a, b};
    const auto rods = buildInitialState<LinearRotor>(scene, rodPotential(scene));
    EXPECT_NEAR((rods.bodies[0].s - Vec3(0, -1, 0)).norm(), 0.0, axisTol);
    EXPECT_NEAR((rods.bodies[1].s - Vec3(1, 0, 0)).norm(), 0.0, axisTol);
    scene.body.kind = "symmetric";
    scene.body.inertia = Vec3(1.0, 1.0, 0.5);
    const auto tops = buildInitialState<SymmetricTop>(scene, rodPotential(scene));
    EXPECT_NEAR((SymmetricTop::axis(tops.bodies[0]) - Vec3(0, -1, 0)).norm(), 0.0, axisTol);
    EXPECT_NEAR((SymmetricTop::axis(tops.bodies[1]) - Vec3(1, 0, 0)).norm(), 0.0, axisTol);
}

// fcc and bcc starts: N bodies on a full lattice at the scene's density, each at the lattice's
// nearest-neighbour distance from its closest (a/√2, a√3/2 with a = L/m), thermal as any start.
TEST(InitialState, FccAndBccStartsFillTheBoxAtTheDensity) {
    struct Case {
        const char* lattice;
        int n, m;
        double nearestInCells;
    };
    for (const Case c :
         {Case{"fcc", 500, 5, 1.0 / std::sqrt(2.0)}, Case{"bcc", 432, 6, std::sqrt(3.0) / 2.0}}) {
        Scene scene = defaultScene();
        scene.potential.kind = "lj";
        scene.body.kind = "sphere";
        scene.state.lattice = c.lattice;
        scene.state.n = c.n;
        const auto sys = buildInitialState<Sphere>(scene, ljPotential(scene));
        ASSERT_EQ(sys.size(), c.n);
        EXPECT_NEAR(sys.size() * std::pow(scene.potential.sigma, 3) / sys.box.volume(), 0.5,
                    densityTol);
        checkThermal(sys);
        double minDistance = 1e300;
        for (int i = 0; i < sys.size(); ++i)
            for (int j = i + 1; j < sys.size(); ++j)
                minDistance = std::min(
                    minDistance, sys.box.minimumImage(sys.bodies[i].r - sys.bodies[j].r).norm());
        EXPECT_NEAR(minDistance, c.nearestInCells * sys.box.length / c.m, latticeTol) << c.lattice;
    }
}

// The overlap refusal looks at the new lattices' own nearest neighbours, closer than the cell
// edge a (a/√2 fcc, a√3/2 bcc): at ρ* 3.4 a full fcc lattice of 500 LJ spheres has a = 1.056 σ,
// where U < 0, and neighbours at 0.746 σ, where U = 111 ε > 50 kT = 70 ε: refused, naming the
// remedies that apply to fcc. At ρ* 2.3 they are 0.85 σ apart (U = 17 ε) and build.
TEST(InitialState, OverlapIsJudgedAtTheLatticesOwnNeighbours) {
    Scene scene = defaultScene();
    scene.potential.kind = "lj";
    scene.body.kind = "sphere";
    scene.state.n = 500;
    scene.state.lattice = "fcc";
    scene.state.density = 3.4;
    try {
        buildInitialState<Sphere>(scene, ljPotential(scene));
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("state.density: 3.4"), std::string::npos) << what;
        EXPECT_NE(what.find("lower the density"), std::string::npos) << what;
    }
    scene.state.density = 2.3;
    EXPECT_NO_THROW(buildInitialState<Sphere>(scene, ljPotential(scene)));
}

// On bcc the second shell, 6 at the cell edge a along the axes, is only 15 % farther than the
// first, and bodies aligned along z meet there end to end. The shipped Gay–Berne ellipsoids
// (κ = 3: 3σ long, σ wide) aligned on bcc at ρ* 0.3 have a = (2/0.3)^(1/3) σ = 1.88σ: the first
// shell's pairs, 1.63σ apart at 54.7° to the axis, sit outside their contact distance of 1.31σ,
// and the side and crossed pairs that the worst-case probe tries touch at σ; but each body's
// neighbour along z is 1.88σ away, inside the end-to-end contact of 3σ (U = +∞). Refused, naming
// that pair; at ρ* 0.06 (a = 3.2σ) the same start builds.
TEST(InitialState, OverlapIsJudgedAtTheSecondShellOfFccAndBcc) {
    Scene scene = loadScene(
        std::string(TERRACE_SOURCE_DIR) + "/experiments/scenes/gay-berne-liquid.json",
        {"state.n=128", "state.density=0.3", "state.lattice=bcc", "state.lattice_aspect=1"});
    ASSERT_EQ(scene.state.orientations, "aligned");
    try {
        buildInitialState<LinearRotor>(scene, gayBernePotential(scene));
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("state.density: 0.3"), std::string::npos) << what;
        EXPECT_NE(what.find("U = inf"), std::string::npos) << what;
        // The pair named is one of a cell edge apart along z: bcc's sites 0 and 2 (cell (0,0,1)).
        EXPECT_NE(what.find("lattice neighbours 0 and 2 "), std::string::npos) << what;
        // They are aligned already: the remedies are the density and the lattice.
        EXPECT_EQ(what.find("start them aligned"), std::string::npos) << what;
        EXPECT_NE(what.find("state.lattice_aspect"), std::string::npos) << what;
    }
    scene.state.density = 0.06;
    EXPECT_NO_THROW(buildInitialState<LinearRotor>(scene, gayBernePotential(scene)));
}

} // namespace test_initial_state
