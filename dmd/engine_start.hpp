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
// without it. Functions of the engine's shared state (dmd/engine_state.hpp), with nothing of their
// own; of the prediction's they take only the horizon stream and the level tolerance.
// Units: Å, kJ/mol, time unit 100 fs.
#include "core/gather_in_place.hpp"
#include "core/overlap.hpp"
#include "core/pair_potential.hpp"
#include "core/scene.hpp"
#include "core/step_potential.hpp"
#include "core/system.hpp"
#include "dmd/body_clocks.hpp"
#include "dmd/engine_state.hpp"
#include "dmd/horizon_jitter.hpp"
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

/// What a resumed engine needs beyond the bodies: the time, the impulse virial, every pair off
/// terrace 0, and the horizon stream's position. Clocks must all be at s.time (right after
/// advanceTo).
template <BodyKind K, PairPotential P>
nlohmann::json checkpointOf(const EngineState<K, P>& s, const HorizonJitter& jitter) {
    for (int i = 0; i < s.sys.size(); ++i)
        if (s.schedule.book(i).clock != s.time)
            throw std::logic_error("dmd: checkpoint with clocks not at one time");
    // Counted first: grown by doubling, the bytes held up to twice their size while the
    // next engine was built from them (the peak of a run with restart points).
    std::size_t count = 0;
    s.lists.forEachPairOffZero([&](int, int, int) { ++count; });
    std::vector<std::uint8_t> pairs;
    pairs.reserve(count * sizeof(PairTerrace));
    // In the scene's numbering of the bodies, whatever the engine's own.
    s.lists.forEachPairOffZero([&](int i, int j, int n) {
        const int a = s.sceneIndex(i), b = s.sceneIndex(j);
        appendPairTerrace(pairs, {std::min(a, b), std::max(a, b), n});
    });
    const auto stream = jitter.position();
    return {{"time", s.time},
            {"impulse_virial", s.impulseVirial},
            {"terraces", nlohmann::json::binary(std::move(pairs))},
            {"horizon_stream", {{"state", stream.state}, {"ready", stream.ready}}}};
}

/// The bodies at s.time, in the scene's order, moved out of the state rather than copied beside
/// it (96 B a rod, a tenth of the engine's memory). The state is then fit only to be destroyed.
template <BodyKind K, PairPotential P> System<K, P> releaseBodies(EngineState<K, P>& s) {
    auto& bodies = s.sys.bodies;
    const int n = s.sys.size();
    for (int i = 0; i < n; ++i)
        bodies[i] = stateNow(s, i); // reads body i and its clock alone
    // Engine order to the scene's, in place: scene body b is engine body engineIndex(b).
    gatherInPlace(bodies, [&](int b) { return s.engineIndex(b); });
    return std::move(s.sys);
}

template <BodyKind K, PairPotential P> void checkBodies(const System<K, P>& sys) {
    for (int i = 0; i < sys.size(); ++i) {
        const typename K::State& b = sys.bodies[i];
        if (!b.r.allFinite() || !b.v.allFinite() || !K::axis(b).allFinite() ||
            !K::angularVelocity(b, sys.body).allFinite())
            throw SceneError("state: body " + std::to_string(i) + " has a non-finite value");
    }
    if (!(sys.body.mass > 0.0)) throw SceneError("body.mass: must be > 0");
    if constexpr (MassPerBody<K>)
        for (const auto& b : sys.bodies)
            if (!(bodyMass<K>(b, sys.body) > 0.0))
                throw SceneError("species: every species' mass must be > 0");
}

/// Terrace of every pair from U at the start; a pair on a level (within the search's level
/// tolerance, kJ/mol) goes to the terrace it is heading into, so that the start holds no zero-time
/// event.
template <BodyKind K, PairPotential P>
void assignInitialTerraces(EngineState<K, P>& s, double levelTolerance) {
    const System<K, P>& sys = s.sys;
    const double uMin = sys.potential.minimumEnergy();
    for (int i = 0; i < sys.size(); ++i)
        s.cells.forEachNeighbour(i, [&](int j) {
            if (j < i) return;
            const typename K::State &bi = sys.bodies[i], &bj = sys.bodies[j];
            const Vec3 rij = sys.box.minimumImage(bi.r - bj.r);
            if (rij.norm() > s.settings.rm) return;
            const PairForce f =
                sys.potential.evaluate(rij, orientationOf<P, K>(bi), orientationOf<P, K>(bj));
            const double rate = dUdt(f, bi.v - bj.v, K::angularVelocity(bi, sys.body),
                                     K::angularVelocity(bj, sys.body));
            int n = s.settings.levels.terraceOf(f.U, rate, levelTolerance);
            if constexpr (isSteppedModel<P>) {
                // A step table's carrier is no energy: a pair overlaps when it lies inside the
                // hard core. One on the core's radius heading in is put outside, to reflect now.
                const auto& L = s.settings.levels;
                if (std::isinf(L.energy(n)) && f.U <= L.lower(n) + levelTolerance) --n;
                if (std::isinf(L.energy(n)))
                    throwOverlap(s.sceneIndex(i), s.sceneIndex(j), L.energy(n));
            } else if (overlapsAtStart(f.U, uMin)) {
                throwOverlap(s.sceneIndex(i), s.sceneIndex(j), f.U);
            }
            s.lists.setTerrace(i, j, n);
        });
}

/// The time, the impulse virial and the horizon stream's position of a checkpoint.
template <BodyKind K, PairPotential P>
void resumeClocks(EngineState<K, P>& s, HorizonJitter& jitter, const nlohmann::json& c) {
    s.time = c.at("time").get<double>();
    if (!std::isfinite(s.time) || s.time < 0.0)
        throw SceneError("restart: the DMD time is not a finite time >= 0");
    s.impulseVirial = c.at("impulse_virial").get<double>();
    if (!std::isfinite(s.impulseVirial))
        throw SceneError("restart: the DMD impulse virial is not finite");
    for (int i = 0; i < s.sys.size(); ++i)
        s.schedule.book(i).clock = s.time;
    const auto& stream = c.at("horizon_stream");
    jitter.resumeAt({stream.at("state").get<std::uint64_t>(), stream.at("ready").get<double>()});
}

/// The terraces of a checkpoint; pairs it does not list are on terrace 0. A pair listed
/// beyond r_m, or out of range, means the file does not belong to these bodies. The file
/// numbers the bodies as the scene does; the engine's numbering is set before this.
template <BodyKind K, PairPotential P>
void resumeTerraces(EngineState<K, P>& s, const nlohmann::json& c) {
    const System<K, P>& sys = s.sys;
    forEachPairTerrace(c.at("terraces"), [&](const PairTerrace& p) {
        const int i = p.i, j = p.j, n = p.terrace;
        if (i < 0 || j < 0 || i >= sys.size() || j >= sys.size() || i == j)
            throw SceneError("restart: terrace of a pair of bodies that do not exist");
        // A pair leaves terrace 0 at r_m exactly: a sample there may read r a round-off
        // beyond it.
        const int a = s.engineIndex(i), b = s.engineIndex(j);
        const Vec3 rij = sys.box.minimumImage(sys.bodies[a].r - sys.bodies[b].r);
        if (rij.norm() > s.settings.rm * (1.0 + resumeRangeTolerance))
            throw SceneError("restart: bodies " + std::to_string(i) + " and " + std::to_string(j) +
                             " are held on terrace " + std::to_string(n) +
                             " beyond the interaction range");
        s.lists.setTerrace(std::min(a, b), std::max(a, b), n);
    });
}

} // namespace terrace::dmd
