#pragma once
// Small hand-built systems for the SMD tests: bodies on a simple cubic lattice filling a periodic
// box at reduced density ρ* = Nσ³/L³, uniformly random unit axes, Maxwell-Boltzmann velocities and
// angular velocities (ω ⟂ s for rods) at kT, total momentum removed. Deterministic from a seed.
#include "core/body_kind.hpp"
#include "core/linear_rotor.hpp"
#include "core/lj_potential.hpp"
#include "core/rod_potential.hpp"
#include "core/scene.hpp"
#include "core/smoothed_potential.hpp"
#include "core/sphere.hpp"
#include "core/system.hpp"
#include "core/top_state.hpp"
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
    s.smd["dt_fs"] = dtFs;
    return s;
}

/// The rods' lattice start turned into tops: attitude with the rod axis as body axis 3, L from
/// the rod's ω plus a spin about the axis, principal moments `inertia`.
template <BodyKind Top>
System<Top, RodModel> topsFromRods(const System<LinearRotor, RodModel>& rods, const Vec3& inertia) {
    System<Top, RodModel> sys;
    sys.box = rods.box;
    sys.potential = rods.potential;
    sys.kT = rods.kT;
    sys.body.mass = rods.body.mass;
    sys.body.inertia = inertia;
    std::mt19937_64 rng(21);
    for (const auto& rod : rods.bodies) {
        TopState b;
        b.r = rod.r;
        b.v = rod.v;
        const Vec3 e3 = rod.s;
        const Vec3 e1 =
            (std::abs(e3.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(e3).normalized();
        b.A.row(0) = e1.transpose();
        b.A.row(1) = e3.cross(e1).transpose();
        b.A.row(2) = e3.transpose();
        const Vec3 omegaBody = b.A * rod.w + Vec3(0, 0, 3.0 * (double(rng() % 1000) / 1000 - 0.5));
        b.L = b.A.transpose() * omegaBody.cwiseProduct(inertia);
        sys.bodies.push_back(b);
    }
    return sys;
}

} // namespace terrace::smd::fixtures
