#pragma once
// The heat bath of a run (scene key run.heat_bath): none (NVE), Andersen's stochastic collisions
// or the canonical-sampling velocity rescaling (CSVR) of Bussi, Donadio & Parrinello, J. Chem.
// Phys. 126, 014101 (2007). The engines apply it (dmd/engine.hpp, smd/engine.hpp); this header
// holds what both share: the settings in engine units, the degrees of freedom the canonical
// kinetic energy has under each, CSVR's exact kinetic-energy propagator, Andersen's fresh
// Maxwell–Boltzmann draw for one body, and the bath's state (its random stream from the scene's
// seed, the energy it removed), which a checkpoint carries so that a continued run draws the
// same numbers as one that never stopped.
#include "core/body_kind.hpp"
#include "core/initial_state.hpp"
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

namespace terrace {

struct HeatBath {
    enum class Kind { None, Andersen, Csvr };
    Kind kind = Kind::None;
    double rate = 0.0; // Andersen: collisions per body per time unit (100 fs)
    double tau = 0.0;  // CSVR: relaxation time of the kinetic energy, time units
    double kT = 0.0;   // kJ/mol
    bool on() const { return kind != Kind::None; }
};

/// The scene's run.heat_bath in engine units, at the scene's temperature.
HeatBath heatBathOf(const Scene& scene);

/// Degrees of freedom of the kinetic energy under the bath, for n bodies with `rotationalDofs`
/// rotational ones together (each body's: 0 a sphere, 2 a linear rotor, 3 a top; a mixture of rods
/// and spheres sums its own): Andersen's collisions change the total momentum, so all 3N + r
/// count; CSVR and NVE keep it, which takes 3 away.
int heatBathDof(HeatBath::Kind kind, int rotationalDofs, int n);

/// CSVR's kinetic energy after a time t of its stochastic equation
///   dK = (K̄ − K) dt/τ + 2 sqrt(K K̄ / f) dW,   K̄ = f kT / 2,
/// drawn exactly (Bussi et al. 2007, eq. A7) with c = e^{−t/τ}: one Gaussian R₁ and the sum of the
/// other f − 1 squared Gaussians, drawn as 2·Gamma((f − 1)/2, 1). `sign` is set to the sign of the
/// velocities' factor (R₁ + sqrt(c f K / ((1 − c) K̄)) < 0 reverses them, as the exact solution
/// for the momenta has it).
double csvrKinetic(double K, double Kbar, int f, double c, std::mt19937_64& rng, double& sign);

/// The state a bath carries through a run: its stream, the energy it has taken out of the system
/// since the run began (kJ/mol; negative when it put energy in), and the time of its next event
/// (DMD's Andersen process) or of its last rescale (DMD's CSVR).
struct HeatBathState {
    std::mt19937_64 rng;
    double removed = 0.0;
    double clock = 0.0; // time units
    /// A fresh stream from the scene's seed.
    explicit HeatBathState(std::uint64_t seed = 1);
    nlohmann::json save() const;
    /// The state saved by save(); SceneError when it does not read.
    void restore(const nlohmann::json& j);
};

/// An exponential waiting time of rate `rate` (per time unit) from the stream.
double exponentialWait(double rate, std::mt19937_64& rng);

/// Andersen's collision of one body: fresh velocity, and angular velocity for a rotating body,
/// from the Maxwell–Boltzmann distribution at kT (the body-frame canonical distribution with the
/// principal inertias: core/initial_state.hpp thermalise). Returns the kinetic energy removed.
template <BodyKind K>
double andersenCollision(typename K::State& b, const BodyParams& p, double kT,
                         std::mt19937_64& rng) {
    const double before = kineticEnergy<K>(b, p);
    detail::thermalise<K>(b, p, kT, rng);
    return before - kineticEnergy<K>(b, p);
}

} // namespace terrace
