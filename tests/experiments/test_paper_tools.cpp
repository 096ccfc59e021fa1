// The numeric helpers behind Makefile.paper: replica statistics, error norms, summary rows, the
// fig1 potential map, the fig2 root-search trace, the orders of convergence and the continuous
// model's energy and pressure on a trajectory.
#include "core/lj_potential.hpp"
#include "core/scene.hpp"
#include "core/xyz.hpp"
#include "experiments/tools/configurational.hpp"
#include "experiments/tools/convergence.hpp"
#include "experiments/tools/equal_accuracy.hpp"
#include "experiments/tools/potential_map.hpp"
#include "experiments/tools/replicas.hpp"
#include "experiments/tools/search_trace.hpp"
#include "experiments/tools/summaries.hpp"
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>

namespace test_paper_tools {

namespace fs = std::filesystem;
using terrace::analysis::CsvTable;
namespace ex = terrace::experiments;

namespace {

/// Sums of a few doubles: exact but for the last bits.
constexpr double roundOff = 1e-12;

fs::path scratch(const std::string& name) {
    const fs::path p = fs::temp_directory_path() / ("terrace-paper-tools-" + name);
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

CsvTable curve(const std::vector<double>& x, const std::vector<double>& y,
               const std::vector<double>& err) {
    return CsvTable{{"t_ps", "c", "err"}, {x, y, err}};
}

} // namespace

TEST(ReplicaMean, MeanAndStandardErrorAcrossReplicas) {
    const std::vector<double> x{0.0, 0.1, 0.2};
    // Replicas 1, 2, 3 (+ row offsets): mean 2, sample variance 1, standard error sqrt(1/3).
    const std::vector<CsvTable> r{curve(x, {1, 11, 21}, {9, 9, 9}),
                                  curve(x, {2, 12, 22}, {9, 9, 9}),
                                  curve(x, {3, 13, 23}, {9, 9, 9})};
    const CsvTable m = ex::replicaMean(r);
    ASSERT_EQ(m.rows(), 3);
    EXPECT_EQ(m.header, r[0].header);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(m.columns[0][i], x[i], roundOff);
        EXPECT_NEAR(m.columns[1][i], 2.0 + 10.0 * i, roundOff);
        EXPECT_NEAR(m.columns[2][i], std::sqrt(1.0 / 3.0), roundOff); // not the runs' own 9
    }
}

TEST(ReplicaMean, CutsToTheShortestAndRejectsMismatches) {
    const CsvTable a = curve({0, 1, 2}, {1, 1, 1}, {0, 0, 0}), b = curve({0, 1}, {3, 3}, {0, 0});
    EXPECT_EQ(ex::replicaMean({a, b}).rows(), 2);
    EXPECT_THROW(ex::replicaMean({a}), std::invalid_argument);
    EXPECT_THROW(ex::replicaMean({a, curve({0, 1.5, 2}, {1, 1, 1}, {0, 0, 0})}),
                 std::invalid_argument);
    CsvTable c = a;
    c.header[1] = "g";
    EXPECT_THROW(ex::replicaMean({a, c}), std::invalid_argument);
}

TEST(ErrorNorm, RmsDifferenceOnTheReferenceGrid) {
    // A straight line sampled coarsely is interpolated exactly onto the finer reference grid.
    std::vector<double> xr, yr, xc, yc;
    for (int i = 0; i <= 20; ++i)
        xr.push_back(0.05 * i), yr.push_back(1.0 - xr.back());
    for (int i = 0; i <= 4; ++i)
        xc.push_back(0.25 * i), yc.push_back(1.0 - xc.back() + 0.1);
    const CsvTable ref = curve(xr, yr, std::vector<double>(21, 0.03));
    const CsvTable off = curve(xc, yc, std::vector<double>(5, 0.04));
    EXPECT_NEAR(ex::rmsDifference(ref, off, "c"), 0.1, roundOff);
    EXPECT_NEAR(ex::rmsDifference(ref, ref, "c"), 0.0, roundOff);
    EXPECT_NEAR(ex::rmsNoise(ref, off, "c"), 0.05, roundOff); // sqrt(0.03² + 0.04²)
    EXPECT_THROW(ex::rmsDifference(ref, off, "nope"), std::invalid_argument);
}

TEST(ErrorNorm, UpperLimitSelectsTheRange) {
    const CsvTable ref = curve({0, 1, 2, 3}, {0, 0, 0, 0}, {0, 0, 0, 0});
    const CsvTable c = curve({0, 1, 2, 3}, {1, 1, 5, 5}, {0, 0, 0, 0});
    EXPECT_NEAR(ex::rmsDifference(ref, c, "c", 1.5), 1.0, roundOff);
    EXPECT_NEAR(ex::rmsDifference(ref, c, "c"), std::sqrt(13.0), roundOff);
}

TEST(Summaries, RowsAverageReplicasAndReadNestedKeys) {
    const fs::path d = scratch("summaries");
    for (int k = 1; k <= 2; ++k) {
        fs::create_directories(d / std::to_string(k));
        nlohmann::json s = {{"engine", "dmd"},
                            {"simulated_ps", 2.0},
                            {"cpu_seconds_per_ps", 1.0 * k},
                            {"collisions_per_ps", 100.0},
                            {"events", {{"total", 400 * k}}},
                            {"energy", {{"rel_fluct", 1e-15}, {"drift_per_ps", 0.0}}},
                            {"temperature_K", 500.0},
                            {"interrupted", false}};
        std::ofstream(d / std::to_string(k) / "summary.json") << s.dump();
    }
    const std::string row = ex::summaryRow("x", {d / "1", d / "2"});
    // cpu 1 and 2: mean 1.5, standard error 0.5; events per ps 200 and 400: mean 300.
    EXPECT_EQ(row.substr(0, row.find(",100,")), "x,dmd,2,2,1.5,0.5");
    EXPECT_NE(row.find(",300,100,"), std::string::npos) << row;
    EXPECT_EQ(ex::jsonValues(d / "1" / "summary.json",
                             {"energy.rel_fluct", "events.total", "interrupted", "missing.key"}),
              "1e-15,400,0,nan");
    EXPECT_THROW(ex::summaryRow("x", {d / "none"}), std::runtime_error);
    fs::remove_all(d);
}

TEST(Summaries, ReplicaValuesScaleByBodiesAndByThermalEnergy) {
    const fs::path d = scratch("replica-values");
    fs::create_directories(d);
    nlohmann::json s = {{"engine", "smd"},
                        {"n_bodies", 200},
                        {"temperature_target_K", 400.0},
                        {"potential_energy_mean", -1000.0},
                        {"energy", {{"drift_per_ps", -3.0}}}};
    std::ofstream(d / "summary.json") << s.dump();
    using ex::SummaryScale;
    EXPECT_DOUBLE_EQ(ex::replicaValue(d, "potential_energy_mean", SummaryScale::total), -1000.0);
    EXPECT_DOUBLE_EQ(ex::replicaValue(d, "potential_energy_mean", SummaryScale::perBody), -5.0);
    // |−3| kJ/mol/ps over N kT = 200 · k_B · 400 K, k_B written out as the engines turn a
    // temperature into kT (core/units.hpp, kJ/(mol K)): the tool must use that one, not its own.
    EXPECT_DOUBLE_EQ(ex::replicaValue(d, "energy.drift_per_ps", SummaryScale::magnitudePerNkT),
                     3.0 / (200 * 0.0083144626 * 400.0));
    EXPECT_TRUE(std::isnan(ex::replicaValue(d, "energy.missing", SummaryScale::total)));
    EXPECT_EQ(ex::summaryScale("per-body"), SummaryScale::perBody);
    EXPECT_THROW(ex::summaryScale("per-volume"), std::invalid_argument);
    EXPECT_THROW(ex::replicaValue(d / "none", "n_bodies", SummaryScale::total), std::runtime_error);
    fs::remove_all(d);
}

TEST(PotentialMap, TerracesFollowThePaperFigure) {
    const fs::path d = scratch("fig1");
    ex::PotentialMapSettings s;
    s.rPoints = 41;
    s.cPoints = 21;
    ex::writePotentialMap(d / "map.csv", s);
    std::ifstream in(d / "map.csv");
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "r,c,U,V");
    int rows = 0, bottom = 0;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        double r, c, U, V;
        char comma;
        std::istringstream(line) >> r >> comma >> c >> comma >> U >> comma >> V;
        ++rows;
        EXPECT_GE(V, s.vMin);
        EXPECT_EQ(V, std::round(V)) << "terrace energies are multiples of ΔV = 1";
        if (U > -1.5) {
            EXPECT_LE(std::abs(V - U), 0.5 + roundOff) << "r " << r << " c " << c;
        } else if (U < -1.5) {
            EXPECT_EQ(V, s.vMin);
            ++bottom;
        }
    }
    EXPECT_EQ(rows, 41 * 21);
    EXPECT_GT(bottom, 0) << "the well (U down to −ε = −2.5) must reach the V_min terrace";
    fs::remove_all(d);
}

