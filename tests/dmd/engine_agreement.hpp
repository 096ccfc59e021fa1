#pragma once
// Sampling two engines alike for the agreement tests (validation tier): after an equilibration with
// rescaling, block means of the continuous U per body and the virial pressure on the engine's own
// configurations (for DMD: the configurational estimators), each with its block standard error.
#include "analysis/block_average.hpp"
#include "core/continuous_sums.hpp"
#include "core/units.hpp"
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <vector>

namespace terrace::agreement_tests {

struct Means {
    analysis::Estimate u, p; // continuous U per body (kJ/mol), pressure (kJ/mol/Å³)
};

/// Samples every `sampleFs` of `productionPs` after `equilibratePs` with rescaling, in `blocks`
/// blocks: the continuous U per body and the virial pressure on the engine's configurations.
template <class E> Means sampleMeans(E& e, double kT, double volume, int n) {
    constexpr double equilibratePs = 1.0, productionPs = 6.0, sampleFs = 10.0;
    constexpr int blocks = 12;
    double t = 0.0;
    while (t < units::fromPs(equilibratePs) - 1e-9) {
        t += units::fromFs(50.0);
        e.advanceTo(t);
        if (t < 0.5 * units::fromPs(equilibratePs)) e.rescaleTemperature(kT); // the lattice's heat
    }
    const int samples = static_cast<int>(std::lround(productionPs * 1000.0 / sampleFs));
    std::vector<double> u(blocks, 0.0), p(blocks, 0.0), w(blocks, 0.0);
    for (int k = 0; k < samples; ++k) {
        t += units::fromFs(sampleFs);
        e.advanceTo(t);
        const ContinuousSums c = e.continuousSums(nullptr);
        const int b = k * blocks / samples;
        u[b] += c.potential / n;
        p[b] += (2.0 * e.translationalKineticEnergy() + c.virial) / (3.0 * volume);
        w[b] += 1.0;
    }
    for (int b = 0; b < blocks; ++b)
        u[b] /= w[b], p[b] /= w[b];
    auto estimate = [&](const std::vector<double>& v) {
        double mean = 0.0;
        for (double x : v)
            mean += x / blocks;
        return analysis::Estimate{mean, analysis::blockError(v, w, mean), double(blocks - 1),
                                  blocks};
    };
    return {estimate(u), estimate(p)};
}

/// DMD's means d against SMD's m: U per body and pressure each within four combined standard
/// errors (a true difference of that size fails), and U's errors below 1 % of U, so that the
/// comparison resolves something; both printed.
inline void expectAgreement(const Means& d, const Means& m) {
    const double uErr = std::hypot(d.u.err, m.u.err), pErr = std::hypot(d.p.err, m.p.err);
    EXPECT_LT(std::abs(d.u.mean - m.u.mean), 4.0 * uErr)
        << "U/N: DMD " << d.u.mean << " ± " << d.u.err << ", SMD " << m.u.mean << " ± " << m.u.err;
    EXPECT_LT(std::abs(d.p.mean - m.p.mean), 4.0 * pErr)
        << "P: DMD " << d.p.mean << " ± " << d.p.err << ", SMD " << m.p.mean << " ± " << m.p.err;
    EXPECT_LT(uErr, 0.01 * std::abs(m.u.mean));
    std::printf("U/N: DMD %.5f ± %.5f, SMD %.5f ± %.5f kJ/mol; P: DMD %.6f ± %.6f, SMD %.6f ± "
                "%.6f kJ/mol/Å³\n",
                d.u.mean, d.u.err, m.u.mean, m.u.err, d.p.mean, d.p.err, m.p.mean, m.p.err);
}

} // namespace terrace::agreement_tests
