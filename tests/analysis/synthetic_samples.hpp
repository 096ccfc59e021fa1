#pragma once
// Sample sets with known correlation functions, built in the tests from the exact free motion of
// core and from exactly sampled stochastic processes:
//   free particles      r(t) = r0 + v t: VACF = 1, MSD = ⟨v²⟩ t²
//   free linear rotors  s(t) by LinearRotor::freeRotate, ω ⟂ s from 2-D Maxwell–Boltzmann
//   Ornstein–Uhlenbeck  v(t+h) = v e^{−γh} + √(kT/m (1 − e^{−2γh})) ξ: VACF = e^{−γt}
//   random walk         r(t+h) = r + √(2 D h) ξ per component: MSD = 6 D t
#include "core/linear_rotor.hpp"
#include "core/snapshot.hpp"
#include "core/units.hpp"
#include <cmath>
#include <random>
#include <vector>

namespace terrace::analysis::synthetic {

inline Vec3 gaussianVector(std::mt19937_64& rng, double sd) {
    std::normal_distribution<double> g(0.0, sd);
    return {g(rng), g(rng), g(rng)};
}

inline Vec3 unitVector(std::mt19937_64& rng) {
    Vec3 u;
    do
        u = gaussianVector(rng, 1.0);
    while (u.norm() < 1e-3);
    return u.normalized();
}

/// n snapshots of `bodies` empty bodies at times k·h (time units) in a box of edge length.
inline std::vector<Snapshot> emptySamples(int n, int bodies, double h, double length) {
    std::vector<Snapshot> s(n);
    for (int k = 0; k < n; ++k) {
        s[k].time = k * h;
        s[k].boxLength = length;
        s[k].position.assign(bodies, Vec3::Zero());
        s[k].velocity.assign(bodies, Vec3::Zero());
        s[k].axis.assign(bodies, Vec3::UnitZ());
        s[k].omega.assign(bodies, Vec3::Zero());
    }
    return s;
}

/// Free linear rotors (and free flight): velocities N(0, kT/m), ω ⟂ s with components N(0, kT/I).
inline std::vector<Snapshot> freeRotors(int n, int bodies, double h, double length, double kT,
                                        double mass, double inertia, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(0.0, length);
    const BodyParams params{mass, Vec3(inertia, inertia, 0.0)};
    auto samples = emptySamples(n, bodies, h, length);
    std::normal_distribution<double> g(0.0, std::sqrt(kT / inertia));
    for (int i = 0; i < bodies; ++i) {
        LinearRotor::State b;
        b.r = {uniform(rng), uniform(rng), uniform(rng)};
        b.v = gaussianVector(rng, std::sqrt(kT / mass));
        b.s = unitVector(rng);
        const Vec3 e1 = b.s.unitOrthogonal(), e2 = b.s.cross(e1);
        b.w = g(rng) * e1 + g(rng) * e2;
        for (int k = 0; k < n; ++k) {
            LinearRotor::State at = b;
            freeMove<LinearRotor>(at, params, k * h); // exact, from t = 0 (no accumulated error)
            samples[k].position[i] = at.r;
            samples[k].velocity[i] = at.v;
            samples[k].axis[i] = at.s;
            samples[k].omega[i] = at.w;
        }
    }
    return samples;
}

/// Ornstein–Uhlenbeck velocities (exact update, started in equilibrium), positions integrated by
/// the trapezoid rule: only the velocities carry a known correlation, e^{−γt}.
inline std::vector<Snapshot> ornsteinUhlenbeck(int n, int bodies, double h, double length,
                                               double kT, double mass, double gamma,
                                               std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    auto samples = emptySamples(n, bodies, h, length);
    const double sd = std::sqrt(kT / mass), decay = std::exp(-gamma * h);
    const double kick = sd * std::sqrt(1.0 - decay * decay);
    std::uniform_real_distribution<double> uniform(0.0, length);
    for (int i = 0; i < bodies; ++i) {
        Vec3 r{uniform(rng), uniform(rng), uniform(rng)}, v = gaussianVector(rng, sd);
        for (int k = 0; k < n; ++k) {
            samples[k].position[i] = r;
            samples[k].velocity[i] = v;
            const Vec3 next = decay * v + gaussianVector(rng, kick);
            r += 0.5 * h * (v + next);
            v = next;
        }
    }
    return samples;
}

/// Brownian random walk with diffusion coefficient d (Å² per time unit), velocities white noise.
inline std::vector<Snapshot> randomWalk(int n, int bodies, double h, double length, double d,
                                        std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    auto samples = emptySamples(n, bodies, h, length);
    std::uniform_real_distribution<double> uniform(0.0, length);
    for (int i = 0; i < bodies; ++i) {
        Vec3 r{uniform(rng), uniform(rng), uniform(rng)};
        for (int k = 0; k < n; ++k) {
            samples[k].position[i] = r;
            samples[k].velocity[i] = gaussianVector(rng, 1.0);
            r += gaussianVector(rng, std::sqrt(2.0 * d * h));
        }
    }
    return samples;
}

} // namespace terrace::analysis::synthetic
