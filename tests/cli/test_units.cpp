// Reduced units end to end, in-process: one physical scene given in real units and in lj units
// runs the same trajectory bit for bit (its times given in τ convert exactly to the same fs),
// while thermo.csv, the CSVs, summary.json's "reduced" entry and the closing lines come out in
// T*, ε per body, τ, σ and P*, each the real result converted.
#include "cli/run_command.hpp"
#include "cli/scene_check.hpp"
#include "cli/summary_line.hpp"
#include "core/scene_units.hpp"
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <unistd.h>

namespace test_units {

using namespace terrace;
using nlohmann::json;

namespace {

/// Argon: σ 3.405 Å, ε/k_B 119.8 K, m 39.948 g/mol (τ ≈ 2.16 ps, no round number of fs).
constexpr double sigma = 3.405, epsilon = 119.8 * units::kB, mass = 39.948;

struct Csv {
    std::vector<std::string> names;
    std::vector<std::vector<double>> rows;
};

Csv readCsv(const std::filesystem::path& path) {
    std::ifstream in(path);
    Csv c;
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::stringstream fields(line);
        std::string f;
        std::vector<std::string> text;
        while (std::getline(fields, f, ','))
            text.push_back(f);
        if (c.names.empty()) {
            c.names = text;
            continue;
        }
        std::vector<double> row;
        for (const auto& x : text)
            row.push_back(x == "nan" ? std::nan("") : std::stod(x));
        c.rows.push_back(row);
    }
    return c;
}

std::string readText(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/// 216 argon atoms at ρ* 0.7, T* 1.2: the times in real units (fs and ps), or the same times in
/// τ through the unit-free twins, each checked to convert back to exactly the same fs.
json argon(const std::string& engine, bool reduced) {
    json j = {{"name", "argon"},
              {"engine", engine},
              {"body", {{"kind", "sphere"}, {"mass", mass}}},
              {"potential",
               {{"kind", "lj"}, {"sigma", sigma}, {"epsilon", epsilon}, {"cutoff", {2.5, 3.0}}}},
              {"state", {{"n", 216}, {"density", 0.7}, {"temperature", 1.2}}}};
    const std::vector<std::tuple<const char*, const char*, const char*, double, Dimension>> times{
        {"run", "equilibrate_ps", "equilibrate", 0.4, Dimension::TimePs},
        {"run", "time_ps", "time", 1.6, Dimension::TimePs},
        {"run", "sample_fs", "sample", 20.0, Dimension::TimeFs},
        {"run", "thermostat_fs", "thermostat", 20.0, Dimension::TimeFs},
        {"output", "trajectory_every_fs", "trajectory_every", 40.0, Dimension::TimeFs},
        {"output", "thermo_every_fs", "thermo_every", 40.0, Dimension::TimeFs},
        {"smd", "dt_fs", "dt", 4.0, Dimension::TimeFs},
        {"dmd", "horizon_fs", "horizon", 8.0, Dimension::TimeFs}};
    const UnitSystem u = UnitSystem::lj(sigma, epsilon, mass);
    if (reduced) j["units"] = "lj";
    for (const auto& [section, named, free, value, d] : times) {
        const double inTau = u.fromReal(value, d);
        EXPECT_EQ(u.toReal(inTau, d), value) << free; // else no bit-for-bit comparison
        if (reduced)
            j[section][free] = inTau;
        else
            j[section][named] = value;
    }
    return j;
}

struct Outcome {
    json summary;
    std::filesystem::path dir;
};

Outcome run(const json& scene, const std::string& label) {
    Scene s = sceneFromJson(scene, label);
    cli::resolveEngineSections(s, label);
    const auto dir = std::filesystem::temp_directory_path() /
                     ("terrace-units-" + label + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    return {cli::runScene(s, {dir, cli::OutputMode::Fresh, true, nullptr}).summary, dir};
}

/// Each value of `lj` equals the real one times `factor` within round-off.
void expectScaled(const std::vector<double>& lj, const std::vector<double>& real, double factor,
                  const std::string& what) {
    ASSERT_EQ(lj.size(), real.size()) << what;
    for (std::size_t k = 0; k < lj.size(); ++k)
        if (std::isnan(real[k]))
            EXPECT_TRUE(std::isnan(lj[k])) << what << " " << k;
        else
            EXPECT_NEAR(lj[k], real[k] * factor, 1e-13 * std::abs(real[k] * factor) + 1e-300)
                << what << " " << k;
}

std::vector<double> column(const Csv& c, std::size_t i) {
    std::vector<double> x;
    for (const auto& r : c.rows)
        x.push_back(r.at(i));
    return x;
}

} // namespace

TEST(Units, RealAndLjGiveTheSameTrajectoryAndConvertedResults) {
    const UnitSystem u = UnitSystem::lj(sigma, epsilon, mass);
    for (const std::string engine : {"dmd", "smd"}) {
        const Outcome real = run(argon(engine, false), engine + "-real");
        const Outcome lj = run(argon(engine, true), engine + "-lj");
        // The same run: every frame of the trajectory byte for byte, every energy.
        const std::string frames = readText(real.dir / "trajectory.xyz");
        ASSERT_FALSE(frames.empty());
        EXPECT_EQ(readText(lj.dir / "trajectory.xyz"), frames) << engine;
        EXPECT_EQ(readText(lj.dir / "initial.xyz"), readText(real.dir / "initial.xyz"));
        for (const char* key : {"potential_energy_mean", "temperature_K", "simulated_ps"})
            EXPECT_EQ(lj.summary[key], real.summary[key]) << engine << " " << key;
        EXPECT_EQ(lj.summary["energy"], real.summary["energy"]);
        EXPECT_EQ(lj.summary["pressure"], real.summary["pressure"]);
        EXPECT_FALSE(real.summary.contains("reduced"));
        EXPECT_FALSE(real.summary.contains("units"));

        // summary.json: "reduced" holds the real results converted.
        ASSERT_TRUE(lj.summary.contains("reduced"));
        EXPECT_EQ(lj.summary["units"], "lj");
        const json& r = lj.summary["reduced"];
        const double n = 216;
        EXPECT_NEAR(r["temperature_target"].get<double>(), 1.2, 1e-14);
        EXPECT_NEAR(r["temperature"].get<double>(),
                    real.summary["temperature_K"].get<double>() * units::kB / epsilon, 1e-13);
        EXPECT_NEAR(r["potential_energy_per_body"].get<double>(),
                    real.summary["potential_energy_mean"].get<double>() / epsilon / n, 1e-13);
        // P* = P σ³/ε, from the pressure in bar (units::bar: kJ/mol/Å³ to bar).
        EXPECT_NEAR(r["pressure"].get<double>(),
                    real.summary["pressure"]["mean_bar"].get<double>() / units::bar(1.0) * sigma *
                        sigma * sigma / epsilon,
                    1e-12 * (1.0 + std::abs(r["pressure"].get<double>())));
        EXPECT_NEAR(r["simulated_tau"].get<double>(), 1.6 / u.tauPs(), 1e-13);
        EXPECT_EQ(r["scale"]["tau_fs"].get<double>(), u.tauFs());
        const double d = real.summary["analysis"]["diffusion"]["einstein_angstrom2_per_ps"];
        EXPECT_NEAR(r["diffusion"]["einstein"].get<double>(), d * u.tauPs() / (sigma * sigma),
                    1e-13 * std::abs(d));
        EXPECT_EQ(r.contains("collisions_per_tau"), engine == "dmd");

        // thermo.csv: time in τ, energies per body in ε, T*, P*.
        const Csv tr = readCsv(real.dir / "thermo.csv"), tl = readCsv(lj.dir / "thermo.csv");
        ASSERT_GE(tl.names.size(), 8u);
        EXPECT_EQ(tl.names[0], "time_tau");
        EXPECT_EQ(tl.names[3], "potential_per_body");
        EXPECT_EQ(tl.names[6], "temperature_reduced");
        EXPECT_EQ(tl.names[7], "pressure_reduced");
        EXPECT_EQ(tr.names[0], "time_ps");
        expectScaled(column(tl, 0), column(tr, 0), 1.0 / u.tauPs(), "time");
        for (std::size_t c = 1; c <= 5; ++c)
            expectScaled(column(tl, c), column(tr, c), 1.0 / (epsilon * n), tl.names[c]);
        expectScaled(column(tl, 6), column(tr, 6), units::kB / epsilon, "temperature");
        expectScaled(column(tl, 7), column(tr, 7),
                     std::pow(sigma, 3) / epsilon / units::barPerKjPerMolPerA3, "pressure");

        // The analysis' CSVs: r in σ, t in τ, the MSD in σ².
        const Csv rr = readCsv(real.dir / "rdf.csv"), rl = readCsv(lj.dir / "rdf.csv");
        EXPECT_EQ(rl.names[0], "r_sigma");
        EXPECT_EQ(rr.names[0], "r_angstrom");
        expectScaled(column(rl, 0), column(rr, 0), 1.0 / sigma, "r");
        expectScaled(column(rl, 1), column(rr, 1), 1.0, "g");
        const Csv mr = readCsv(real.dir / "msd.csv"), ml = readCsv(lj.dir / "msd.csv");
        EXPECT_EQ(ml.names, (std::vector<std::string>{"t_tau", "msd_sigma2", "err"}));
        expectScaled(column(ml, 0), column(mr, 0), 1.0 / u.tauPs(), "t");
        expectScaled(column(ml, 1), column(mr, 1), 1.0 / (sigma * sigma), "msd");
        const Csv vl = readCsv(lj.dir / "vacf.csv");
        EXPECT_EQ(vl.names, (std::vector<std::string>{"t_tau", "c", "err"}));

        // scene.json records the units; read again, it is the scene that ran.
        const json recorded = json::parse(readText(lj.dir / "scene.json"));
        EXPECT_EQ(recorded["units"], "lj");
        EXPECT_FALSE(json::parse(readText(real.dir / "scene.json")).contains("units"));

        // The closing lines: T*, U/N in ε beside the total, P*; real ones U/N beside ⟨U⟩.
        const std::string line = cli::runSummaryText("argon", lj.summary, lj.dir);
        for (const char* needle :
             {" τ (τ = ", "T* = ", "(target 1.2)", "U/N = ", " ε (U = ", "P* = "})
            EXPECT_NE(line.find(needle), std::string::npos) << needle << "\n" << line;
        EXPECT_EQ(line.find(" K "), std::string::npos) << line;
        const std::string realLine = cli::runSummaryText("argon", real.summary, real.dir);
        for (const char* needle :
             {" ps simulated", "T = ", "<U>/N = ", "kJ/mol (<U> = ", "bar (P* = "})
            EXPECT_NE(realLine.find(needle), std::string::npos) << needle << "\n" << realLine;
        std::filesystem::remove_all(real.dir);
        std::filesystem::remove_all(lj.dir);
    }
}

} // namespace test_units
