#pragma once
// How the DMD engine (dmd/engine.hpp) starts: from a scene, or from a checkpoint of a run.
//
// A fresh start checks the bodies and gives every pair the terrace of its U, a pair on a level
// going to the terrace it is heading into (so that the start holds no zero-time event). A resumed
// start takes the time, the impulse virial, the pair terraces (never re-derived from U, which may
// sit exactly on a level) and the horizon stream's position from a checkpoint(), which is written
// here too: the writer and the reader of the restart format side by side (cli/restart.hpp keeps
// the file). Calendars, lists and cells are built afresh either way, by the engine.
//
// The pair terraces are the checkpoint's one part that grows with N (a few pairs per body in a
// dense liquid): they are raw bytes, 12 per pair, not JSON arrays (over 100 B per pair in memory,
// held beside the engine at every restart point).
//
// Apart from the engine because it runs once, before the first event: the event loop reads better
// without it. A mixin (CRTP), as dmd/pair_prediction.hpp: EngineStart is a base of the engine,
// with no state of its own, and sets the engine's members. Units: Å, kJ/mol, time unit 100 fs.
#include "core/gather_in_place.hpp"
#include "core/overlap.hpp"
#include "core/pair_potential.hpp"
#include "core/scene.hpp"
#include "core/system.hpp"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace terrace::dmd {

/// A restart file's pair off terrace 0 may sit this fraction beyond r_m (round-off of r at the
/// instant it reached r_m); farther out, the file does not belong to the bodies.
inline constexpr double resumeRangeTolerance = 1e-9;

/// One pair off terrace 0 in a checkpoint: its bodies by scene number (i < j) and its terrace.
struct PairTerrace {
    std::int32_t i = 0, j = 0, terrace = 0;
};
static_assert(sizeof(PairTerrace) == 12, "a checkpoint's pair record is three int32, unpadded");

/// Appends p to a checkpoint's pair bytes (native byte order, as the restart file's bodies).
inline void appendPairTerrace(std::vector<std::uint8_t>& bytes, const PairTerrace& p) {
    const auto* b = reinterpret_cast<const std::uint8_t*>(&p);
    bytes.insert(bytes.end(), b, b + sizeof p);
}

/// f(PairTerrace) for every pair of a checkpoint's "terraces" (raw bytes). A value that is not
/// raw bytes, or bytes that are not whole records (a file cut short or damaged), is a SceneError
/// naming what is wrong.
template <class F> void forEachPairTerrace(const nlohmann::json& terraces, F&& f) {
    if (!terraces.is_binary())
        throw SceneError("restart: the DMD pair terraces are not raw bytes (a checkpoint of "
                         "another format)");
    const auto& bytes = terraces.get_binary();
    if (bytes.size() % sizeof(PairTerrace) != 0)
        throw SceneError("restart: the DMD pair terraces hold " + std::to_string(bytes.size()) +
                         " bytes, not whole records of " + std::to_string(sizeof(PairTerrace)) +
                         " (damaged or cut short)");
    for (std::size_t at = 0; at < bytes.size(); at += sizeof(PairTerrace)) {
        PairTerrace p;
        std::memcpy(&p, bytes.data() + at, sizeof p);
        f(p);
    }
}

/// The pairs of a checkpoint's "terraces", in the order written.
inline std::vector<PairTerrace> pairTerraces(const nlohmann::json& terraces) {
    std::vector<PairTerrace> pairs;
    forEachPairTerrace(terraces, [&](const PairTerrace& p) { pairs.push_back(p); });
    return pairs;
}

template <BodyKind K, PairPotential P> class Engine;

