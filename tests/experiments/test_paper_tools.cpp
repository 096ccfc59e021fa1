// The numeric helpers behind Makefile.paper: replica statistics, error norms, summary rows, the
// fig1 potential map and the fig2 root-search trace.
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
