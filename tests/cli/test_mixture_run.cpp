// The shipped Kob–Andersen scene (experiments/scenes/kob-andersen.json) run end to end, in-process,
// by each engine as `terrace run` runs it: both finish with their documented files, DMD with its
// energy constant to round-off, both at the scene's temperature with the mixture's U per body;
// and `terrace export lammps` writes its deck. The same run of rods among spheres
// (rods-in-solvent.json).
#include "cli/lammps_deck.hpp"
#include "cli/run_command.hpp"
#include "cli/scene_check.hpp"
#include "cli/summary_line.hpp"
#include "core/initial_state.hpp"
#include "core/lj_mixture.hpp"
#include "core/smoothed_potential.hpp"
#include "core/species_sphere.hpp"
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <numbers>
#include <sstream>
#include <unistd.h>

namespace test_mixture_run {

using namespace terrace;
using nlohmann::json;

namespace {

const std::string sceneFile =
    std::string(TERRACE_SOURCE_DIR) + "/experiments/scenes/kob-andersen.json";

json runShort(const std::string& engine, const std::string& file = sceneFile,
              const std::vector<std::string>& lengths = {"run.equilibrate=1", "run.time=2",
                                                         "analysis.max_lag=0.5"}) {
    // A short run: by default the scene's N 500, 1 τ of equilibration and 2 τ of production
    // (τ = 100 fs).
    std::vector<std::string> overrides = lengths;
    overrides.push_back("engine=" + engine);
    Scene s = loadScene(file, overrides);
    cli::resolveEngineSections(s, file);
    const auto dir = std::filesystem::temp_directory_path() /
                     ("terrace-mixture-" + engine + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    json summary = cli::runScene(s, {dir, cli::OutputMode::Fresh, true, nullptr}).summary;
    for (const char* f : {"summary.json", "scene.json", "rdf.csv", "msd.csv", "thermo.csv"})
        EXPECT_TRUE(std::filesystem::exists(dir / f)) << engine << " " << f;
    std::filesystem::remove_all(dir);
    return summary;
}

} // namespace

TEST(MixtureScene, KobAndersenRunsInBothEngines) {
    for (const std::string engine : {"dmd", "smd"}) {
        const json s = runShort(engine);
        EXPECT_EQ(s["n_bodies"], 500) << engine;
        const json& r = s["reduced"];
        EXPECT_NEAR(r["temperature"].get<double>(), 2.0, 0.3) << engine;
        // The continuous U per body (DMD's on its configurations: its terraced one lies a
        // terrace's worth above). This scene, each pair cut at its own σ_ab, at N 500 over 5 τ
        // gives −5.37 ε (SMD) and −5.32 ε (DMD, ΔV = kT/4; −5.43 and −5.34 on the one cutoff); a
        // run that lost the unlike pairs' ε_AB = 1.5 to Lorentz–Berthelot's 0.71 would sit well
        // above the range, one without a cutoff below it.
        const double u = engine == "dmd"
                             ? r["configurational"]["potential_energy_per_body"].get<double>()
                             : r["potential_energy_per_body"].get<double>();
        EXPECT_GT(u, -6.0) << engine;
        EXPECT_LT(u, -4.8) << engine;
        if (engine == "dmd") {
            EXPECT_LT(std::abs(s["energy"]["max_abs_dev"].get<double>()),
                      1e-9 * std::abs(s["energy"]["mean"].get<double>()));
        }
    }
}

// The shipped rods among spheres (experiments/scenes/rods-in-solvent.json): both engines reach the
// scene's temperature with 5 degrees of freedom per rod and 3 per sphere (counting the spheres'
// 2 missing ones would read 350 K for 505 K), the OACF is the rods' alone, each species has its D,
// and DMD keeps its energy to round-off.
TEST(MixtureScene, RodsInSolventRunsInBothEngines) {
    const std::string file =
        std::string(TERRACE_SOURCE_DIR) + "/experiments/scenes/rods-in-solvent.json";
    for (const std::string engine : {"dmd", "smd"}) {
        const json s =
            runShort(engine, file,
                     {"run.equilibrate_ps=0.9", "run.time_ps=1.8", "analysis.max_lag_ps=0.45"});
        EXPECT_EQ(s["n_bodies"], 512) << engine;
        EXPECT_NEAR(s["temperature_K"].get<double>() / s["temperature_target_K"].get<double>(), 1.0,
                    0.1)
            << engine;
        EXPECT_EQ(s["analysis"]["oacf"]["species"], json::array({"rod"})) << engine;
        for (const char* name : {"rod", "solvent"})
            EXPECT_TRUE(s["analysis"]["diffusion"]["species"].contains(name)) << engine << name;
        // The continuous U per body: −7.44 kJ/mol (DMD at kT/2, on its configurations) and −7.25
        // (SMD) over 9 ps at N 512; the range leaves a short run's noise and the start's heat.
        const double u = (engine == "dmd" ? s["configurational"]["potential_energy_mean"]
                                          : s["potential_energy_mean"])
                             .get<double>() /
                         512;
        EXPECT_GT(u, -8.4) << engine;
        EXPECT_LT(u, -6.3) << engine;
        if (engine == "dmd") {
            EXPECT_LT(std::abs(s["energy"]["max_abs_dev"].get<double>()),
                      1e-9 * std::abs(s["energy"]["mean"].get<double>()));
        }
    }
}

// The deck of a mixture: each species an atom type with its mass (B three times as heavy here),
// the bodies' types as terrace dealt them, each pair of species a table of its own ε and σ, and
// the first frame's U under the deck's tables within the tables' tolerance of terrace's.
TEST(MixtureScene, ExportWritesEachSpeciesATypeAndEachPairATable) {
    Scene s = loadScene(sceneFile, {"state.n=256", "state.density=0.85"});
    s.species[1].mass = 3.0;
    const cli::LammpsDeck deck = cli::lammpsDeck(s);
    EXPECT_EQ(deck.atoms, 256);
    EXPECT_NE(deck.data.find("\n256 atoms\n2 atom types\n"), std::string::npos);
    EXPECT_NE(deck.data.find("Masses\n\n1 1\n2 3\n\nAtoms # atomic"), std::string::npos)
        << deck.data.substr(0, 400);
    // The types as the lattice start deals the species.
    const auto sys =
        buildInitialState<SpeciesSphere>(s, Smoothed<LJMixture>{ljMixture(s), sceneCutoff(s)});
    std::istringstream atoms(deck.data.substr(deck.data.find("Atoms # atomic\n\n") + 16));
    for (int i = 0; i < 256; ++i) {
        int id = 0, type = 0;
        atoms >> id >> type;
        std::string rest;
        std::getline(atoms, rest);
        ASSERT_EQ(id, i + 1);
        ASSERT_EQ(type, sys.bodies[i].species + 1) << i;
    }
    // Each pair's table ends at its own r_u = 3 σ_ab (the scene cuts each pair at its own σ, as
    // Kob and Andersen do), and LAMMPS cuts it there.
    const std::pair<const char*, double> coefficients[] = {
        {"pair_coeff      1 1 pair.table TERRACE_LJ_A_A ", 3.0},
        {"pair_coeff      1 2 pair.table TERRACE_LJ_A_B ", 3.0 * 0.8},
        {"pair_coeff      2 2 pair.table TERRACE_LJ_B_B ", 3.0 * 0.88}};
    ASSERT_TRUE(s.potential.cutoff_per_pair);
    for (const auto& [line, cutoff] : coefficients) {
        const auto at = deck.input.find(line);
        ASSERT_NE(at, std::string::npos) << line;
        EXPECT_DOUBLE_EQ(std::stod(deck.input.substr(at + std::strlen(line))), cutoff) << line;
    }
    // Each table's parameters: ε_AB 1.5, σ_AB 0.8 as Kob and Andersen give them.
    EXPECT_NE(deck.table.find("\nTERRACE_LJ_A_B\n"), std::string::npos);
    EXPECT_NE(deck.table.find("of A_B, eps = 1.5 kJ/mol, sigma = 0.80000000000000004 Å"),
              std::string::npos);
    ASSERT_TRUE(std::isfinite(deck.energyTerrace));
    EXPECT_NEAR(deck.energyDeck, deck.energyTerrace, 2.5e-7 * std::abs(deck.energyTerrace));
    EXPECT_NE(deck.energyDeck, deck.energyTerrace); // a table is not the formula
}

// The shipped binary hard-sphere mixture (experiments/scenes/hard-sphere-mixture.json: σ_B =
// 0.6 σ_A, equal numbers, packing 0.4 on an fcc start), each pair reflecting at its own σ_ab, run
// by `terrace run`'s path: no energy, the kinetic energy to round-off, both species' and every
// partial g(r), and Z within 3 % of the BMCSL equation of state (tests/dmd/test_step_physics.cpp
// holds it to 1 %; this run is short). SMD refuses the scene.
TEST(MixtureScene, HardSphereMixtureRunsInDmd) {
    const std::string file =
        std::string(TERRACE_SOURCE_DIR) + "/experiments/scenes/hard-sphere-mixture.json";
    Scene s = loadScene(file, {"run.equilibrate=2", "run.time=10", "analysis.max_lag=1"});
    cli::resolveEngineSections(s, file);
    const auto dir = std::filesystem::temp_directory_path() /
                     ("terrace-hs-mixture-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    const json summary = cli::runScene(s, {dir, cli::OutputMode::Fresh, true, nullptr}).summary;
    std::ifstream rdf(dir / "rdf.csv");
    std::string header;
    std::getline(rdf, header);
    std::filesystem::remove_all(dir);
    for (const char* column : {",g_A_A,", ",g_A_B,", ",g_B_B,"})
        EXPECT_NE(header.find(column), std::string::npos) << header;
    EXPECT_EQ(summary["potential_energy_mean"].get<double>(), 0.0);
    // With U 0 throughout there is no ⟨U⟩ to measure the energy's fluctuation by: said so.
    const std::string line = cli::runSummaryText("hs", summary, dir);
    EXPECT_NE(line.find("energy rel. fluctuation undefined (<U> = 0)"), std::string::npos) << line;
    EXPECT_LT(summary["energy"]["max_abs_dev"].get<double>(),
              1e-12 * std::abs(summary["energy"]["mean"].get<double>()));
    // ζ_n = (π/6) ρ Σ x_a σ_a^n, Z = (6/πρ)[ζ0/(1−ζ3) + 3ζ1ζ2/(1−ζ3)² + (3−ζ3)ζ2³/(1−ζ3)³].
    const double rho = s.state.density, pi = std::numbers::pi;
    auto zeta = [&](int n) { return pi / 6.0 * rho * 0.5 * (1.0 + std::pow(0.6, n)); };
    const double g = 1.0 - zeta(3);
    const double bmcsl = 6.0 / (pi * rho) *
                         (zeta(0) / g + 3.0 * zeta(1) * zeta(2) / (g * g) +
                          (3.0 - zeta(3)) * std::pow(zeta(2), 3) / (g * g * g));
    const json& p = summary["pressure"];
    const double z =
        p["mean_reduced"].get<double>() / (rho * summary["reduced"]["temperature"].get<double>());
    EXPECT_NEAR(z, bmcsl, 0.03 * bmcsl) << "Z = " << z << ", BMCSL " << bmcsl;
    EXPECT_THROW(loadScene(file, {"engine=smd"}), SceneError);
}

} // namespace test_mixture_run