/// Engine: the class deriving from this one (dmd::Engine<K, P>), a friend of it.
template <BodyKind K, PairPotential P, class Engine> class EngineStart {
public:
    /// What a resumed engine needs beyond the bodies: the time, every pair off terrace 0, and the
    /// horizon stream's position. Clocks must all be at time() (call right after advanceTo).
    nlohmann::json checkpoint() const {
        const Engine& engine = self();
        for (int i = 0; i < engine.sys_.size(); ++i)
            if (engine.schedule_.book(i).clock != engine.time_)
                throw std::logic_error("dmd: checkpoint with clocks not at one time");
        // Counted first: grown by doubling, the bytes held up to twice their size while the
        // next engine was built from them (the peak of a run with restart points).
        std::size_t count = 0;
        engine.lists_.forEachPairOffZero([&](int, int, int) { ++count; });
        std::vector<std::uint8_t> pairs;
        pairs.reserve(count * sizeof(PairTerrace));
        // In the scene's numbering of the bodies, whatever the engine's own.
        engine.lists_.forEachPairOffZero([&](int i, int j, int n) {
            const int a = engine.sceneIndex(i), b = engine.sceneIndex(j);
            appendPairTerrace(pairs, {std::min(a, b), std::max(a, b), n});
        });
        const auto stream = engine.jitter_.position();
        return {{"time", engine.time_},
                {"impulse_virial", engine.impulseVirial_},
                {"terraces", nlohmann::json::binary(std::move(pairs))},
                {"horizon_stream", {{"state", stream.state}, {"ready", stream.ready}}}};
    }

    /// The bodies at time(), in the scene's order, as system() gives them, but moved
    /// out of the engine rather than copied beside it (96 B a rod, a tenth of the engine's
    /// memory). The engine is then fit only to be destroyed. Called as releaseSystem(engine).
    static System<K, P> release(Engine& engine) {
        auto& bodies = engine.sys_.bodies;
        const int n = engine.sys_.size();
        for (int i = 0; i < n; ++i)
            bodies[i] = engine.stateNow(i); // reads body i and its clock alone
        // Engine order to the scene's, in place: scene body b is engine body engineIndex(b).
        gatherInPlace(bodies, [&](int b) { return engine.engineIndex(b); });
        return std::move(engine.sys_);
    }

protected:
    using State = typename K::State;

    void checkBodies() const {
        const System<K, P>& sys = self().sys_;
        for (int i = 0; i < sys.size(); ++i) {
            const State& b = sys.bodies[i];
            if (!b.r.allFinite() || !b.v.allFinite() || !K::axis(b).allFinite() ||
                !K::angularVelocity(b, sys.body).allFinite())
                throw SceneError("state: body " + std::to_string(i) + " has a non-finite value");
        }
        if (!(sys.body.mass > 0.0)) throw SceneError("body.mass: must be > 0");
    }

    /// Terrace of every pair from U at the start; a pair on a level (within the search's level
    /// tolerance) goes to the terrace it is heading into, so that the start holds no zero-time
    /// event.
    void assignInitialTerraces() {
        Engine& engine = self();
        const System<K, P>& sys = engine.sys_;
        const double uMin = sys.potential.minimumEnergy();
        for (int i = 0; i < sys.size(); ++i)
            engine.cells_.forEachNeighbour(i, [&](int j) {
                if (j < i) return;
                const State &bi = sys.bodies[i], &bj = sys.bodies[j];
                const Vec3 rij = sys.box.minimumImage(bi.r - bj.r);
                if (rij.norm() > engine.settings_.rm) return;
                const PairForce f =
                    sys.potential.evaluate(rij, orientationOf<P, K>(bi), orientationOf<P, K>(bj));
                if (overlapsAtStart(f.U, uMin))
                    throwOverlap(engine.sceneIndex(i), engine.sceneIndex(j), f.U);
                const double rate = dUdt(f, bi.v - bj.v, K::angularVelocity(bi, sys.body),
                                         K::angularVelocity(bj, sys.body));
                engine.lists_.setTerrace(
                    i, j,
                    engine.settings_.levels.terraceOf(f.U, rate, engine.search_.levelTolerance));
            });
    }

    void resumeClocks(const nlohmann::json& c) {
        Engine& engine = self();
        engine.time_ = c.at("time").get<double>();
        if (!std::isfinite(engine.time_) || engine.time_ < 0.0)
            throw SceneError("restart: the DMD time is not a finite time >= 0");
        engine.impulseVirial_ = c.at("impulse_virial").get<double>();
        if (!std::isfinite(engine.impulseVirial_))
            throw SceneError("restart: the DMD impulse virial is not finite");
        for (int i = 0; i < engine.sys_.size(); ++i)
            engine.schedule_.book(i).clock = engine.time_;
        const auto& stream = c.at("horizon_stream");
        engine.jitter_.resumeAt(
            {stream.at("state").get<std::uint64_t>(), stream.at("ready").get<double>()});
    }

    /// The terraces of a checkpoint; pairs it does not list are on terrace 0. A pair listed
    /// beyond r_m, or out of range, means the file does not belong to these bodies. The file
    /// numbers the bodies as the scene does; the engine's numbering is set before this.
    void resumeTerraces(const nlohmann::json& c) {
        Engine& engine = self();
        const System<K, P>& sys = engine.sys_;
        forEachPairTerrace(c.at("terraces"), [&](const PairTerrace& p) {
            const int i = p.i, j = p.j, n = p.terrace;
            if (i < 0 || j < 0 || i >= sys.size() || j >= sys.size() || i == j)
                throw SceneError("restart: terrace of a pair of bodies that do not exist");
            // A pair leaves terrace 0 at r_m exactly: a sample there may read r a round-off
            // beyond it.
            const int a = engine.engineIndex(i), b = engine.engineIndex(j);
            const Vec3 rij = sys.box.minimumImage(sys.bodies[a].r - sys.bodies[b].r);
            if (rij.norm() > engine.settings_.rm * (1.0 + resumeRangeTolerance))
                throw SceneError("restart: bodies " + std::to_string(i) + " and " +
                                 std::to_string(j) + " are held on terrace " + std::to_string(n) +
                                 " beyond the interaction range");
            engine.lists_.setTerrace(std::min(a, b), std::max(a, b), n);
        });
    }

private:
    const Engine& self() const { return static_cast<const Engine&>(*this); }
    Engine& self() { return static_cast<Engine&>(*this); }
};

/// A restart point's bodies (EngineStart::release): moved out of an engine about to be dropped.
template <BodyKind K, PairPotential P> System<K, P> releaseSystem(Engine<K, P>&& engine) {
    return EngineStart<K, P, Engine<K, P>>::release(engine);
}

} // namespace terrace::dmd
