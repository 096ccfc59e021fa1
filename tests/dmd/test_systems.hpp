#pragma once
// Small systems for the DMD tests, built from the scene machinery (core/initial_state.hpp) or by
// hand when a test needs an exact configuration.
#include "core/initial_state.hpp"
#include "core/linear_rotor.hpp"
#include "core/rod_potential.hpp"
#include "dmd/engine.hpp"
#include <cmath>
#include <random>

namespace terrace::dmdtest {

using RodSystem = System<LinearRotor, RodPotential>;
using RodEngine = dmd::Engine<LinearRotor, RodPotential>;

/// The paper's rods (ε 3, σ 3.035, ζ 1, m 18, I 1.154) at N, ρ*, T* from a lattice.
inline Scene rodScene(int n, double density, double temperature, double dVInKT) {
    Scene s = defaultScene();
    s.state.n = n;
    s.state.density = density;
    s.state.temperature = temperature;
    s.dmd.dV = dVInKT;
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

inline double totalEnergy(const RodEngine& e) {
    return e.kineticEnergy() + e.potentialEnergy();
}

} // namespace terrace::dmdtest