TEST(SearchTrace, TheRootLiesOnTheLevelAfterTheGridPoints) {
    const fs::path d = scratch("fig2");
    ex::writeSearchTrace(d, 0.5);
    nlohmann::json info;
    std::ifstream(d / "fig2_info.json") >> info;
    EXPECT_GE(info["grid_points"].get<int>(), 3);
    const auto grid = terrace::analysis::readCsv(d / "fig2_grid.csv");
    for (int i = 1; i < grid.rows(); ++i)
        EXPECT_GT(grid.columns[0][i], grid.columns[0][i - 1]);
    const auto root = terrace::analysis::readCsv(d / "fig2_root.csv");
    ASSERT_EQ(root.rows(), 1);
    const double tRoot = root.columns[0][0], uRoot = root.columns[1][0], level = root.columns[2][0];
    // The search refines the root to ~1e-13 of its step; U changes by ~0.1 kJ/mol per fs there.
    constexpr double levelTolerance = 1e-6; // kJ/mol
    EXPECT_NEAR(uRoot, level, levelTolerance);
    EXPECT_GT(tRoot, grid.columns[0][grid.rows() - 2]);
    EXPECT_LE(tRoot, grid.columns[0][grid.rows() - 1]);
    fs::remove_all(d);
}

TEST(ReplicaStatistics, MeanAndStandardError) {
    const auto m = ex::replicaStatistics({1.0, 2.0, 3.0});
    EXPECT_NEAR(m.mean, 2.0, roundOff);
    EXPECT_NEAR(m.error, std::sqrt(1.0 / 3.0), roundOff); // sample variance 1, R = 3
    EXPECT_TRUE(std::isnan(ex::replicaStatistics({4.0}).error)) << "one run: error unknown";
    EXPECT_THROW(ex::replicaStatistics({}), std::invalid_argument);
    EXPECT_THROW(ex::replicaStatistics({1.0, NAN}), std::invalid_argument);
}

