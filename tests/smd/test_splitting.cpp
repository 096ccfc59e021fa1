// The SMD splittings of smd/splitting.hpp (smd.scheme = verlet | omelyan | yoshida4): consistent
// and symmetric coefficients, time reversibility to round-off, the measured order of the energy
// error (slope of log max|E(t) − E(0)| over 0.5 ps against log dt, with the fit's standard error)
// on the paper's rods and on asymmetric tops, and no drift over 100 ps at 1.8 fs.
#include "core/asymmetric_top.hpp"
#include "smd/scene_engine.hpp"
#include "systems.hpp"
#include <gtest/gtest.h>
#include <numeric>

namespace test_splitting {

using namespace terrace;

namespace {

constexpr double sigmaRod = 3.035; // Å, the paper's σ
const std::vector<std::string> schemes = {"verlet", "omelyan", "yoshida4"};
// Sums of a scheme's coefficients: a few roundings of O(1) numbers.
constexpr double coefficientSumTol = 1e-15;
// Yoshida's order condition with cubes of coefficients up to ~1.7: a few ulp of ~10.
constexpr double orderConditionTol = 1e-14;

Scene sceneFor(const std::string& scheme, double dtFs) {
    Scene s = smd::fixtures::smdScene(sigmaRod, dtFs);
    s.smd["scheme"] = scheme;
    return s;
}

/// Rods melted from the lattice at ρ* = 0.5, T* = 1.4 (2 ps, rescaled every 10 fs).
System<LinearRotor, smd::fixtures::RodModel> meltedRods(std::uint64_t seed) {
    const auto start = smd::fixtures::rods(6, 0.5, 1.4, seed);
    smd::SceneEngine<LinearRotor, smd::fixtures::RodModel> e(start, sceneFor("verlet", 1.0));
    for (int k = 1; k <= 200; ++k) {
        e.advanceTo(units::fromFs(10.0 * k));
        e.rescaleTemperature(start.kT);
    }
    return e.system();
}

/// max |E(t) − E(0)| over `durationFs`, checked every `sampleFs` (multiples of dt).
template <BodyKind K>
double maxEnergyError(const System<K, smd::fixtures::RodModel>& start, const std::string& scheme,
                      double dtFs, double durationFs, double sampleFs) {
    smd::SceneEngine<K, smd::fixtures::RodModel> e(start, sceneFor(scheme, dtFs));
    const double e0 = e.kineticEnergy() + e.potentialEnergy();
    double worst = 0.0;
    for (long k = 1; k <= std::lround(durationFs / sampleFs); ++k) {
        e.advanceTo(units::fromFs(k * sampleFs));
        worst = std::max(worst, std::abs(e.kineticEnergy() + e.potentialEnergy() - e0));
    }
    return worst;
}

struct Fit {
    double slope, error;
};

/// Least-squares slope of y against x and its standard error.
Fit fitSlope(const std::vector<double>& x, const std::vector<double>& y) {
    const double n = double(x.size());
    const double mx = std::accumulate(x.begin(), x.end(), 0.0) / n;
    const double my = std::accumulate(y.begin(), y.end(), 0.0) / n;
    double sxx = 0.0, sxy = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k)
        sxx += (x[k] - mx) * (x[k] - mx), sxy += (x[k] - mx) * (y[k] - my);
    const double slope = sxy / sxx;
    double residual = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k) {
        const double r = y[k] - my - slope * (x[k] - mx);
        residual += r * r;
    }
    return {slope, std::sqrt(residual / (n - 2.0) / sxx)};
}

/// The measured order of each scheme's energy error over a dt ladder.
template <BodyKind K>
void checkOrders(const System<K, smd::fixtures::RodModel>& start, const char* what) {
    const std::vector<double> dts = {0.25, 0.5, 1.0}; // fs; 0.5 ps each, E checked every 2 fs
    for (const auto& scheme : schemes) {
        std::vector<double> logDt, logError;
        for (double dt : dts) {
            const double error = maxEnergyError(start, scheme, dt, 500.0, 2.0);
            logDt.push_back(std::log(dt));
            logError.push_back(std::log(error));
            std::cout << what << ", " << scheme << ", dt " << dt << " fs: max|ΔE| " << error
                      << " kJ/mol\n";
        }
        const Fit fit = fitSlope(logDt, logError);
        const int order = smd::splitting(scheme).order;
        std::cout << what << ", " << scheme << ": measured order " << fit.slope << " ± "
                  << fit.error << " (expected " << order << ")\n";
        // Within 0.3 of the scheme's order: a second-order scheme mistaken for a fourth-order one
        // (or a coefficient off, which drops a symmetric scheme to first order) is far outside.
        constexpr double orderTolerance = 0.3;
        EXPECT_NEAR(fit.slope, order, orderTolerance) << what << ", " << scheme;
    }
}

} // namespace

