#pragma once
// Initial states for a scene: N bodies on a lattice (state.lattice: simple cubic, fcc or bcc,
// core/start_lattice.hpp) filling a cubic box at density ρ* = Nσ³/L³, orientations uniform on the
// sphere (or all aligned), velocities and angular velocities drawn from Maxwell–Boltzmann at kT,
// total momentum removed, then rescaled so that the kinetic temperature is exactly kT.
// Deterministic from the scene seed (named random streams). An explicit `state.particles` list is
// used as given instead (converted from ps to time units).
#include "core/body_kind.hpp"
#include "core/body_orientation.hpp"
#include "core/gay_berne_potential.hpp"
#include "core/lj_mixture.hpp"
#include "core/lj_potential.hpp"
#include "core/rod_mixture.hpp"
#include "core/rod_potential.hpp"
#include "core/scene.hpp"
#include "core/site_potential.hpp"
#include "core/smoothed_cutoff.hpp"
#include "core/start_lattice.hpp"
#include "core/step_mixture.hpp"
#include "core/step_potential.hpp"
#include "core/system.hpp"
#include "core/units.hpp"
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>

namespace terrace {

RodPotential rodPotential(const Scene& scene);
LJPotential ljPotential(const Scene& scene);
/// The species' Lennard-Jones pairs (Scene::species, potential.pairs) in kJ/mol and Å.
LJMixture ljMixture(const Scene& scene);
GayBernePotential gayBernePotential(const Scene& scene);
/// potential.kind steps: the scene's table in σ and ε, scaled by potential.sigma and epsilon.
StepPotential stepPotential(const Scene& scene);
/// potential.kind steps with species: that table between the species' pairs, each in its σ_ab.
StepMixture stepMixture(const Scene& scene);
/// potential.kind rod-lj with species: rods among spheres, the rod pairs' ζ potential.zeta, every
/// pair's ε_ab, σ_ab as for ljMixture.
RodMixture rodMixture(const Scene& scene);
/// body.sites as the site potential takes them.
std::vector<Site> sceneSites(const Scene& scene);
BodyParams bodyParams(const Scene& scene);
/// potential.cutoff in Å: the smoothed cutoff of the model both engines simulate.
SmoothedCutoff sceneCutoff(const Scene& scene);

/// A random stream named by its purpose, derived from the one scene seed, so that e.g. adding a
/// draw to the velocities never changes the orientations.
std::mt19937_64 namedStream(std::uint64_t seed, const std::string& purpose);

namespace detail {

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
    const double sv = std::sqrt(kT / bodyMass<K>(b, p));
    b.v = Vec3(gauss(rng), gauss(rng), gauss(rng)) * sv;
    if constexpr (K::rotationalDof == 2) { // linear rotor: ω ⟂ s, two components
        double inertia = p.inertia[0];
        if constexpr (requires { K::inertia(b, p); }) {
            inertia = K::inertia(b, p);
            if (inertia == 0.0) return; // a sphere of a mixture with rods: no spin (ω stays 0)
        }
        const Vec3 e1 = anyPerpendicular(b.s), e2 = b.s.cross(e1);
        const double sw = std::sqrt(kT / inertia);
        b.w = (gauss(rng) * e1 + gauss(rng) * e2) * sw;
    } else if constexpr (K::rotationalDof == 3) { // tops: body-frame ω_a ~ N(0, kT/I_a)
        Vec3 Lbody;
        for (int a = 0; a < 3; ++a)
            Lbody[a] = gauss(rng) * std::sqrt(kT * p.inertia[a]);
        b.L = b.A.transpose() * Lbody;
    }
}

/// The lattice start with its orientations: every body against its nearest lattice neighbours
/// (periodic; sc: along x, y and z, fcc: the 12 at a/√2, bcc: the 8 at a√3/2) and, on fcc and
/// bcc, the second shell's 6 at a along the axes (bodies aligned along an axis meet end to end
/// there, and on bcc it is only 15 % farther than the first), each pair's U at most
/// maxStartEnergyInKT kT, else a SceneError naming the remedy. What the worst-case probe of
/// the rods cannot see: elongated bodies end to end, or a molecule's sites, at the start's own
/// orientations. O(N): each pair once, from the site whose forward neighbour the other is.
template <BodyKind K, PairPotential P>
void refuseOverlappingNeighbours(const System<K, P>& sys, const LatticeShape& lattice,
                                 const Scene& scene) {
    const int n = sys.size();
    const double limit = maxStartEnergyInKT * sys.kT;
    for (int i = 0; i < n; ++i) {
        const SiteList first = lattice.forwardNeighbours(i),
                       second = lattice.forwardSecondNeighbours(i);
        for (const SiteList* shell : {&first, &second})
            for (const long jl : *shell) {
                if (jl >= n || jl == i) continue;
                const int j = static_cast<int>(jl);
                const Vec3 rij = sys.box.minimumImage(sys.bodies[i].r - sys.bodies[j].r);
                const double U = startEnergy(sys.potential, rij, orientationOf<P, K>(sys.bodies[i]),
                                             orientationOf<P, K>(sys.bodies[j]));
                if (!(U <= limit))
                    throw SceneError(
                        "state.density: " + std::to_string(scene.state.density) +
                        " puts lattice neighbours " + std::to_string(i) + " and " +
                        std::to_string(j) + " at U = " + std::to_string(U) + " kJ/mol (> " +
                        std::to_string(maxStartEnergyInKT) +
                        " kT) in their start orientations: lower the density, " +
                        (scene.state.orientations == "aligned"
                             ? std::string()
                             : std::string("start them aligned (state.orientations), ")) +
                        "or " +
                        (lattice.kind == LatticeKind::SimpleCubic
                             ? std::string("lengthen the lattice cell along the bodies "
                                           "(state.lattice_aspect)")
                             : std::string(
                                   "start on a simple-cubic cell lengthened along the bodies "
                                   "(state.lattice sc, state.lattice_aspect)")));
            }
    }
}

/// Deals the species out over the bodies: counts[a] bodies of species a, in an order shuffled by
/// `rng`, so that a lattice start mixes them.
template <class Bodies>
void assignSpecies(Bodies& bodies, const std::vector<int>& counts, std::mt19937_64 rng) {
    std::vector<std::int32_t> deck;
    for (std::size_t a = 0; a < counts.size(); ++a)
        deck.insert(deck.end(), static_cast<std::size_t>(counts[a]), static_cast<std::int32_t>(a));
    if (deck.size() != bodies.size())
        throw SceneError("species: the counts do not add up to the number of bodies");
    std::shuffle(deck.begin(), deck.end(), rng);
    for (std::size_t i = 0; i < deck.size(); ++i)
        bodies[i].species = deck[i];
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
            if constexpr (requires { b.species; }) b.species = spec.species;
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

    const LatticeShape lattice = latticeShape(n, sys.box.length, latticeKind(scene.state.lattice),
                                              scene.state.lattice_aspect);
    const std::vector<Vec3> sites = latticeSites(lattice, n);
    // Worst case: r_e is smallest for aligned neighbours (rods) -- probe along and across, at
    // the nearest-neighbour distance. (A frame potential has no such worst pair;
    // refuseOverlappingNeighbours checks its start.)
    if constexpr (P::attitude == AttitudeUse::None || P::attitude == AttitudeUse::Axis)
        if (n > 1) {
            const Vec3 d(lattice.nearest, 0, 0);
            const double uAligned = startEnergy(potential, d, Vec3::UnitY(), Vec3::UnitY());
            const double uCrossed = startEnergy(potential, d, Vec3::UnitY(), Vec3::UnitZ());
            if (std::max(uAligned, uCrossed) > detail::maxStartEnergyInKT * sys.kT)
                throw SceneError(
                    "state.density: " + std::to_string(scene.state.density) +
                    " puts lattice neighbours " + std::to_string(lattice.nearest) +
                    " Å apart, deep in the repulsive core (overlap); lower the density");
        }
    // The species before the velocities: each body's are drawn at its species' mass.
    if constexpr (requires { sys.bodies[0].species; })
        detail::assignSpecies(sys.bodies, speciesCounts(scene, n),
                              namedStream(scene.seed, "species"));
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
    if (n > 1) detail::refuseOverlappingNeighbours(sys, lattice, scene);
    // The centre of mass at rest.
    double totalMass = sys.body.mass * n;
    if constexpr (MassPerBody<K>) {
        totalMass = 0.0;
        for (const auto& b : sys.bodies)
            totalMass += bodyMass<K>(b, sys.body);
    }
    const Vec3 pMean = totalMomentum(sys) / totalMass;
    for (auto& b : sys.bodies)
        b.v -= pMean;
    rescaleToTemperature(sys, sys.kT);
    return sys;
}

} // namespace terrace
