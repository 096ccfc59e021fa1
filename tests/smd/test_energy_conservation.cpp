// Energy conservation of the splitting on the paper's rods at ρ* = 0.5, T* = 1.4: the total-energy
// error scales as dt² (second-order integrator), there is no secular drift over 100 ps at the
// paper's 1.8 fs, and std(E)/std(U) at 1.8 fs is of the paper's size (about 1 %).
#include "smd/scene_engine.hpp"
#include "systems.hpp"
#include <gtest/gtest.h>
#include <numeric>

namespace test_energy_conservation {

using namespace terrace;
using RodEngine = smd::SceneEngine<LinearRotor, smd::fixtures::RodModel>;

namespace {

constexpr double sigmaRod = 3.035; // Å

struct Series {
    std::vector<double> t, energy, potential;
    double mean(const std::vector<double>& x) const {
        return std::accumulate(x.begin(), x.end(), 0.0) / x.size();
    }
    double std(const std::vector<double>& x) const {
        const double m = mean(x);
        double s = 0.0;
        for (double v : x)
            s += (v - m) * (v - m);
        return std::sqrt(s / x.size());
    }
    /// Least-squares slope of energy against t.
    double slope() const {
        const double mt = mean(t), me = mean(energy);
        double num = 0.0, den = 0.0;
        for (std::size_t k = 0; k < t.size(); ++k) {
            num += (t[k] - mt) * (energy[k] - me);
            den += (t[k] - mt) * (t[k] - mt);
        }
        return num / den;
    }
};

/// Rods melted from the lattice and brought to T* = 1.4 by rescaling every 10 fs for 2 ps.
System<LinearRotor, smd::fixtures::RodModel> equilibratedRods(int perEdge, std::uint64_t seed) {
    auto sys = smd::fixtures::rods(perEdge, 0.5, 1.4, seed);
    RodEngine e(sys, smd::fixtures::smdScene(sigmaRod, 1.0));
    for (int k = 1; k <= 200; ++k) {
        e.advanceTo(units::fromFs(10.0 * k));
        e.rescaleTemperature(sys.kT);
    }
    return e.system();
}

/// NVE run of `durationFs` sampled every `sampleFs` (both multiples of dt).
Series run(const System<LinearRotor, smd::fixtures::RodModel>& start, double dtFs,
           double durationFs, double sampleFs) {
    RodEngine e(start, smd::fixtures::smdScene(sigmaRod, dtFs));
    Series s;
    const long samples = std::lround(durationFs / sampleFs);
    for (long k = 0; k <= samples; ++k) {
        e.advanceTo(units::fromFs(k * sampleFs));
        s.t.push_back(units::toPs(e.time()));
        s.energy.push_back(e.kineticEnergy() + e.potentialEnergy());
        s.potential.push_back(e.potentialEnergy());
    }
    return s;
}

} // namespace

TEST(EnergyConservation, ErrorScalesAsTimeStepSquared) {
    // 6³ rods (L ≈ 7.6σ, the smallest cube holding 2(r_u + skin) at ρ* = 0.5), 1 ps per dt.
    const auto start = equilibratedRods(6, 11);
    const std::vector<double> dts = {0.25, 0.5, 1.0, 2.0};
    std::vector<double> logDt, logError;
    for (double dt : dts) {
        const Series s = run(start, dt, 1000.0, 2.0);
        logDt.push_back(std::log(dt));
        logError.push_back(std::log(s.std(s.energy)));
        std::cout << "dt " << dt << " fs: std(E) " << s.std(s.energy) << " kJ/mol\n";
    }
    const double mx = std::accumulate(logDt.begin(), logDt.end(), 0.0) / logDt.size();
    const double my = std::accumulate(logError.begin(), logError.end(), 0.0) / logError.size();
    double num = 0.0, den = 0.0;
    for (std::size_t k = 0; k < logDt.size(); ++k) {
        num += (logDt[k] - mx) * (logError[k] - my);
        den += (logDt[k] - mx) * (logDt[k] - mx);
    }
    const double order = num / den;
    std::cout << "fitted order of the energy error: " << order << "\n";
    constexpr double orderTolerance = 0.2; // the acceptance band around 2
    EXPECT_NEAR(order, 2.0, orderTolerance);
}

TEST(EnergyConservation, NoDriftOver100ps) {
    const auto start = equilibratedRods(6, 12);
    const Series s = run(start, 1.8, 100000.2, 10.8); // 100 ps in whole 1.8 fs steps
    const double fluctuation = s.std(s.energy);
    const double drift = s.slope() * (s.t.back() - s.t.front()); // kJ/mol over the run
    std::cout << "std(E) " << fluctuation << " kJ/mol, drift over " << s.t.back()
              << " ps: " << drift << " kJ/mol\n";
    EXPECT_LT(std::abs(drift), fluctuation);
}

TEST(EnergyConservation, FluctuationRatioOfPaperSize) {
    // The paper's state point at its size, N = 512; 5 ps of NVE at its 1.8 fs. The paper reports
    // "relative fluctuations of the total energy to the potential energy of about 1 %": the ratio
    // std(E)/std(U) of the two fluctuations. (std(E)/|mean U|, the summary's rel_fluct, is two
    // orders smaller and is printed for reference.)
    const auto start = equilibratedRods(8, 13);
    const Series s = run(start, 1.8, 5004.0, 10.8);
    const double fluctRatio = s.std(s.energy) / s.std(s.potential);
    const double relFluct = s.std(s.energy) / std::abs(s.mean(s.potential));
    std::cout << "N = 512, dt = 1.8 fs: std(E)/std(U) = " << fluctRatio
              << ", rel_fluct = std(E)/|mean U| = " << relFluct << " (mean U "
              << s.mean(s.potential) << " kJ/mol, std U " << s.std(s.potential) << ", std E "
              << s.std(s.energy) << ")\n";
    // "About 1 %" comes without error bars; a factor of three either way still fails for an
    // integrator of the wrong order (or dt off by ~1.7x) and for a force inconsistent with U.
    constexpr double paperRatio = 0.01, paperFactor = 3.0;
    EXPECT_GT(fluctRatio, paperRatio / paperFactor);
    EXPECT_LT(fluctRatio, paperRatio * paperFactor);
}

} // namespace test_energy_conservation
