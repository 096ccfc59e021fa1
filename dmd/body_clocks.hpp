#pragma once
// The local clocks of the DMD engine's bodies (dmd/engine.hpp) and the free orbits cached at them.
//
// Between events every body moves freely (core freeMove: straight line + exact rotation), so a
// body's stored state is kept at its own clock and brought to the current time only when it
// takes part in an event (or at a sample, for all). Its free orbit from that state
// (core/free_orbit.hpp) is cached beside it: the searches (dmd/pair_prediction.hpp) evaluate U(t)
// from it without copying states, and a linear rotor is turned on by its orbit alone. With the
// orbit the clock keeps a bound on how fast the body's axis turns, for the search steps and the
// hold screen. The clock and that bound sit in the body's book (dmd/schedule.hpp BodyBook), in
// the cache line its event bookkeeping reads anyway.
//
// Apart from the engine so that its event loop reads as the algorithm: every event starts by
// bringing its bodies to now. A mixin (CRTP), as dmd/pair_prediction.hpp: BodyClocks is a base of
// the engine, owns the orbits and moves the engine's bodies. Units: Å, time unit 100 fs.
#include "core/free_orbit.hpp"
#include "core/sphere.hpp"
#include "core/symmetric_top.hpp"
#include "core/system.hpp"
#include "core/vec.hpp"
#include <cmath>
#include <type_traits>
#include <vector>

namespace terrace::dmd {

/// What the clocks keep of a body's orbit: what its state at the clock does not already hold,
/// from which of(state, params) gives the orbit back, bit for bit. In a large system a partner's
/// orbit is a miss at every prediction, so the less kept, the fewer lines fetched:
/// - an asymmetric top: the whole orbit (its prepared free rotation);
/// - a linear rotor: the orbit, based at its clock, holds the state's own axis and ω, so only its
///   turn (|ω| and ω̂ × s) is kept, 32 B in one line instead of 88 B over two or three;
/// - a sphere (nothing turns) and a symmetric top (whose orbit is a copy of the state, rotated
///   afresh at every τ): nothing.
template <BodyKind K> struct KeptOrbit {
    FreeOrbit<K> orbit;
    explicit KeptOrbit(const FreeOrbit<K>& o) : orbit(o) {}
    const FreeOrbit<K>& of(const typename K::State&, const BodyParams&) const { return orbit; }
};
template <> struct KeptOrbit<LinearRotor> {
    FreeOrbit<LinearRotor>::Turn turn;
    explicit KeptOrbit(const FreeOrbit<LinearRotor>& o) : turn(o.turn()) {}
    FreeOrbit<LinearRotor> of(const LinearRotor::State& b, const BodyParams&) const {
        return {b.s, b.w, turn};
    }
};
template <BodyKind K>
requires(std::is_same_v<K, Sphere> || std::is_same_v<K, SymmetricTop>) struct KeptOrbit<K> {
    explicit KeptOrbit(const FreeOrbit<K>&) {}
    FreeOrbit<K> of(const typename K::State& b, const BodyParams& p) const { return {b, p}; }
};
static_assert(sizeof(KeptOrbit<LinearRotor>) == 32);

/// Engine: the class deriving from this one (dmd::Engine<K, P>), a friend of it.
template <BodyKind K, PairPotential P, class Engine> class BodyClocks {
protected:
    using State = typename K::State;

    /// Each body's orbit from its state at its clock (all clocks set).
    void cacheOrbits() {
        Engine& engine = self();
        orbit_.reserve(engine.sys_.bodies.size());
        for (int i = 0; i < engine.sys_.size(); ++i) {
            orbit_.emplace_back(FreeOrbit<K>(engine.sys_.bodies[i], engine.sys_.body));
            engine.schedule_.book(i).axisRate = axisRateBound(engine.sys_.bodies[i]);
        }
    }

    Vec3 positionNow(int i) const {
        const Engine& engine = self();
        const State& b = engine.sys_.bodies[i];
        return translated(b.r, b.v, engine.time_ - engine.schedule_.book(i).clock);
    }

    void bringToNow(int i) {
        Engine& engine = self();
        const double dt = engine.time_ - engine.schedule_.book(i).clock;
        engine.schedule_.book(i).clock = engine.time_;
        if constexpr (std::is_same_v<K, LinearRotor>) {
            // A rotor's ω is constant in free flight: its cached orbit, turned on by dt, gives
            // its new axis and stays its orbit (FreeOrbit::advancedBy).
            State& b = engine.sys_.bodies[i];
            b.r = translated(b.r, b.v, dt);
            const FreeOrbit<K> turned = orbitOf(i).advancedBy(dt); // from b.s before it turns
            b.s = turned.axis();
            orbit_[i] = KeptOrbit<K>(turned);
        } else {
            freeMove<K>(engine.sys_.bodies[i], engine.sys_.body, dt);
            refreshOrbit(i);
        }
    }
    /// The cached orbit is rebuilt after every change of a stored state other than a rotor's free
    /// flight, which bringToNow follows by turning the orbit itself (impulse, rescale, free motion
    /// of other kinds).
    void refreshOrbit(int i) {
        Engine& engine = self();
        orbit_[i] = KeptOrbit<K>(FreeOrbit<K>(engine.sys_.bodies[i], engine.sys_.body));
        engine.schedule_.book(i).axisRate = axisRateBound(engine.sys_.bodies[i]);
    }

    /// A bound on how fast the body's long axis turns in free flight, |ṡ| = |ω × s| ≤ |ω| (rad per
    /// time unit): |ω| itself for a linear rotor, whose ω is constant; for a top, whose |ω| varies,
    /// the largest |ω| its rotational energy allows, 2T = Σ I_k ω_k² ≥ I_min |ω|².
    double axisRateBound(const State& b) const {
        const BodyParams& body = self().sys_.body;
        if constexpr (K::rotationalDof == 0) {
            return 0.0;
        } else if constexpr (std::is_same_v<K, LinearRotor>) {
            return b.w.norm();
        } else {
            return std::sqrt(2.0 * K::rotationalKinetic(b, body) / body.inertia.minCoeff());
        }
    }

    void synchronise(double t) {
        Engine& engine = self();
        engine.time_ = t;
        for (int i = 0; i < engine.sys_.size(); ++i)
            bringToNow(i);
    }

    /// Body i's free orbit from its state at its clock (unless the whole orbit is kept, built
    /// from the state: a value, not a reference).
    decltype(auto) orbitOf(int i) const {
        return orbit_[i].of(self().sys_.bodies[i], self().sys_.body);
    }

    std::vector<KeptOrbit<K>> orbit_; // each body's free orbit from its state at its clock

private:
    const Engine& self() const { return static_cast<const Engine&>(*this); }
    Engine& self() { return static_cast<Engine&>(*this); }
};

} // namespace terrace::dmd
