#pragma once
// Small systems for the DMD tests, built from the scene machinery (core/initial_state.hpp) or by
// hand when a test needs an exact configuration.
#include "core/initial_state.hpp"
#include "core/linear_rotor.hpp"
#include "core/rod_potential.hpp"
#include "core/smoothed_potential.hpp"
#include "dmd/scene_engine.hpp"
#include "dmd/testing.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <random>

using terrace::dmd::testing::Probe;

namespace terrace::dmdtest {

using RodSystem = System<LinearRotor, RodPotential>;
using RodEngine = dmd::SceneEngine<LinearRotor, RodPotential>;
// The rods on the model SMD integrates: U smoothed to zero over the scene's cutoff.
using SmoothedRods = Smoothed<RodPotential>;
using SmoothedRodEngine = dmd::SceneEngine<LinearRotor, SmoothedRods>;

inline SmoothedRods smoothedRods(const Scene& s) {
    return {rodPotential(s), sceneCutoff(s)};
}

/// The paper's rods (ε 3, σ 3.035, ζ 1, m 18, I 1.154) at N, ρ*, T* from a lattice.
inline Scene rodScene(int n, double density, double temperature, double dVInKT) {
    Scene s = defaultScene();
    s.state.n = n;
    s.state.density = density;
    s.state.temperature = temperature;
    s.dmd["dV"] = dVInKT;
    return s;
}

inline RodSystem rodSystem(const Scene& s) {
    return buildInitialState<LinearRotor>(s, rodPotential(s));
}

/// Parallel rods (axes along z) on a simple cubic lattice of spacing a (m³ sites), thermal
/// velocities and angular velocities ⟂ z at kT, zero total momentum.
inline RodSystem alignedLattice(int m, double a, double kT, std::uint64_t seed) {
    RodSystem sys;
    sys.box.length = m * a;
    sys.body.mass = 18.0;
    sys.body.inertia = Vec3(1.154, 1.154, 0.0);
    sys.kT = kT;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    Vec3 p = Vec3::Zero();
    for (int x = 0; x < m; ++x)
        for (int y = 0; y < m; ++y)
            for (int z = 0; z < m; ++z) {
                LinearRotor::State b;
                b.r = Vec3(x + 0.5, y + 0.5, z + 0.5) * a;
                b.s = Vec3::UnitZ();
                b.v = Vec3(gauss(rng), gauss(rng), gauss(rng)) * std::sqrt(kT / 18.0);
                b.w = Vec3(gauss(rng), gauss(rng), 0.0) * std::sqrt(kT / 1.154);
                p += b.v;
                sys.bodies.push_back(b);
            }
    for (auto& b : sys.bodies)
        b.v -= p / sys.size();
    return sys;
}

/// Inner (repulsive-side) root of the LJ curve at u: 4ε(y² − y) = u with y = (σ/x)^6.
inline double innerRoot(double u, double epsilon, double sigma) {
    const double y = 0.5 * (1.0 + std::sqrt(1.0 + u / epsilon));
    return sigma / std::pow(y, 1.0 / 6.0);
}

/// Outer (attractive-side) root of the LJ curve at −ε < u < 0.
inline double outerRoot(double u, double epsilon, double sigma) {
    const double y = 0.5 * (1.0 - std::sqrt(1.0 + u / epsilon));
    return sigma / std::pow(y, 1.0 / 6.0);
}

/// Advances both engines on a 2 fs grid for `samples` samples, asserting the same collisions
/// (up, down, reflect) at every sample: a screen or a bookkeeping mode that must change none.
template <class E> void expectSameCollisions(E& a, E& b, int samples) {
    for (int k = 1; k <= samples; ++k) {
        a.advanceTo(units::fromFs(2.0 * k));
        b.advanceTo(units::fromFs(2.0 * k));
        ASSERT_EQ(Probe::counts(a).up, Probe::counts(b).up) << k * 2 << " fs";
        ASSERT_EQ(Probe::counts(a).down, Probe::counts(b).down) << k * 2 << " fs";
        ASSERT_EQ(Probe::counts(a).reflect, Probe::counts(b).reflect) << k * 2 << " fs";
    }
}

inline double totalEnergy(const RodEngine& e) {
    return e.kineticEnergy() + e.potentialEnergy();
}

} // namespace terrace::dmdtest
