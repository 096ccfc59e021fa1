#pragma once
// What the run driver (cli) needs from an engine. Sampling in physical time is decided outside the
// engines: the driver calls advanceTo(t_k) on a uniform grid for either engine (STYLE.md item 9).
#include "core/snapshot.hpp"
#include "core/vec.hpp"
#include <concepts>
#include <nlohmann/json.hpp>
#include <span>

namespace terrace {

template <class E>
concept Engine = requires(E e, const E ce, double t, std::span<const int> bodies) {
    e.advanceTo(t);                                        // t in time units, t ≥ time()
    { ce.time() } -> std::convertible_to<double>;          // current (synchronised) time
    { ce.snapshot() } -> std::same_as<Snapshot>;           // all bodies at time()
    { ce.snapshot(bodies) } -> std::same_as<Snapshot>;     // those bodies (scene numbers), in order
    { ce.positions() } -> std::same_as<Snapshot>;          // every body's position only
    { ce.position(0) } -> std::same_as<Vec3>;              // one body's (scene number), at time()
    { ce.kineticEnergy() } -> std::convertible_to<double>; // kJ/mol at time()
    { ce.potentialEnergy() } -> std::convertible_to<double>; // kJ/mol: terraced for DMD
    { ce.totalMomentum() } -> std::convertible_to<Vec3>;     // g/mol Å per time unit
    e.rescaleTemperature(t); // scale v and ω so that the kinetic temperature is kT = t
    { ce.statistics() } -> std::convertible_to<nlohmann::json>; // engine-specific summary keys
};

} // namespace terrace
