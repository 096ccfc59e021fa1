#pragma once
// What the run driver (cli/run_driver.hpp) needs from an engine, all of it: the driver calls
// these and nothing else, so it never asks which engine it holds. Sampling in physical time is
// decided outside the engines: the driver calls advanceTo(t_k) on a uniform grid for either
// engine (STYLE.md item 9); where an engine keeps its bodies in an order of its own (for memory
// locality), it renumbers them inside advanceTo and answers every question in the scene's
// numbering.
#include "core/continuous_sums.hpp"
#include "core/pressure.hpp"
#include "core/snapshot.hpp"
#include "core/vec.hpp"
#include <concepts>
#include <nlohmann/json.hpp>
#include <span>
#include <utility>

namespace terrace {

/// What an engine hands over when it is dropped at a restart point: its bodies as they are now,
/// in the scene's numbering, and what a new engine needs beyond them to undergo the same events
/// (its checkpoint). The engine is spent by it.
template <class System> struct Released {
    System system;
    nlohmann::json checkpoint;
};

template <class E>
concept Engine = requires(E e, const E ce, double t, std::span<const int> bodies,
                          TerracingProfile* profile) {
    e.advanceTo(t);                                        // t in time units, t ≥ time()
    { ce.time() } -> std::convertible_to<double>;          // current (synchronised) time
    { ce.snapshot() } -> std::same_as<Snapshot>;           // all bodies at time()
    { ce.snapshot(bodies) } -> std::same_as<Snapshot>;     // those bodies (scene numbers), in order
    { ce.positions() } -> std::same_as<Snapshot>;          // every body's position only
    { ce.position(0) } -> std::same_as<Vec3>;              // one body's (scene number), at time()
    { ce.kineticEnergy() } -> std::convertible_to<double>; // kJ/mol at time()
    { ce.translationalKineticEnergy() } -> std::convertible_to<double>; // ½ m Σ v², kJ/mol
    {
        ce.potentialEnergy()
        } -> std::convertible_to<double>; // kJ/mol: the one integrated
                                          // (terraced for DMD)
    // the continuous model's U and W on the engine's configuration (core/continuous_sums.hpp);
    // each interacting pair's e^{−β(U−V)} into *profile when not null (nothing for SMD: V = U)
    { ce.continuousSums(profile) } -> std::same_as<ContinuousSums>;
    { E::virialKind } -> std::convertible_to<VirialKind>; // what virial() holds
    { ce.virial() } -> std::convertible_to<double>;       // core/pressure.hpp
    { ce.totalMomentum() } -> std::convertible_to<Vec3>;  // g/mol Å per time unit
    e.rescaleTemperature(t); // scale v and ω so that the kinetic temperature is kT = t
    // kinetic energy the heat bath (run.heat_bath) has taken out since the run began, kJ/mol
    { ce.thermostatEnergy() } -> std::convertible_to<double>;
    { ce.statistics() } -> std::convertible_to<nlohmann::json>; // engine-specific summary keys
    { ce.checkpoint() } -> std::convertible_to<nlohmann::json>; // beyond the bodies, at time()
    ce.system();                                                // the bodies now (a copy)
    { std::move(e).release() } -> std::same_as<Released<decltype(ce.system())>>;
};

} // namespace terrace