TEST(Splitting, CoefficientsAreConsistentAndSymmetric) {
    for (const auto& scheme : schemes) {
        const auto s = smd::splitting(scheme);
        ASSERT_EQ(s.kick.size(), s.drift.size() + 1) << scheme;
        EXPECT_NEAR(std::accumulate(s.kick.begin(), s.kick.end(), 0.0), 1.0, coefficientSumTol)
            << scheme;
        EXPECT_NEAR(std::accumulate(s.drift.begin(), s.drift.end(), 0.0), 1.0, coefficientSumTol)
            << scheme;
        for (std::size_t k = 0; k < s.kick.size(); ++k)
            EXPECT_DOUBLE_EQ(s.kick[k], s.kick[s.kick.size() - 1 - k]) << scheme;
        for (std::size_t k = 0; k < s.drift.size(); ++k)
            EXPECT_DOUBLE_EQ(s.drift[k], s.drift[s.drift.size() - 1 - k]) << scheme;
    }
    // Yoshida's fourth-order condition: 2 w₁³ + w₀³ = 0 for the composed steps.
    const auto y = smd::splitting("yoshida4");
    EXPECT_NEAR(2.0 * std::pow(y.drift[0], 3) + std::pow(y.drift[1], 3), 0.0, orderConditionTol);
    EXPECT_THROW(smd::splitting("leapfrog"), SceneError);
}

TEST(Splitting, EverySchemeIsTimeReversible) {
    const auto start = smd::fixtures::rods(6, 0.5, 1.4, 9);
    smd::SceneEngine<LinearRotor, smd::fixtures::RodModel> warm(start, sceneFor("verlet", 1.8));
    warm.advanceTo(units::fromFs(200 * 1.8));
    for (const auto& scheme : schemes) {
        smd::SceneEngine<LinearRotor, smd::fixtures::RodModel> e(warm.system(),
                                                                 sceneFor(scheme, 1.0));
        const auto before = e.system().bodies;
        e.advanceTo(200 * e.parameters().dt);
        e.reverseMotion();
        e.advanceTo(400 * e.parameters().dt);
        // As for the paper's splitting (test_engine.cpp): round-off grown by the liquid's chaos
        // over 2 × 200 steps stays orders below this.
        constexpr double reversibilityTolerance = 1e-8; // Å
        double worst = 0.0;
        for (std::size_t i = 0; i < before.size(); ++i)
            worst = std::max(worst, (e.system().bodies[i].r - before[i].r).norm());
        EXPECT_LT(worst, reversibilityTolerance) << scheme;
    }
}

TEST(Splitting, EnergyErrorHasEachSchemesOrderForRods) {
    checkOrders(meltedRods(31), "rods");
}

TEST(Splitting, EnergyErrorHasEachSchemesOrderForAsymmetricTops) {
    const auto tops =
        smd::fixtures::topsFromRods<AsymmetricTop>(meltedRods(32), Vec3(0.9, 1.154, 0.4));
    checkOrders(tops, "asymmetric tops");
}

TEST(Splitting, NoDriftOver100psAtThePapersStep) {
    const auto start = meltedRods(33);
    for (const auto& scheme : {std::string("omelyan"), std::string("yoshida4")}) {
        smd::SceneEngine<LinearRotor, smd::fixtures::RodModel> e(start, sceneFor(scheme, 1.8));
        std::vector<double> t, energy;
        for (long k = 0; k <= 9260; ++k) { // 100.008 ps in samples of 6 steps
            e.advanceTo(units::fromFs(10.8 * k));
            t.push_back(units::toPs(e.time()));
            energy.push_back(e.kineticEnergy() + e.potentialEnergy());
        }
        const double mean = std::accumulate(energy.begin(), energy.end(), 0.0) / energy.size();
        double var = 0.0;
        for (double x : energy)
            var += (x - mean) * (x - mean);
        const double fluctuation = std::sqrt(var / energy.size());
        const double drift = fitSlope(t, energy).slope * (t.back() - t.front());
        std::cout << scheme << " at 1.8 fs: std(E) " << fluctuation << " kJ/mol, drift over "
                  << t.back() << " ps " << drift << " kJ/mol\n";
        EXPECT_LT(std::abs(drift), fluctuation) << scheme;
    }
}

} // namespace test_splitting
