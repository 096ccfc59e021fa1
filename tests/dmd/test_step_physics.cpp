// The physics of step tables in DMD (core/step_potential.hpp) against what is known exactly or
// published, each pressure from the engine's collision (impulse) virial,
//     P = (2 K_trans + ΔW/Δt) / (3V),   Z = PV/(N kT),
// with kT the time average of the kinetic temperature over 3(N − 1) degrees of freedom:
//   - hard spheres (a table with a hard core only) against Carnahan–Starling,
//     Z = (1 + η + η² − η³)/(1 − η)³ (J. Chem. Phys. 51, 635 (1969); within ~0.5 % of simulated
//     hard spheres up to η = 0.45);
//   - the square well of range λ at low density against its virial coefficients,
//     Z − 1 = B2 ρ + B3 ρ² + O(ρ³),  B2 = (2πσ³/3)[1 − (λ³ − 1)(e^{βε} − 1)];
//   - mixtures (core/step_mixture.hpp), each pair in its own σ_ab: a binary mixture of additive
//     hard spheres against the Boublík–Mansoori–Carnahan–Starling–Leland equation of state, and
//     a dilute square-well mixture against its B2 = Σ_ab x_a x_b B2(σ_ab).
// Units: σ = 1 Å, ε = 1 kJ/mol, m = 1 g/mol, so that kT = T* kJ/mol and the engine's time unit
// (100 fs) is about σ/√(kT/m).
#include "analysis/block_average.hpp"
#include "core/initial_state.hpp"
#include "core/species_sphere.hpp"
#include "core/sphere.hpp"
#include "core/step_mixture.hpp"
#include "core/step_potential.hpp"
#include "dmd/scene_engine.hpp"
#include "dmd/testing.hpp"
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <numbers>
#include <vector>