namespace {
/// e = 0.3 ΔV^p at ΔV = 2 … ⅛ with a relative uncertainty rel (σ_ln e = rel).
std::vector<ex::ConvergencePoint> powerLaw(double p, double rel) {
    std::vector<ex::ConvergencePoint> points;
    for (double dV : {2.0, 1.0, 0.5, 0.25, 0.125}) {
        const double e = 0.3 * std::pow(dV, p);
        points.push_back({dV, e, rel * e});
    }
    return points;
}
double spreadOfLogs(const std::vector<ex::ConvergencePoint>& points) {
    double mean = 0.0, ss = 0.0;
    for (const auto& q : points)
        mean += std::log(q.dV) / points.size();
    for (const auto& q : points)
        ss += (std::log(q.dV) - mean) * (std::log(q.dV) - mean);
    return ss;
}
} // namespace

TEST(OrderFit, AnExactPowerLawGivesItsExponentAndTheWeightedError) {
    const auto points = powerLaw(1.5, 0.05);
    const ex::OrderFit f = ex::fitOrder(points);
    EXPECT_EQ(f.points, 5);
    EXPECT_NEAR(f.order, 1.5, 1e-12);
    EXPECT_NEAR(f.logPrefactor, std::log(0.3), 1e-12);
    EXPECT_NEAR(f.chi2PerDof, 0.0, 1e-20);
    // Equal weights 1/0.05²: σ_p² = S/Δ = σ_y² / Σ(x − x̄)² (Numerical Recipes eq. 15.2.9).
    EXPECT_NEAR(f.orderError, 0.05 / std::sqrt(spreadOfLogs(points)), 1e-12);
}

TEST(OrderFit, PointsWithinTheFloorAreLeftOut) {
    auto points = powerLaw(2.0, 0.1);
    points.push_back({0.0625, 1e-3, 0.6e-3}); // e < 2σ: noise, and far off the line
    points.push_back({0.0, 5.0, 0.1});        // the reference's row takes no part
    EXPECT_FALSE(ex::isResolved(points[5]));
    EXPECT_TRUE(ex::isResolved(points[0]));
    EXPECT_FALSE(ex::isResolved({1.0, NAN, 0.1}));
    const ex::OrderFit f = ex::fitOrder(points);
    EXPECT_EQ(f.points, 5);
    EXPECT_NEAR(f.order, 2.0, 1e-12);
    const ex::OrderFit none = ex::fitOrder({points[0], points[5]});
    EXPECT_EQ(none.points, 1);
    EXPECT_TRUE(std::isnan(none.order) && std::isnan(none.orderError));
}

