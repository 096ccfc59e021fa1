#pragma once
// The local clocks of the DMD engine's bodies (dmd/engine.hpp) and the free orbits cached at them.
//
// Between events every body moves freely (core freeMove: straight line + exact rotation), so a
// body's stored state is kept at its own clock and brought to the current time only when it
// takes part in an event (or at a sample, for all). Its free orbit from that state
// (core/free_orbit.hpp) serves the searches (dmd/pair_prediction.hpp), which evaluate U(t) from
// it without copying states, and turns a linear rotor on; it is kept beside the state only where
// building it costs more than fetching it (keepsOrbit). With the
// orbit the clock keeps a bound on how fast the body's axis turns, for the search steps and the
// hold screen. The clock and that bound sit in the body's book (dmd/schedule.hpp BodyBook), in
// the cache line its event bookkeeping reads anyway.
//
// Apart from the engine so that its event loop reads as the algorithm: every event starts by
// bringing its bodies to now. Functions of the engine's shared state (dmd/engine_state.hpp), which
// holds the bodies, their books and the orbits: the clocks keep nothing of their own.
// Units: Å, time unit 100 fs.
#include "core/asymmetric_top.hpp"
#include "core/free_orbit.hpp"
#include "core/linear_rotor.hpp"
#include "core/species_rotor.hpp"
#include "core/sphere.hpp"
#include "core/symmetric_top.hpp"
#include "core/system.hpp"
#include "core/vec.hpp"
#include "dmd/engine_state.hpp"
#include <cmath>
#include <type_traits>
#include <vector>

namespace terrace::dmd {

/// Whether the clocks keep each body's orbit beside its state, or build it from the state (and
/// the book's |ω|) whenever a search or a flight asks for it. In a large system a kept orbit is
/// one more line fetched for every body an event touches, its own and each partner's, so it is
/// kept only where building it costs more than a miss:
/// - an asymmetric top: kept (its prepared free rotation, elliptic functions and all);
/// - a linear rotor: built (s and ω are the state's; |ω| is the book's axis rate, so ω̂ × s takes
///   one division and a cross product); keeping the 32 B of |ω| and ω̂ × s in an array of their
///   own was 13 % of the lines an event read from memory at 262 144 rods, though not measurably
///   of its time, and 32 B per body (docs/PERFORMANCE.md);
/// - a sphere (nothing turns) and a symmetric top (its orbit is a copy of the state, rotated
///   afresh at every τ): built, a copy.
template <BodyKind K> inline constexpr bool keepsOrbit = std::is_same_v<K, AsymmetricTop>;

// The functions below are declared inline, as the members they once were implicitly: g++ gives
// inline-declared functions a larger budget, and without it kept positionNow out of line in the
// list rebuild's scan (~1.5 % more instructions in a run of the dense rods).

/// A bound on how fast the body's long axis turns in free flight, |ṡ| = |ω × s| ≤ |ω| (rad per
/// time unit): |ω| itself for a linear rotor, whose ω is constant; for a top, whose |ω| varies,
/// the largest |ω| its rotational energy allows, 2T = Σ I_k ω_k² ≥ I_min |ω|².
template <BodyKind K>
inline double axisRateBound(const typename K::State& b, const BodyParams& body) {
    if constexpr (K::rotationalDof == 0) {
        return 0.0;
    } else if constexpr (isLinearRotorKind<K>) {
        return b.w.norm();
    } else {
        return std::sqrt(2.0 * K::rotationalKinetic(b, body) / body.inertia.minCoeff());
    }
}

/// Each body's orbit from its state at its clock (all clocks set).
template <BodyKind K, PairPotential P> inline void cacheOrbits(EngineState<K, P>& s) {
    if constexpr (keepsOrbit<K>) s.orbit.reserve(s.sys.bodies.size());
    for (int i = 0; i < s.sys.size(); ++i) {
        if constexpr (keepsOrbit<K>) s.orbit.emplace_back(s.sys.bodies[i], s.sys.body);
        s.schedule.book(i).axisRate = axisRateBound<K>(s.sys.bodies[i], s.sys.body);
    }
}

/// Body i's free orbit from its state at its clock: the kept one, or one built from the state
/// (a value, not a reference).
template <BodyKind K, PairPotential P>
inline decltype(auto) orbitOf(const EngineState<K, P>& s, int i) {
    if constexpr (keepsOrbit<K>)
        return s.orbit[i];
    else if constexpr (isLinearRotorKind<K>)
        return FreeOrbit<K>(s.sys.bodies[i], s.schedule.book(i).axisRate);
    else
        return FreeOrbit<K>(s.sys.bodies[i], s.sys.body);
}

template <BodyKind K, PairPotential P> inline Vec3 positionNow(const EngineState<K, P>& s, int i) {
    const typename K::State& b = s.sys.bodies[i];
    return translated(b.r, b.v, s.time - s.schedule.book(i).clock);
}

/// The engine's body i as it is now, its stored state moved freely from its clock.
template <BodyKind K, PairPotential P>
inline typename K::State stateNow(const EngineState<K, P>& s, int i) {
    typename K::State b = s.sys.bodies[i];
    freeMove<K>(b, s.sys.body, s.time - s.schedule.book(i).clock);
    return b;
}

/// The cached orbit is rebuilt after every change of a stored state other than a rotor's free
/// flight, which bringToNow follows by turning the orbit itself (impulse, rescale, free motion
/// of other kinds).
template <BodyKind K, PairPotential P> inline void refreshOrbit(EngineState<K, P>& s, int i) {
    if constexpr (keepsOrbit<K>) s.orbit[i] = FreeOrbit<K>(s.sys.bodies[i], s.sys.body);
    s.schedule.book(i).axisRate = axisRateBound<K>(s.sys.bodies[i], s.sys.body);
}

template <BodyKind K, PairPotential P> inline void bringToNow(EngineState<K, P>& s, int i) {
    const double dt = s.time - s.schedule.book(i).clock;
    s.schedule.book(i).clock = s.time;
    if constexpr (isLinearRotorKind<K>) {
        // A rotor's ω is constant in free flight: its orbit, turned on by dt, gives its new
        // axis (FreeOrbit::advancedBy), and |ω| in the book stays.
        typename K::State& b = s.sys.bodies[i];
        b.r = translated(b.r, b.v, dt);
        b.s = orbitOf(s, i).advancedBy(dt).axis(); // from b.s before it turns
    } else {
        freeMove<K>(s.sys.bodies[i], s.sys.body, dt);
        refreshOrbit(s, i);
    }
}

/// Every clock brought to t.
template <BodyKind K, PairPotential P> inline void synchronise(EngineState<K, P>& s, double t) {
    s.time = t;
    for (int i = 0; i < s.sys.size(); ++i)
        bringToNow(s, i);
}

} // namespace terrace::dmd
