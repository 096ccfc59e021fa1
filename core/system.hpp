#pragma once
// The shape both engines share: bodies of one kind in a periodic box, interacting through one pair
// potential. Engines take a System by value, advance it, and hand out Snapshots.
#include "core/body_kind.hpp"
#include "core/body_orientation.hpp"
#include "core/box.hpp"
#include "core/huge_pages.hpp"
#include "core/pair_potential.hpp"
#include <cmath>
#include <vector>

namespace terrace {

template <BodyKind K, PairPotential P> struct System {
    using Kind = K;
    using Potential = P;
    PeriodicBox box;
    BodyParams body;
    P potential;
    BodyArray<typename K::State> bodies; // in huge pages when large (core/huge_pages.hpp)
    double kT = 0.0;                     // thermal energy of the state point, kJ/mol

    int size() const { return static_cast<int>(bodies.size()); }
};

/// Degrees of freedom used for the instantaneous temperature: total momentum is fixed (-3).
inline int degreesOfFreedom(int rotationalDof, int n) {
    return (3 + rotationalDof) * n - 3;
}
/// The same for n bodies of a kind whose bodies all have K::rotationalDof.
template <BodyKind K>
requires(!DofPerBody<K>) int degreesOfFreedom(int n) {
    return degreesOfFreedom(K::rotationalDof, n);
}

/// The rotational degrees of freedom of every body together.
template <BodyKind K, PairPotential P> int totalRotationalDof(const System<K, P>& sys) {
    if constexpr (DofPerBody<K>) {
        int f = 0;
        for (const auto& b : sys.bodies)
            f += K::rotationalDofOf(b, sys.body);
        return f;
    } else {
        return K::rotationalDof * sys.size();
    }
}
/// Degrees of freedom of the instantaneous temperature of the system (total momentum fixed).
template <BodyKind K, PairPotential P> int degreesOfFreedom(const System<K, P>& sys) {
    return 3 * sys.size() + totalRotationalDof(sys) - 3;
}

template <BodyKind K, PairPotential P> double totalKinetic(const System<K, P>& sys) {
    double e = 0.0;
    for (const auto& b : sys.bodies)
        e += kineticEnergy<K>(b, sys.body);
    return e;
}

/// ½ m Σ v², kJ/mol: the kinetic energy of the centres, which alone enters the pressure.
template <BodyKind K, PairPotential P> double translationalKinetic(const System<K, P>& sys) {
    double e = 0.0;
    if constexpr (MassPerBody<K>) {
        for (const auto& b : sys.bodies)
            e += bodyMass<K>(b, sys.body) * b.v.squaredNorm();
        return 0.5 * e;
    }
    for (const auto& b : sys.bodies)
        e += b.v.squaredNorm();
    return 0.5 * sys.body.mass * e;
}

template <BodyKind K, PairPotential P> Vec3 totalMomentum(const System<K, P>& sys) {
    Vec3 p = Vec3::Zero();
    for (const auto& b : sys.bodies)
        p += bodyMass<K>(b, sys.body) * b.v;
    return p;
}

/// Scale v and ω of every body so that the kinetic temperature equals kT exactly.
template <BodyKind K, PairPotential P> void rescaleToTemperature(System<K, P>& sys, double kT) {
    const double target = 0.5 * degreesOfFreedom(sys) * kT;
    const double now = totalKinetic(sys);
    if (now <= 0.0) return;
    const double f = std::sqrt(target / now);
    for (auto& b : sys.bodies) {
        b.v *= f;
        K::scaleAngularVelocity(b, sys.body, f);
    }
}

/// Total angular momentum about the origin, Σ (r_i × p_i + L_i). Meaningful for isolated
/// clusters only: periodic images break rotational invariance.
template <BodyKind K, PairPotential P> Vec3 totalAngularMomentum(const System<K, P>& sys) {
    Vec3 l = Vec3::Zero();
    for (const auto& b : sys.bodies)
        l += b.r.cross(bodyMass<K>(b, sys.body) * b.v) + K::angularMomentum(b, sys.body);
    return l;
}

/// Continuous potential energy by the O(N²) minimum-image sum: the slow, obviously right path.
template <BodyKind K, PairPotential P> double potentialEnergyAllPairs(const System<K, P>& sys) {
    double u = 0.0;
    for (int i = 0; i < sys.size(); ++i)
        for (int j = i + 1; j < sys.size(); ++j) {
            const Vec3 rij = sys.box.minimumImage(sys.bodies[i].r - sys.bodies[j].r);
            u += sys.potential.energy(rij, orientationOf<P, K>(sys.bodies[i]),
                                      orientationOf<P, K>(sys.bodies[j]));
        }
    return u;
}

} // namespace terrace