TEST(OrderFit, ScatterBeyondTheErrorsWidensTheOrderByTheBirgeRatio) {
    // ln e alternately ±0.2 off a line of slope 1, with σ_ln e = 0.02: χ²/(n − 2) ≫ 1.
    std::vector<ex::ConvergencePoint> points;
    double sign = 1.0;
    for (double dV : {2.0, 1.0, 0.5, 0.25}) {
        const double e = dV * std::exp(0.2 * sign);
        points.push_back({dV, e, 0.02 * e});
        sign = -sign;
    }
    const ex::OrderFit f = ex::fitOrder(points);
    ASSERT_EQ(f.points, 4);
    EXPECT_GT(f.chi2PerDof, 1.0);
    const double unscaled = 0.02 / std::sqrt(spreadOfLogs(points));
    EXPECT_NEAR(f.orderError, unscaled * std::sqrt(f.chi2PerDof), 1e-12);
    // The residuals, refitted by hand: χ² = Σ ((y − a − p x)/σ)².
    double chi2 = 0.0;
    for (const auto& q : points) {
        const double r = (std::log(q.error) - f.logPrefactor - f.order * std::log(q.dV)) / 0.02;
        chi2 += r * r;
    }
    EXPECT_NEAR(f.chi2PerDof, chi2 / 2.0, 1e-9);
}

TEST(OrderFit, TablesGetFitColumnsAndOneRowPerQuantity) {
    const fs::path d = scratch("orders");
    const auto law = powerLaw(1.0, 0.05);
    CsvTable t{{"dV_kT", "U", "err_U", "sigma_U", "err_g", "sigma_g"}, {}};
    t.columns.assign(6, {});
    auto row = [&](double dV, double u, double e, double s, double eg, double sg) {
        const double values[] = {dV, u, e, s, eg, sg};
        for (int c = 0; c < 6; ++c)
            t.columns[c].push_back(values[c]);
    };
    row(0.0, -9.0, NAN, NAN, NAN, NAN); // the reference
    for (const auto& q : law)
        row(q.dV, -9.0 + q.error, q.error, q.sigma, 0.01, 0.02); // g: all within the floor
    const auto rows = ex::fitOrders(t, (d / "out.csv").string());
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0].substr(0, rows[0].find(',', 2)), "U,1");
    EXPECT_EQ(rows[1], "g,nan,nan,nan,nan,0");
    const CsvTable out = terrace::analysis::readCsv(d / "out.csv");
    const std::vector<std::string> header{"dV_kT",   "U",       "err_U",       "sigma_U",
                                          "fit_U",   "order_U", "order_U_err", "err_g",
                                          "sigma_g", "fit_g",   "order_g",     "order_g_err"};
    EXPECT_EQ(out.header, header);
    EXPECT_TRUE(std::isnan(out.columns[4][0])) << "the reference is neither fitted nor left out";
    for (int i = 1; i < out.rows(); ++i) {
        EXPECT_EQ(out.columns[4][i], 1.0);
        EXPECT_EQ(out.columns[9][i], 0.0);
        EXPECT_TRUE(std::isnan(out.columns[10][i])) << "no local order within the floor";
        if (i + 1 < out.rows()) {
            // e ∝ ΔV: halving ΔV halves e, p = 1, σ_p = sqrt(2) · 0.05 / ln 2.
            EXPECT_NEAR(out.columns[5][i], 1.0, 1e-12);
            EXPECT_NEAR(out.columns[6][i], std::sqrt(2.0) * 0.05 / std::log(2.0), 1e-12);
        } else {
            EXPECT_TRUE(std::isnan(out.columns[5][i])) << "the finest ΔV has no ΔV/2";
        }
    }
    fs::remove_all(d);
}