namespace test_step_physics {

using terrace::dmd::testing::Probe;
using namespace terrace;

namespace {

using StepEngine = dmd::SceneEngine<Sphere, StepPotential>;
using MixtureEngine = dmd::SceneEngine<SpeciesSphere, StepMixture>;

struct Measured {
    double z, zError; // compressibility factor and its block error
    // Z − 1 as the collisions' virial over twice the kinetic energy, W/(2K), and its block error:
    // Z − 1 without the −1/N that the fixed centre of mass takes from the kinetic term's N kT
    // (3(N − 1) degrees of freedom), which at low density is as large as B2ρ's error (−1/(Nρ) in
    // (Z − 1)/ρ: −0.1 σ³ at N 2000, ρ 0.005).
    double excess, excessError;
    double kT; // mean kinetic temperature, kJ/mol
    double u;  // mean potential energy per body, kJ/mol
};

/// Z measured on the engine e of scene s (N bodies), as measureZ below says.
template <class E>
Measured measureZ(E& e, const Scene& s, int n, double warmup, int blocks, double blockTime) {
    const double V = std::pow(s.boxLength(), 3);
    e.advanceTo(warmup);
    const double energy = e.kineticEnergy() + e.potentialEnergy();
    std::vector<double> z, excess, temperature, u;
    constexpr int parts = 20;
    for (int b = 0; b < blocks; ++b) {
        const double t0 = e.time(), w0 = e.virial();
        double kin = 0.0, pot = 0.0;
        for (int k = 1; k <= parts; ++k) {
            e.advanceTo(t0 + blockTime * k / parts);
            kin += e.translationalKineticEnergy() / parts;
            pot += e.potentialEnergy() / parts;
        }
        const double pressure = (2.0 * kin + (e.virial() - w0) / blockTime) / (3.0 * V);
        const double kTb = 2.0 * kin / (3.0 * (n - 1.0));
        z.push_back(pressure * V / (n * kTb));
        excess.push_back((e.virial() - w0) / blockTime / (2.0 * kin));
        temperature.push_back(kTb);
        u.push_back(pot / n);
    }
    // Energy to round-off over the whole run (a reflection or crossing conserves it exactly).
    EXPECT_NEAR(e.kineticEnergy() + e.potentialEnergy(), energy, 1e-10 * e.kineticEnergy());
    const analysis::Estimate zs = analysis::blockMean(z, blocks);
    const analysis::Estimate xs = analysis::blockMean(excess, blocks);
    return {zs.mean,
            zs.err,
            xs.mean,
            xs.err,
            analysis::blockMean(temperature, blocks).mean,
            analysis::blockMean(u, blocks).mean};
}

/// Z of the table `potential` (a scene's potential section, kind steps) at number density rho
/// (σ⁻³), N bodies started at temperature kT: `warmup` time units forgotten, then `blocks`
/// blocks of `blockTime`, each with its kinetic energy averaged over 20 sub-intervals. With
/// `species` (a scene's list), the mixture of them; `lattice` the start's (simple cubic if none).
Measured measureZ(nlohmann::json potential, int n, double rho, double kT, double warmup, int blocks,
                  double blockTime, const nlohmann::json& species = nullptr,
                  const char* lattice = nullptr) {
    potential["kind"] = "steps";
    potential["epsilon"] = 1.0;
    potential["sigma"] = 1.0;
    nlohmann::json j = {{"body", {{"kind", "sphere"}, {"mass", 1.0}}},
                        {"potential", potential},
                        {"state", {{"n", n}, {"density", rho}, {"temperature", kT}}}};
    if (!species.is_null()) j["species"] = species;
    if (lattice) j["state"]["lattice"] = lattice;
    const Scene s = sceneFromJson(j, "<steps>");
    if (species.is_null()) {
        StepEngine e(buildInitialState<Sphere, StepPotential>(s, stepPotential(s)), s);
        return measureZ(e, s, n, warmup, blocks, blockTime);
    }
    MixtureEngine e(buildInitialState<SpeciesSphere, StepMixture>(s, stepMixture(s)), s);
    return measureZ(e, s, n, warmup, blocks, blockTime);
}

} // namespace

TEST(StepPhysics, HardSpheresFollowCarnahanStarling) {
    for (double eta : {0.2, 0.35, 0.45}) {
        const double cs = (1.0 + eta + eta * eta - eta * eta * eta) / std::pow(1.0 - eta, 3);
        const double rho = 6.0 * eta / std::numbers::pi;
        const Measured m = measureZ({{"steps", nlohmann::json::array()}, {"hard_core", 1.0}}, 500,
                                    rho, 1.0, 5.0, 20, 1.0);
        // The block error and Carnahan–Starling's own accuracy (0.5 % of Z at η = 0.45).
        // Measured (N 500, 20 blocks of 100 fs): Z = 2.412 ± 0.012, 5.215 ± 0.018, 9.404 ± 0.027
        // against CS 2.406, 5.206, 9.385: within 1σ at each η.
        EXPECT_NEAR(m.z, cs, 4.0 * m.zError + 0.005 * cs)
            << "η = " << eta << ": Z = " << m.z << " ± " << m.zError << ", CS " << cs;
        EXPECT_LT(m.zError, 0.01 * cs) << "η = " << eta; // the check has teeth
        EXPECT_NEAR(m.kT, 1.0, 1e-9);                    // reflections keep the kinetic energy
        std::printf("hard spheres η = %.2f: Z = %.4f ± %.4f, Carnahan–Starling %.4f\n", eta, m.z,
                    m.zError, cs);
    }
}

TEST(StepPhysics, DiluteSquareWellFollowsItsVirialCoefficients) {
    constexpr double lambda = 1.5, rho = 0.005;
    const Measured m =
        measureZ({{"steps", "square_well"}, {"lambda", lambda}}, 2000, rho, 1.5, 200.0, 20, 100.0);
    // B2 and, for λ ≤ 2, the closed-form B3 of the square well (Kihara 1953; as given by Barker
    // & Henderson, Rev. Mod. Phys. 48, 587 (1976)), in b0 = 2πσ³/3 and x = e^{βε} − 1:
    //   B3/b0² = [5 − c1 x − c2 x² − c3 x³]/8,  c1 = λ⁶ − 18λ⁴ + 32λ³ − 15,
    //   c2 = 2λ⁶ − 36λ⁴ + 32λ³ + 18λ² − 16,  c3 = 6λ⁶ − 18λ⁴ + 18λ² − 6.
    // B3 ρ is some 0.02 σ³ here, a fifth of the error allowed: the check is of B2. Measured
    // (N 2000, T* 1.532): (Z − 1)/ρ = −2.430 ± 0.089 σ³ against B2 + B3ρ = −2.468 σ³.
    const double l2 = lambda * lambda, l3 = l2 * lambda, l4 = l2 * l2, l6 = l3 * l3;
    const double x = std::expm1(1.0 / m.kT), b0 = 2.0 * std::numbers::pi / 3.0;
    const double b2 = b0 * (1.0 - (l3 - 1.0) * x);
    const double c1 = l6 - 18 * l4 + 32 * l3 - 15, c2 = 2 * l6 - 36 * l4 + 32 * l3 + 18 * l2 - 16,
                 c3 = 6 * l6 - 18 * l4 + 18 * l2 - 6;
    const double b3 = b0 * b0 * (5.0 - c1 * x - c2 * x * x - c3 * x * x * x) / 8.0;
    const double expected = b2 + b3 * rho; // (Z − 1)/ρ to first order in ρ
    const double measured = m.excess / rho, error = m.excessError / rho;
    EXPECT_NEAR(measured, expected, 4.0 * error)
        << "(Z − 1)/ρ = " << measured << " ± " << error << ", B2 + B3ρ = " << expected << " at kT "
        << m.kT;
    EXPECT_LT(error, 0.1 * std::abs(b2)); // the check has teeth: B2's sign and size
    std::printf("square well λ 1.5, ρ* %.3f, T* %.4f: (Z − 1)/ρ = %.3f ± %.3f, B2 + B3ρ = %.3f "
                "(B2 %.3f) σ³\n",
                rho, m.kT, measured, error, expected, b2);
}

// A binary mixture of additive hard spheres, σ_B = 0.6 σ_A, equal numbers, B half as heavy, on an
// fcc start: each pair reflects at its own σ_ab = (σ_a + σ_b)/2. Against the BMCSL equation of
// state (T. Boublík, J. Chem. Phys. 53, 471 (1970); G. A. Mansoori, N. F. Carnahan, K. E.
// Starling and T. W. Leland, J. Chem. Phys. 54, 1523 (1971)), with ζ_n = (π/6) ρ Σ_a x_a σ_a^n:
//     Z = (6/πρ) [ζ0/(1 − ζ3) + 3ζ1ζ2/(1 − ζ3)² + (3 − ζ3)ζ2³/(1 − ζ3)³],
// which reduces to Carnahan–Starling for one species and lies within about 1 % of simulated
// binary mixtures of this size ratio up to a packing of 0.4. Measured (N 500, 20 blocks of 100
// fs): Z = 3.686 ± 0.015 and 6.267 ± 0.016 against BMCSL's 3.675 and 6.287 at η = 0.3 and 0.4.
TEST(StepPhysics, HardSphereMixtureFollowsBmcsl) {
    const double x[2] = {0.5, 0.5}, sigma[2] = {1.0, 0.6};
    const nlohmann::json species = {
        {{"name", "A"}, {"fraction", x[0]}, {"sigma", sigma[0]}},
        {{"name", "B"}, {"fraction", x[1]}, {"sigma", sigma[1]}, {"mass", 0.5}}};
    for (double eta : {0.3, 0.4}) {
        auto moment = [&](int k) {
            return x[0] * std::pow(sigma[0], k) + x[1] * std::pow(sigma[1], k);
        };
        const double rho = 6.0 * eta / (std::numbers::pi * moment(3));
        double zeta[4];
        for (int k = 0; k < 4; ++k)
            zeta[k] = std::numbers::pi / 6.0 * rho * moment(k);
        const double g = 1.0 - zeta[3];
        const double bmcsl = 6.0 / (std::numbers::pi * rho) *
                             (zeta[0] / g + 3.0 * zeta[1] * zeta[2] / (g * g) +
                              (3.0 - zeta[3]) * std::pow(zeta[2], 3) / (g * g * g));
        nlohmann::json table = {{"steps", nlohmann::json::array()}, {"hard_core", 1.0}};
        const Measured m = measureZ(table, 500, rho, 1.0, 5.0, 20, 1.0, species, "fcc");
        EXPECT_NEAR(m.z, bmcsl, 4.0 * m.zError + 0.01 * bmcsl)
            << "η = " << eta << ": Z = " << m.z << " ± " << m.zError << ", BMCSL " << bmcsl;
        EXPECT_LT(m.zError, 0.01 * bmcsl) << "η = " << eta; // the check has teeth
        EXPECT_NEAR(m.kT, 1.0, 1e-9);
        std::printf("hard-sphere mixture η = %.2f: Z = %.4f ± %.4f, BMCSL %.4f\n", eta, m.z,
                    m.zError, bmcsl);
    }
}

// A dilute binary square-well mixture, λ = 1.5 in each pair's own σ_ab, at its own depth ε_ab:
// σ_B = 0.5 σ_A, ε_B = 0.3 ε_A, equal numbers (Lorentz–Berthelot: σ_AB = 0.75 σ_A, ε_AB = √0.3
// ε_A). (Z − 1)/ρ → B2 = Σ_ab x_a x_b B2(σ_ab, ε_ab), each pair's B2 that of the one-component well
// above with its σ_ab and ε_ab, here −0.65 σ³. One depth ε_A for every pair would give −1.29 σ³,
// far outside the error allowed (the σ_ab are held to BMCSL above). Measured (N 1000, T* 1.513):
// (Z − 1)/ρ = −0.624 ± 0.049 σ³ against B2 = −0.625 σ³.
TEST(StepPhysics, DiluteSquareWellMixtureFollowsItsSecondVirialCoefficient) {
    constexpr double lambda = 1.5, rho = 0.006;
    const double x[2] = {0.5, 0.5}, sigma[2] = {1.0, 0.5}, epsilon[2] = {1.0, 0.3};
    const nlohmann::json species = {
        {{"name", "A"}, {"fraction", x[0]}, {"sigma", sigma[0]}, {"epsilon", epsilon[0]}},
        {{"name", "B"}, {"fraction", x[1]}, {"sigma", sigma[1]}, {"epsilon", epsilon[1]}}};
    const Measured m = measureZ({{"steps", "square_well"}, {"lambda", lambda}}, 1000, rho, 1.5,
                                200.0, 20, 100.0, species);
    const double l3 = lambda * lambda * lambda;
    double b2 = 0.0;
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
            const double s = 0.5 * (sigma[a] + sigma[b]), e = std::sqrt(epsilon[a] * epsilon[b]);
            b2 += x[a] * x[b] * 2.0 * std::numbers::pi / 3.0 * s * s * s *
                  (1.0 - (l3 - 1.0) * std::expm1(e / m.kT));
        }
    const double measured = m.excess / rho, error = m.excessError / rho;
    // B3ρ is left out: for the one-component well it is some 0.02 σ³ at ρ 0.005 (above), and
    // smaller here where the mean σ³ and the wells are smaller.
    EXPECT_NEAR(measured, b2, 4.0 * error + 0.05)
        << "(Z − 1)/ρ = " << measured << " ± " << error << ", B2 " << b2 << " at kT " << m.kT;
    EXPECT_LT(error, 0.15 * std::abs(b2)); // the check has teeth: B2's sign and size
    std::printf("square-well mixture λ 1.5, ρ* %.3f, T* %.4f: (Z − 1)/ρ = %.3f ± %.3f, B2 %.3f "
                "σ³\n",
                rho, m.kT, measured, error, b2);
}

} // namespace test_step_physics
