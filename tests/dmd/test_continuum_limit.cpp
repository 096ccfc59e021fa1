// As ΔV → 0 the terraced dynamics approaches the continuous one (paper, "Comparison between
// standard molecular dynamics and event-driven simulations"; validation tier). The reference is a
// plain symplectic splitting on the continuous rod potential, all pairs, minimum image, written
// here so that this test needs nothing from smd/: half kick → exact free motion (core freeMove)
// → half kick (van Zon & Schofield, Phys. Rev. E 75, 056701 (2007)).
#include "test_systems.hpp"
#include <gtest/gtest.h>
#include <vector>

namespace test_continuum_limit {

using namespace terrace;
using namespace terrace::dmdtest;

namespace {

constexpr int bodies = 128;
// The lattice start is melted once by the continuous dynamics (with rescaling); both dynamics
// then start from that liquid, DMD after a short re-equilibration on its terraces.
constexpr double meltPs = 1.0, dmdEquilibratePs = 0.2, productionPs = 2.0, sampleFs = 10.0;
constexpr double mdProductionPs = 8.0; // the one reference run: four times as long as a DMD run
// DMD runs per ΔV, with different horizon-jitter streams (the trajectories part within ~1 ps).
constexpr int dmdRuns = 3;
constexpr double rescaleEveryFs = 50.0;
constexpr double binWidth = 0.1; // Å, g(r) histogram
constexpr double gMaxR = 8.0;    // Å, inside L/2 ≈ 9.6 Å

struct Observables {
    double meanU = 0.0;    // continuous U per body, kJ/mol
    std::vector<double> g; // centre-of-mass g(r)
};

void accumulate(const RodSystem& s, Observables& o, int& samples) {
    o.meanU += potentialEnergyAllPairs(s) / s.size();
    if (o.g.empty()) o.g.assign(static_cast<std::size_t>(gMaxR / binWidth), 0.0);
    for (int i = 0; i < s.size(); ++i)
        for (int j = i + 1; j < s.size(); ++j) {
            const double r = s.box.minimumImage(s.bodies[i].r - s.bodies[j].r).norm();
            if (r < gMaxR) o.g[static_cast<std::size_t>(r / binWidth)] += 2.0;
        }
    ++samples;
}

void normalise(Observables& o, int samples, int n, double volume) {
    o.meanU /= samples;
    for (std::size_t k = 0; k < o.g.size(); ++k) {
        const double r0 = k * binWidth, r1 = r0 + binWidth;
        const double shell = 4.0 / 3.0 * M_PI * (r1 * r1 * r1 - r0 * r0 * r0);
        o.g[k] /= samples * n * (n / volume) * shell;
    }
}

Observables dmdObservables(const Scene& s, const RodSystem& start) {
    RodEngine e(start, s);
    double t = 0.0;
    while (t < units::fromPs(dmdEquilibratePs)) {
        t += units::fromFs(rescaleEveryFs);
        e.advanceTo(t);
        e.rescaleTemperature(start.kT);
    }
    Observables o;
    int samples = 0;
    const double end = t + units::fromPs(productionPs);
    while (t < end) {
        t += units::fromFs(sampleFs);
        e.advanceTo(t);
        accumulate(e.system(), o, samples);
    }
    normalise(o, samples, start.size(), start.box.volume());
    return o;
}

void forces(const RodSystem& s, std::vector<Vec3>& f, std::vector<Vec3>& tau) {
    f.assign(s.size(), Vec3::Zero());
    tau.assign(s.size(), Vec3::Zero());
    for (int i = 0; i < s.size(); ++i)
        for (int j = i + 1; j < s.size(); ++j) {
            const Vec3 rij = s.box.minimumImage(s.bodies[i].r - s.bodies[j].r);
            const PairForce p = s.potential.evaluate(rij, s.bodies[i].s, s.bodies[j].s);
            f[i] += p.F;
            f[j] -= p.F;
            tau[i] += p.tauI;
            tau[j] += p.tauJ;
        }
}

/// The continuous splitting integrator; rescales to kT every rescaleEveryFs while melting.
class ContinuousDynamics {
public:
    explicit ContinuousDynamics(RodSystem s) : s_(std::move(s)) { forces(s_, f_, tau_); }
    const RodSystem& system() const { return s_; }
    void run(double ps, bool rescale, Observables* o, int* samples) {
        const int perRescale = steps(units::fromFs(rescaleEveryFs));
        const int perSample = steps(units::fromFs(sampleFs));
        const int total = steps(units::fromPs(ps));
        for (int k = 1; k <= total; ++k) {
            step();
            if (rescale && k % perRescale == 0) rescaleToTemperature(s_, s_.kT);
            if (o && k % perSample == 0) accumulate(s_, *o, *samples);
        }
    }

private:
    static constexpr double dt = units::fromFs(1.8) / 2.0; // half the paper's step: cleaner
    static int steps(double t) { return static_cast<int>(std::lround(t / dt)); }
    void kick() {
        for (int i = 0; i < s_.size(); ++i) {
            s_.bodies[i].v += 0.5 * dt / s_.body.mass * f_[i];
            LinearRotor::addAngularMomentum(s_.bodies[i], s_.body, 0.5 * dt * tau_[i]);
        }
    }
    void step() {
        kick();
        for (auto& b : s_.bodies)
            freeMove<LinearRotor>(b, s_.body, dt);
        forces(s_, f_, tau_);
        kick();
    }
    RodSystem s_;
    std::vector<Vec3> f_, tau_;
};

/// The DMD observables averaged over dmdRuns runs from one start, seeds 1, 2, ….
Observables dmdAverage(Scene s, const RodSystem& start) {
    Observables sum;
    for (int run = 1; run <= dmdRuns; ++run) {
        s.seed = static_cast<std::uint64_t>(run);
        const Observables o = dmdObservables(s, start);
        sum.meanU += o.meanU / dmdRuns;
        sum.g.resize(o.g.size(), 0.0);
        for (std::size_t k = 0; k < o.g.size(); ++k)
            sum.g[k] += o.g[k] / dmdRuns;
    }
    return sum;
}

double gDistance(const Observables& a, const Observables& b) {
    double d = 0.0;
    for (std::size_t k = 0; k < a.g.size(); ++k)
        d += std::abs(a.g[k] - b.g[k]) * binWidth;
    return d; // Å: the integrated |Δg|
}

} // namespace

// Mean potential energy and g(r) of DMD at ΔV = kT/10 agree with the continuous dynamics, and
// are closer to it than at ΔV = kT, where the paper sees exaggerated g(r) peaks.
TEST(ContinuumLimit, SmallTerracesApproachTheContinuousDynamics) {
    // ⟨U⟩/N ≈ −9.2 kJ/mol. Measured over 16 single 2 ps DMD runs at kT/10 from this start: a
    // residual bias of −0.13 ± 0.02 against the reference and a spread of 0.08 per run (one run
    // alone, tested against 0.2, failed for 4 of the 16 seeds). Averaged over 3 runs and with the
    // 8 ps reference's own noise (~0.03), the comparison has σ ≈ 0.055: 0.3 is the bias plus 3 σ,
    // and the kT bias (−0.55 measured) lies well beyond it.
    constexpr double energyTolerance = 0.3;
    // Integrated |Δg| (Å): noise of 200 samples is ~0.15; ΔV = kT gives ~0.45 (measured).
    constexpr double gTolerance = 0.3;
    const Scene fine = rodScene(bodies, 0.5, 1.4, 0.1), coarse = rodScene(bodies, 0.5, 1.4, 1.0);
    ContinuousDynamics dynamics(rodSystem(fine));
    dynamics.run(meltPs, true, nullptr, nullptr);
    const RodSystem start = dynamics.system();
    Observables md;
    int samples = 0;
    dynamics.run(mdProductionPs, false, &md, &samples);
    normalise(md, samples, start.size(), start.box.volume());
    const Observables dFine = dmdAverage(fine, start);
    const Observables dCoarse = dmdAverage(coarse, start);
    std::printf("<U>/N: MD %.4f  DMD(kT/10) %.4f  DMD(kT) %.4f kJ/mol; |dg|: %.4f %.4f A\n",
                md.meanU, dFine.meanU, dCoarse.meanU, gDistance(dFine, md), gDistance(dCoarse, md));
    EXPECT_NEAR(dFine.meanU, md.meanU, energyTolerance);
    EXPECT_LT(gDistance(dFine, md), gTolerance);
    EXPECT_LT(std::abs(dFine.meanU - md.meanU), std::abs(dCoarse.meanU - md.meanU));
    EXPECT_LT(gDistance(dFine, md), gDistance(dCoarse, md));
}

} // namespace test_continuum_limit