TEST(Configurational, TwoSpheresGiveTheirPairEnergyAndVirial) {
    const fs::path d = scratch("configurational");
    terrace::Scene scene = terrace::defaultScene();
    scene.body.kind = "sphere";
    scene.body.mass = 2.0;
    scene.body.inertia = terrace::Vec3::Zero();
    scene.potential.kind = "lj";
    scene.potential.epsilon = 1.5;
    scene.potential.sigma = 1.0;
    scene.state.n = 2;
    scene.state.density = 0.01;
    scene.analysis.rdf_max = 0.0; // L/2: two bodies make a box narrower than the default's 10 σ
    std::ofstream(d / "scene.json") << terrace::toJson(scene).dump(2);
    // Two frames: a pair 1.2σ apart (inside r_l = 2.5σ: the bare LJ) moving apart at 0.5 Å per
    // time unit each, then 2.0σ apart at rest, across the box's periodic boundary.
    const double L = 10.0;
    terrace::Snapshot a, b;
    a.boxLength = b.boxLength = L;
    a.position = {{1.0, 1.0, 1.0}, {2.2, 1.0, 1.0}};
    a.velocity = {{-0.5, 0.0, 0.0}, {0.5, 0.0, 0.0}};
    b.position = {{0.5, 3.0, 3.0}, {8.5, 3.0, 3.0}};
    b.velocity = {terrace::Vec3::Zero(), terrace::Vec3::Zero()};
    for (auto* f : {&a, &b}) {
        f->axis.assign(2, terrace::Vec3::UnitZ());
        f->omega.assign(2, terrace::Vec3::Zero());
    }
    {
        std::ofstream out(d / "trajectory.xyz");
        terrace::writeXyzFrame(out, a, terrace::TrajectoryLayout::Sphere);
        terrace::writeXyzFrame(out, b, terrace::TrajectoryLayout::Sphere);
    }
    const terrace::LJPotential lj{1.5, 1.0};
    const terrace::Vec3 s = terrace::Vec3::UnitZ();
    auto pairVirial = [&](double r) {
        const terrace::Vec3 rij(-r, 0.0, 0.0); // r_1 − r_2
        return rij.dot(lj.evaluate(rij, s, s).F);
    };
    const double uA = lj.energy({1.2, 0, 0}, s, s), uB = lj.energy({2.0, 0, 0}, s, s);
    const double pA = (2.0 * 0.5 * 2.0 * 0.5 + pairVirial(1.2)) / (3.0 * L * L * L);
    const double pB = pairVirial(2.0) / (3.0 * L * L * L);
    const ex::Configurational c = ex::configurational(d);
    EXPECT_EQ(c.frames, 2);
    // Positions and velocities survive the file to ~1e-16 relative (17 digits; v via Å/ps).
    EXPECT_NEAR(c.potentialPerBody, 0.5 * (uA + uB) / 2.0, 1e-12);
    EXPECT_NEAR(c.pressureReduced, 0.5 * (pA + pB) * 1.0 / 1.5, 1e-12);
    EXPECT_THROW(ex::configurational(d / "none"), std::exception);
    fs::remove_all(d);
}

TEST(EqualAccuracy, ParetoFrontKeepsOnlyUnbeatenPoints) {
    const auto front = ex::paretoFront({{"c", 3.0, 0.08},
                                        {"a", 1.0, 0.1},
                                        {"d", 4.0, 0.01},
                                        {"b", 2.0, 0.05},
                                        {"failed", std::nan(""), 0.001},
                                        {"zero", 5.0, 0.0}});
    ASSERT_EQ(front.size(), 3u);
    EXPECT_EQ(front[0].label, "a");
    EXPECT_EQ(front[1].label, "b");
    EXPECT_EQ(front[2].label, "d");
}

TEST(EqualAccuracy, CostIsInterpolatedInLogLogAlongTheFront) {
    const std::vector<ex::FrontPoint> front{{"a", 1.0, 0.1}, {"b", 2.0, 0.05}, {"d", 4.0, 0.01}};
    // Halfway between b and d in ln e is halfway in ln c: √(2·4).
    const auto mid = ex::costAtError(front, std::sqrt(0.05 * 0.01));
    EXPECT_NEAR(mid.cost, std::sqrt(8.0), roundOff);
    EXPECT_FALSE(mid.bound);
    EXPECT_EQ(mid.via, "b~d");
    EXPECT_EQ(ex::costAtError(front, 0.05).via, "b");
    EXPECT_NEAR(ex::costAtError(front, 0.05).cost, 2.0, roundOff);
    const auto easy = ex::costAtError(front, 0.2); // looser than the cheapest point
    EXPECT_EQ(easy.cost, 1.0);
    EXPECT_TRUE(easy.bound);
    EXPECT_EQ(easy.via, "a");
    EXPECT_TRUE(std::isnan(ex::costAtError(front, 0.005).cost)); // beyond the best
}

