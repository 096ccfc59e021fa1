// Error bars from independent replicas: the mean and spread of the replicas' own curves.
#include "analysis/csv.hpp"
#include "analysis/dynamic_correlations.hpp"
#include "analysis/replicas.hpp"
#include "synthetic_samples.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <unistd.h>

using namespace terrace;
using namespace terrace::analysis;
namespace fs = std::filesystem;

namespace {

/// The combined curve is arithmetic on the replicas' curves, which are rewritten with 17 digits.
constexpr double roundOff = 1e-12;
/// Four replicas: (mean − exact)/err is Student-t with 3 degrees of freedom; 12.9 is its
/// two-sided 0.1 % point, so one false alarm per thousand lags.
constexpr double studentT3Limit = 12.9;

} // namespace

TEST(Replicas, MeanAndSpreadOfTheReplicaCurves) {
    const double rate = 0.5, h = 0.1;
    std::vector<std::vector<Snapshot>> replicas;
    for (std::uint64_t seed = 21; seed < 25; ++seed)
        replicas.push_back(synthetic::ornsteinUhlenbeck(400, 30, h, 20.0, 4.2, 18.0, rate, seed));
    const fs::path dir =
        fs::temp_directory_path() / ("terrace_analysis_replicas_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    const auto summary = writeReplicaCorrelations(replicas, dir);
    const CsvTable vacf = readCsv(dir / "vacf.csv");
    EXPECT_FALSE(fs::exists(dir / "oacf.csv"));
    EXPECT_EQ(summary["replicas"], 4);

    std::vector<std::vector<double>> each;
    for (const auto& r : replicas)
        each.push_back(velocityAutocorrelation(r, 199, 8).value);
    ASSERT_EQ(vacf.rows(), 200);
    int beyond = 0;
    for (int k = 0; k < vacf.rows(); ++k) {
        double mean = 0.0, sq = 0.0;
        for (const auto& c : each)
            mean += c[k] / 4.0;
        for (const auto& c : each)
            sq += (c[k] - mean) * (c[k] - mean);
        EXPECT_NEAR(vacf.columns[1][k], mean, roundOff);
        EXPECT_NEAR(vacf.columns[2][k], std::sqrt(sq / 12.0), roundOff);
        if (k > 0)
            beyond += std::abs(vacf.columns[1][k] - std::exp(-rate * h * k)) >
                      studentT3Limit * vacf.columns[2][k];
    }
    EXPECT_EQ(beyond, 0);
    fs::remove_all(dir);
}

TEST(Replicas, RejectsMismatchedReplicas) {
    std::vector<std::vector<Snapshot>> one{synthetic::randomWalk(20, 4, 0.1, 10.0, 0.1, 1)};
    EXPECT_THROW(writeReplicaCorrelations(one, "unused"), std::invalid_argument);
    one.push_back(synthetic::randomWalk(22, 4, 0.1, 10.0, 0.1, 2));
    EXPECT_THROW(writeReplicaCorrelations(one, "unused"), std::invalid_argument);
    EXPECT_FALSE(fs::exists("unused"));
}
