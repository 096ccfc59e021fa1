#pragma once
// Initial states for a scene: N bodies on a simple cubic lattice filling a cubic box at density
// ρ* = Nσ³/L³, orientations uniform on the sphere (or all aligned), velocities and angular
// velocities drawn from Maxwell–Boltzmann at kT, total momentum removed, then rescaled so that the
// kinetic temperature is exactly kT. Deterministic from the scene seed (named random streams).
// An explicit `state.particles` list is used as given instead (converted from ps to time units).
#include "core/body_kind.hpp"
#include "core/lj_potential.hpp"
#include "core/rod_potential.hpp"
#include "core/scene.hpp"
#include "core/smoothed_cutoff.hpp"
#include "core/system.hpp"
#include "core/units.hpp"
#include <cmath>
#include <random>
#include <string>

namespace terrace {

RodPotential rodPotential(const Scene& scene);
LJPotential ljPotential(const Scene& scene);
BodyParams bodyParams(const Scene& scene);
/// potential.cutoff in Å: the smoothed cutoff of the model both engines simulate.
SmoothedCutoff sceneCutoff(const Scene& scene);

/// A random stream named by its purpose, derived from the one scene seed, so that e.g. adding a
/// draw to the velocities never changes the orientations.
std::mt19937_64 namedStream(std::uint64_t seed, const std::string& purpose);

namespace detail {

/// Lattice sites of a simple cubic lattice with m = ceil(N^(1/3)) sites per edge, first N used.
std::vector<Vec3> cubicLattice(int n, double boxLength);
Vec3 randomUnitVector(std::mt19937_64& rng);
Mat3 randomRotation(std::mt19937_64& rng); // uniform on SO(3), lab -> body
Vec3 anyPerpendicular(const Vec3& s);

/// Refuse lattices whose neighbours overlap: U at the nearest-neighbour distance in the worst
/// orientation must be below this many kT (a start far up the repulsive wall makes the first
/// events or forces meaningless).
inline constexpr double maxStartEnergyInKT = 50.0;

template <BodyKind K>
void thermalise(typename K::State& b, const BodyParams& p, double kT, std::mt19937_64& rng) {
    std::normal_distribution<double> gauss(0.0, 1.0);
    const double sv = std::sqrt(kT / p.mass);
    b.v = Vec3(gauss(rng), gauss(rng), gauss(rng)) * sv;
    if constexpr (K::rotationalDof == 2) { // linear rotor: ω ⟂ s, two components
        const Vec3 e1 = anyPerpendicular(b.s), e2 = b.s.cross(e1);
        const double sw = std::sqrt(kT / p.inertia[0]);
        b.w = (gauss(rng) * e1 + gauss(rng) * e2) * sw;
    } else if constexpr (K::rotationalDof == 3) { // tops: body-frame ω_a ~ N(0, kT/I_a)
        Vec3 Lbody;
        for (int a = 0; a < 3; ++a)
            Lbody[a] = gauss(rng) * std::sqrt(kT * p.inertia[a]);
        b.L = b.A.transpose() * Lbody;
    }
}

template <BodyKind K> void setOrientation(typename K::State& b, const Vec3& axis, const Mat3& A) {
    if constexpr (requires { b.s; }) b.s = axis;
    if constexpr (requires { b.A; }) b.A = A;
}

} // namespace detail

template <BodyKind K, PairPotential P>
System<K, P> buildInitialState(const Scene& scene, const P& potential) {
    System<K, P> sys;
    sys.box.length = scene.boxLength();
    sys.body = bodyParams(scene);
    sys.potential = potential;
    sys.kT = scene.kT();
    const int n = scene.state.particles.empty() ? scene.state.n
                                                : static_cast<int>(scene.state.particles.size());
    sys.bodies.resize(n);

    if (!scene.state.particles.empty()) {
        for (int i = 0; i < n; ++i) {
            const auto& spec = scene.state.particles[i];
            auto& b = sys.bodies[i];
            b.r = spec.r;
            b.v = spec.v * units::psPerTimeUnit; // Å/ps -> Å per time unit
            const Vec3 omega = spec.omega * units::psPerTimeUnit;
            // The orientation, when given, decides: the axis is its image of the body z axis
            // (q * ẑ, as in core/xyz.cpp); else the least rotation taking ẑ to the axis.
            const Quat q = spec.orientation
                               ? spec.orientation->normalized()
                               : Quat::FromTwoVectors(Vec3::UnitZ(), spec.axis.normalized());
            if constexpr (requires { b.s; }) {
                b.s = spec.orientation ? Vec3(q * Vec3::UnitZ()) : spec.axis.normalized();
                b.w = omega - omega.dot(b.s) * b.s;
            }
            if constexpr (requires { b.A; }) {
                const Mat3 A = q.toRotationMatrix().transpose();
                b.A = A;
                b.L = A.transpose() * (A * omega).cwiseProduct(sys.body.inertia);
            }
        }
        return sys;
    }

    const auto sites = detail::cubicLattice(n, sys.box.length);
    if (n > 1) {
        const double spacing = sys.box.length / std::ceil(std::cbrt(double(n)) - 1e-9);
        // Worst case: r_e is smallest for aligned neighbours (rods) -- probe along and across.
        const Vec3 d(spacing, 0, 0);
        const double uAligned = potential.energy(d, Vec3::UnitY(), Vec3::UnitY());
        const double uCrossed = potential.energy(d, Vec3::UnitY(), Vec3::UnitZ());
        if (std::max(uAligned, uCrossed) > detail::maxStartEnergyInKT * sys.kT)
            throw SceneError("state.density: " + std::to_string(scene.state.density) +
                             " puts lattice neighbours " + std::to_string(spacing) +
                             " Å apart, deep in the repulsive core (overlap); lower the density");
    }
    auto orientRng = namedStream(scene.seed, "orientations");
    auto velocityRng = namedStream(scene.seed, "velocities");
    for (int i = 0; i < n; ++i) {
        auto& b = sys.bodies[i];
        b.r = sites[i];
        if (scene.state.orientations == "aligned") {
            detail::setOrientation<K>(b, Vec3::UnitZ(), Mat3::Identity());
        } else {
            const Mat3 A = detail::randomRotation(orientRng);
            detail::setOrientation<K>(b, detail::randomUnitVector(orientRng), A);
        }
        detail::thermalise<K>(b, sys.body, sys.kT, velocityRng);
    }
    const Vec3 pMean = totalMomentum(sys) / (sys.body.mass * n);
    for (auto& b : sys.bodies)
        b.v -= pMean;
    rescaleToTemperature(sys, sys.kT);
    return sys;
}

} // namespace terrace