TEST(EqualAccuracy, EfficiencyIsSmdCostOverDesignCostAtTheTargets) {
    const fs::path dir = scratch("fronts");
    std::ofstream(dir / "fronts.csv")
        << "set,engine,design,param,cpu_s_per_ps,err_g,floor_g,status\n"
           "smd-1,smd,-,1,4,0.01,0.001,ok\n"
           "smd-1.8,smd,-,1.8,2,0.04,0.001,ok\n"
           "smd-4,smd,-,4,1,0.16,0.001,failed: unstable\n"
           "dmd-0.5,dmd,uniform,0.5,1,0.08,0.001,ok\n"
           "dmd-0.25,dmd,uniform,0.25,4,0.02,0.001,ok\n"
           "dmd-0.5-opt,dmd,optimal,0.5,0.5,0.04,0.001,ok\n";
    const auto rows = ex::equalAccuracy(dir / "fronts.csv", "smd-1.8");
    ASSERT_EQ(rows.size(), 4u); // 2 designs × 2 targets, one quantity; SMD-1.8's error resolved
    // optimal reaches SMD-1.8's error at 0.5 against SMD's 2: 4 times cheaper, an exact point.
    EXPECT_EQ(rows[0], "optimal,g,smd-1.8,0.04,1,2,0.5,4,0,smd-1.8");
    // At twice the error SMD's cheapest stable point already is below it: a bound on both.
    EXPECT_EQ(rows[1], "optimal,g,2xsmd-1.8,0.08,1,2,0.5,4,1,smd-1.8");
    // uniform: 0.04 lies halfway (in ln e) between 0.08 and 0.02, so its cost is √(1·4) = 2.
    EXPECT_EQ(rows[2], "uniform,g,smd-1.8,0.04,1,2,2,1,0,smd-1.8");
    EXPECT_EQ(rows[3], "uniform,g,2xsmd-1.8,0.08,1,2,1,2,1,smd-1.8");
    // A target within its floor is marked: SMD-1.8's error 0.04 against a floor of 0.03.
    std::ofstream(dir / "noisy.csv")
        << "set,engine,design,param,cpu_s_per_ps,err_g,floor_g,status\n"
           "smd-1.8,smd,-,1.8,2,0.04,0.03,ok\n"
           "dmd-1,dmd,uniform,1,1,0.05,0.03,ok\n";
    EXPECT_EQ(ex::equalAccuracy(dir / "noisy.csv", "smd-1.8")[0],
              "uniform,g,smd-1.8,0.04,0,2,nan,nan,0,smd-1.8");
}

TEST(EqualAccuracy, SmdFrontTakesTheCheapestSchemeReachingTheTargetAndNamesIt) {
    const fs::path dir = scratch("schemes");
    // A fourth-order scheme at 3 fs is both cheaper and more accurate than the paper's at 1.8 fs;
    // between it and verlet at 1 fs SMD's front runs through both schemes.
    std::ofstream(dir / "fronts.csv")
        << "set,engine,design,param,cpu_s_per_ps,err_g,floor_g,status\n"
           "smd-1-mayfail,smd,verlet,1,4,0.01,0.001,ok\n"
           "smd-1.8-mayfail,smd,verlet,1.8,2,0.04,0.001,ok\n"
           "smd-3-yoshida4-mayfail,smd,yoshida4,3,1.5,0.02,0.001,ok\n"
           "dmd-0.5,dmd,uniform,0.5,1,0.04,0.001,ok\n";
    const auto rows = ex::equalAccuracy(dir / "fronts.csv", "smd-1.8-mayfail");
    ASSERT_EQ(rows.size(), 2u);
    // At SMD-1.8's error the cheapest SMD is yoshida4 at 3 fs (1.5, a bound): DMD 1.5× cheaper.
    EXPECT_EQ(rows[0], "uniform,g,smd-1.8-mayfail,0.04,1,1.5,1,1.5,1,smd-3-yoshida4-mayfail");
    EXPECT_EQ(rows[1], "uniform,g,2xsmd-1.8-mayfail,0.08,1,1.5,1,1.5,1,smd-3-yoshida4-mayfail");
    const std::vector<ex::FrontPoint> front = ex::paretoFront(
        {{"smd-1", 4.0, 0.01}, {"smd-1.8", 2.0, 0.04}, {"smd-3-yoshida4", 1.5, 0.02}});
    EXPECT_EQ(ex::costAtError(front, 0.015).via, "smd-3-yoshida4~smd-1");
}

} // namespace test_paper_tools
