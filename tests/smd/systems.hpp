#pragma once
// Small hand-built systems for the SMD tests: bodies on a simple cubic lattice filling a periodic
// box at reduced density ρ* = Nσ³/L³, uniformly random unit axes, Maxwell-Boltzmann velocities and
// angular velocities (ω ⟂ s for rods) at kT, total momentum removed. Deterministic from a seed.
#include "core/linear_rotor.hpp"
#include "core/lj_potential.hpp"
#include "core/rod_potential.hpp"
#include "core/scene.hpp"
#include "core/smoothed_potential.hpp"
#include "core/sphere.hpp"
#include "core/system.hpp"
#include <cmath>
#include <random>

namespace terrace::smd::fixtures {

/// The models the SMD tests integrate: the paper's cutoff, r_l = 2.5σ, r_u = 3σ.
using RodModel = Smoothed<RodPotential>;
using LJModel = Smoothed<LJPotential>;
template <class P> Smoothed<P> paperModel(const P& bare) {
    return {bare, SmoothedCutoff{2.5 * bare.sigma, 3.0 * bare.sigma}};
}

inline Vec3 randomUnit(std::mt19937_64& rng) {
    std::normal_distribution<double> gauss;
    Vec3 u(gauss(rng), gauss(rng), gauss(rng));
    return u / u.norm();
}

/// The paper's rods ("Model System"): ε 3 kJ/mol, σ 3.035 Å, ζ 1 Å, m 18 g/mol, I 1.154 g/mol Å².
inline System<LinearRotor, RodModel> rods(int perEdge, double density, double reducedT,
                                          std::uint64_t seed) {
    System<LinearRotor, RodModel> sys;
    sys.potential = paperModel(RodPotential{});
    sys.body.mass = 18.0;
    sys.body.inertia = Vec3(1.154, 1.154, 0.0);
    const int n = perEdge * perEdge * perEdge;
    const double sigma = sys.potential.bare.sigma;
    sys.box.length = std::cbrt(n / density) * sigma;
    sys.kT = reducedT * sys.potential.bare.epsilon;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss;
    const double a = sys.box.length / perEdge;
    Vec3 p = Vec3::Zero();
    for (int i = 0; i < n; ++i) {
        LinearRotor::State b;
        b.r = a * Vec3(i / (perEdge * perEdge), (i / perEdge) % perEdge, i % perEdge);
        b.s = randomUnit(rng);
        b.v = std::sqrt(sys.kT / sys.body.mass) * Vec3(gauss(rng), gauss(rng), gauss(rng));
        const Vec3 w =
            std::sqrt(sys.kT / sys.body.inertia[0]) * Vec3(gauss(rng), gauss(rng), gauss(rng));
        b.w = w - w.dot(b.s) * b.s;
        p += b.v;
        sys.bodies.push_back(b);
    }
    for (auto& b : sys.bodies)
        b.v -= p / n;
    return sys;
}

/// Lennard-Jones spheres in reduced units (ε = 1 kJ/mol, σ = 1 Å, m = 1 g/mol: τ = 1 time unit).
inline System<Sphere, LJModel> ljSpheres(int perEdge, double density, double reducedT,
                                         std::uint64_t seed) {
    System<Sphere, LJModel> sys;
    sys.potential = paperModel(LJPotential{});
    sys.body.mass = 1.0;
    const int n = perEdge * perEdge * perEdge;
    sys.box.length = std::cbrt(n / density);
    sys.kT = reducedT;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss;
    const double a = sys.box.length / perEdge;
    Vec3 p = Vec3::Zero();
    for (int i = 0; i < n; ++i) {
        Sphere::State b;
        b.r = a * Vec3(i / (perEdge * perEdge), (i / perEdge) % perEdge, i % perEdge);
        b.v = std::sqrt(sys.kT) * Vec3(gauss(rng), gauss(rng), gauss(rng));
        p += b.v;
        sys.bodies.push_back(b);
    }
    for (auto& b : sys.bodies)
        b.v -= p / n;
    return sys;
}

/// A scene whose smd block and σ match the systems above.
inline Scene smdScene(double sigma, double dtFs) {
    Scene s;
    s.engine = "smd";
    s.potential.sigma = sigma;
    s.smd.dt_fs = dtFs;
    return s;
}

} // namespace terrace::smd::fixtures
