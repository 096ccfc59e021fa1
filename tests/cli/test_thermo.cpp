// The pressure and thermo.csv from production samples (cli/thermo.hpp, core/pressure.hpp): the
// unit conversion and both virial forms on hand-made numbers, the rows of thermo.csv, and an ideal
// gas run by both engines, whose pressure is its kinetic term alone, P = 2K_trans/(3V) = ρkT.
#include "cli/run_command.hpp"
#include "cli/sample_statistics.hpp"
#include "cli/thermo.hpp"
#include "core/initial_state.hpp"
#include "core/pressure.hpp"
#include "core/sphere.hpp"
#include "core/units.hpp"
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <unistd.h>

namespace test_thermo {

using namespace terrace;
using cli::SampleRecord;
using cli::VirialKind;

namespace {

/// Relative agreement expected of a few operations' round-off.
constexpr double roundOff = 1e-14;

std::vector<std::string> split(const std::string& text, char by) {
    std::vector<std::string> out;
    std::stringstream in(text);
    std::string part;
    while (std::getline(in, part, by))
        out.push_back(part);
    return out;
}

std::vector<double> numbers(const std::string& row) {
    std::vector<double> x;
    for (const auto& f : split(row.substr(0, row.size() - 1), ','))
        x.push_back(std::strtod(f.c_str(), nullptr));
    return x;
}

SampleRecord sample(double time, double kTrans, double virial, double collisions = 0.0) {
    SampleRecord s;
    s.time = time, s.tPs = units::toPs(time), s.kineticTranslational = kTrans, s.virial = virial;
    s.collisions = collisions;
    return s;
}

} // namespace

TEST(Pressure, OneKilojoulePerMolePerCubicAngstromInBarAndReducedUnits) {
    // 1e3 J / 6.02214076e23 / 1e-30 m³ = 1.66053906717e9 Pa
    EXPECT_NEAR(units::bar(1.0), 16605.390671738467, 1e-15 * 16605.39);
    EXPECT_NEAR(units::bar(1.0) * 1e5, 1e33 / 6.02214076e23, 1e-15 * 1.7e9);
    EXPECT_DOUBLE_EQ(reducedPressure(3.0 / (2.0 * 2.0 * 2.0), 2.0, 3.0), 1.0); // P = ε/σ³
}

TEST(Pressure, SmdTakesTheVirialAtEachSample) {
    // (2·30 − 15) / (3·1000) = 0.015 kJ/mol/Å³ at each of the two samples
    const std::vector<SampleRecord> s{sample(2.0, 30.0, -15.0), sample(2.5, 15.0, 0.0)};
    const auto p0 = cli::pressureTerms(s[0], s[0], VirialKind::Instantaneous, 1000.0);
    const auto p1 = cli::pressureTerms(s[1], s[0], VirialKind::Instantaneous, 1000.0);
    EXPECT_DOUBLE_EQ(p0.kinetic, 0.02);
    EXPECT_DOUBLE_EQ(p0.virial, -0.005);
    EXPECT_DOUBLE_EQ(p0.kinetic + p0.virial, 0.015);
    EXPECT_DOUBLE_EQ(p1.kinetic + p1.virial, 0.01);
    EXPECT_DOUBLE_EQ(virialPressure(30.0, -15.0, 1000.0), 0.015);
}

TEST(Pressure, DmdTakesTheImpulseVirialOverEachSampleInterval) {
    // W_imp 10 → 16 over 0.5 time units: 12 kJ/mol; then no collision: 0.
    const std::vector<SampleRecord> s{sample(2.0, 20.0, 10.0), sample(2.5, 30.0, 16.0),
                                      sample(3.5, 25.0, 16.0)};
    const auto p1 = cli::pressureTerms(s[1], s[0], VirialKind::Impulse, 1000.0);
    const auto p2 = cli::pressureTerms(s[2], s[1], VirialKind::Impulse, 1000.0);
    EXPECT_DOUBLE_EQ(p1.kinetic + p1.virial, (60.0 + 12.0) / 3000.0);
    EXPECT_DOUBLE_EQ(p2.virial, 0.0);
    EXPECT_DOUBLE_EQ(p2.kinetic + p2.virial, 50.0 / 3000.0);
    EXPECT_DOUBLE_EQ(impulseVirialOver(10.0, 16.0, 2.0, 2.5), 12.0);

    // The summary, from the samples one by one: mean of the two pressures (production's first
    // sample ends no interval), error from the two blocks that hold one, |P1 − P2|/2.
    const double sigma = 3.035, epsilon = 3.0, mean = (0.024 + 50.0 / 3000.0) / 2.0;
    cli::SampleStatistics stats(cli::SamplePlan{3, 0, VirialKind::Impulse, 1000.0, 9});
    for (const auto& e : s)
        stats.add(e);
    nlohmann::json summary;
    stats.summarise(summary, sigma, epsilon);
    const auto& j = summary["pressure"];
    EXPECT_NEAR(j["mean_bar"].get<double>(), mean * units::barPerKjPerMolPerA3, 1e-12);
    EXPECT_NEAR(j["error_bar"].get<double>(),
                (0.024 - 50.0 / 3000.0) / 2.0 * units::barPerKjPerMolPerA3, 1e-12);
    EXPECT_NEAR(j["mean_reduced"].get<double>(), mean * sigma * sigma * sigma / epsilon, 1e-15);
    EXPECT_NEAR(j["kinetic_term_reduced"].get<double>() + j["virial_term_reduced"].get<double>(),
                j["mean_reduced"].get<double>(), 1e-15);
    EXPECT_EQ(j["samples"], 2);
    // One pressure: no error (null in summary.json).
    cli::SampleStatistics two(cli::SamplePlan{3, 0, VirialKind::Impulse, 1000.0, 9});
    two.add(s[0]), two.add(s[1]);
    nlohmann::json short_;
    two.summarise(short_, sigma, epsilon);
    const auto& one = short_["pressure"];
    EXPECT_EQ(one["samples"], 1);
    EXPECT_TRUE(std::isnan(one["error_bar"].get<double>()));
    EXPECT_EQ(one.dump().find("NaN"), std::string::npos);
}

TEST(Thermo, HeaderNamesEveryColumnAndItsUnit) {
    for (const auto kind : {VirialKind::Instantaneous, VirialKind::Impulse}) {
        const auto lines = split(cli::thermoHeader({kind, 1000.0, 9, 4, {}, false}), '\n');
        ASSERT_EQ(lines.size(), 3u);
        const auto names = split(lines[0], ',');
        EXPECT_EQ(names.front(), "time_ps");
        EXPECT_EQ(names.size(), kind == VirialKind::Impulse ? 9u : 8u);
        EXPECT_EQ(names.back(), kind == VirialKind::Impulse ? "collisions" : "pressure_bar");
        EXPECT_EQ(split(lines[1], ',').size(), names.size());
        EXPECT_EQ(lines[1][0], '#');
        EXPECT_EQ(lines[2][0], '#');
        EXPECT_EQ(lines[0][0] == '#', false); // pandas' comment='#' keeps the names
    }
}

TEST(Thermo, RowsTakeTheirPressureAndCollisionsOverTheThermoInterval) {
    const cli::ThermoLayout dmd{VirialKind::Impulse, 1000.0, 9, 4, {}, false};
    SampleRecord a = sample(2.0, 20.0, 10.0, 100.0), b = sample(2.5, 30.0, 16.0, 130.0);
    b.kinetic = 45.0, b.potential = -60.0, b.total = -15.0;
    const auto first = numbers(cli::thermoRow(a, nullptr, -61.0, dmd));
    EXPECT_TRUE(std::isnan(first[7])); // no interval yet
    EXPECT_EQ(first[8], 0.0);
    const std::string text = cli::thermoRow(b, &a, -61.5, dmd);
    ASSERT_EQ(text.back(), '\n');
    const auto row = numbers(text);
    ASSERT_EQ(row.size(), 9u);
    EXPECT_EQ(row[0], b.tPs);
    EXPECT_EQ(row[1], 30.0);
    EXPECT_EQ(row[2], 15.0); // K − K_trans
    EXPECT_EQ(row[3], -60.0);
    EXPECT_EQ(row[4], -61.5);
    EXPECT_EQ(row[5], -15.0);
    EXPECT_DOUBLE_EQ(row[6], 2.0 * 45.0 / 9.0 / units::kB);
    EXPECT_DOUBLE_EQ(row[7], units::bar((60.0 + 12.0) / 3000.0));
    EXPECT_EQ(row[8], 30.0);
    // SMD: the virial at the row's instant, no collisions column.
    const auto smd =
        numbers(cli::thermoRow(b, &a, -60.0, {VirialKind::Instantaneous, 1000.0, 9, 4, {}, false}));
    ASSERT_EQ(smd.size(), 8u);
    EXPECT_DOUBLE_EQ(smd[7], units::bar((60.0 + 16.0) / 3000.0));
}

// The time column shows a time on the sample grid as the decimal it is (as trajectory.xyz's
// Time=): 20 samples of 9 fs summed carry binary round-off, the row reads 0.18.
TEST(Thermo, TheTimeIsTheGridsDecimal) {
    double t = 0.0;
    for (int k = 0; k < 20; ++k)
        t += units::fromFs(9.0);
    ASSERT_NE(units::toPs(t), 0.18);
    const SampleRecord s = sample(t, 20.0, 10.0);
    const std::string row =
        cli::thermoRow(s, nullptr, -61.0, {VirialKind::Impulse, 1000.0, 9, 4, {}, false});
    EXPECT_EQ(row.substr(0, row.find(',')), "0.18") << row;
    // From the sample index on the plan's grid (20 · 0.09 time units) it is 0.18 here exactly.
    EXPECT_EQ(units::toPs(20.0 * units::fromFs(9.0)), 0.18);
}

namespace {

/// 27 LJ spheres 20 σ apart (ρ* = 1/8000) with the cutoff at 3 σ: in 0.45 ps at T* = 1.4 a sphere
/// moves ~3 Å, so no pair ever comes within range. An ideal gas.
Scene idealGas(const std::string& engine) {
    Scene s = defaultScene();
    s.name = "ideal-gas";
    s.engine = engine;
    s.body.kind = "sphere";
    s.body.inertia = Vec3::Zero();
    s.potential.kind = "lj";
    s.state.n = 27;
    s.state.density = 1.0 / 8000.0;
    s.run.equilibrate_ps = 0.0;
    s.run.time_ps = 0.45;
    s.output.thermo_every_fs = 90.0;
    return sceneFromJson(toJson(s), "ideal gas"); // validated as a scene file would be
}

} // namespace

TEST(Pressure, AnIdealGasHasTheKineticPressureAlone) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("terrace-ideal-" + std::to_string(::getpid()));
    for (const std::string engine : {"smd", "dmd"}) {
        const Scene scene = idealGas(engine);
        const auto sys = buildInitialState<Sphere>(scene, ljPotential(scene));
        const double volume = std::pow(sys.box.length, 3);
        // With no force, K_trans stays that of the start: P = 2K_trans/(3V) at every sample.
        const double kinetic = virialPressure(translationalKinetic(sys), 0.0, volume);
        const double expected =
            reducedPressure(kinetic, scene.potential.sigma, scene.potential.epsilon);
        std::filesystem::remove_all(dir);
        const auto out = cli::runScene(scene, {dir, cli::OutputMode::Fresh, true, nullptr});
        const auto& p = out.summary.at("pressure");
        EXPECT_EQ(p["virial_term_reduced"].get<double>(), 0.0) << engine;
        EXPECT_NEAR(p["mean_reduced"].get<double>(), expected, roundOff * expected) << engine;
        EXPECT_NEAR(p["kinetic_term_reduced"].get<double>(), expected, roundOff * expected);
        EXPECT_NEAR(p["error_reduced"].get<double>(), 0.0, roundOff * expected);
        EXPECT_EQ(p["samples"], engine == "dmd" ? 50 : 51);
        EXPECT_EQ(out.summary.value("collisions_per_ps", 0.0), 0.0);
        // thermo.csv: rows at 0, 90, …, 450 fs, the pressure in bar at each (DMD: from the second).
        std::ifstream in(dir / "thermo.csv");
        std::string line;
        int rows = 0;
        while (std::getline(in, line)) {
            if (line.empty() || line[0] == '#' || line[0] == 't') continue;
            const auto x = numbers(line + "\n");
            EXPECT_NEAR(x[0], 0.09 * rows, 1e-12);
            if (engine == "dmd" && rows == 0)
                EXPECT_TRUE(std::isnan(x[7]));
            else
                EXPECT_NEAR(x[7], units::bar(kinetic), roundOff * x[7]);
            ++rows;
        }
        EXPECT_EQ(rows, 6) << engine;
    }
    std::filesystem::remove_all(dir);
}

} // namespace test_thermo
