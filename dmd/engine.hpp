#pragma once
// Event-driven dynamics of rigid bodies on a terraced pair potential (paper secs. 2–5 and
// "Implementation of the event-driven simulation"; DESIGN.md "DMD engine").
//
// Between events every body moves freely (core freeMove: straight line + exact rotation) and the
// terraced energy is constant. An event is the first time a pair's continuous U reaches a level
// bounding its terrace (dmd/root_search.hpp); the collision rule (dmd/collision_rule.hpp) then
// transmits the pair up or down or reflects it, conserving energy and both momenta.
//
// The loop, per calendar entry:  pop → discard if stale → resolve → invalidate → predict.
// This header holds the loop (step, collide, resume, crossCell, relist) and the Engine contract
// (core/engine.hpp); the rest is apart, each part in a header that reads whole:
//   dmd/schedule.hpp — bookkeeping: per-body agendas of pending events with one calendar entry
//     per body, its earliest event (a collision makes some 20 predicted events stale, which then
//     mostly never reach the calendar); per-body event counters captured in each pair event
//     (lazy invalidation; `eager` erases the calendar entries of an invalidated body and those
//     about it through stored handles instead); a cleanup of stale entries when the calendar
//     grows beyond a multiple of its size after the previous cleanup; bins of the bounded queue
//     tuned from the measured push rate (dmd/bin_tuning.hpp).
//   dmd/pair_prediction.hpp — predict: a screen in front of every search: a pair sure to stay on
//     its terrace past the horizon, by bounds on its free motion (dmd/terrace_hold.hpp), gets a
//     sample-less virtual event at the end of that hold instead; virtual events at a jittered
//     horizon (dmd/horizon_jitter.hpp) that resume a truncated search from its stored end point;
//     of a body's own events — cell crossing, relist, entry — only the earliest is planned in its
//     agenda.
//   dmd/body_clocks.hpp — local clocks (a body is brought to the current time only when it takes
//     part in an event) and a free orbit per body cached at its clock (core/free_orbit.hpp) for
//     the searches.
//   dmd/engine_start.hpp — the start from a scene or from a checkpoint, and the checkpoint.
// Here: a cell list with crossing events from which per-body candidate lists with a skin are
// rebuilt by relist events (dmd/neighbour_lists.hpp; a body's pairs are screened from its list
// only); sample events that synchronise all clocks. What more than one part reads — bodies,
// settings, schedule, lists, cells, orbits, time — is the engine's shared state
// (dmd/engine_state.hpp), a member handed to the parts by reference; the prediction, which keeps
// state of its own, is a member beside it (no virtual call, no pointer in the pair loop).
// A clock that stops advancing (a Zeno-like cascade of events at one instant) raises an error
// (dmd/stall_watch.hpp).
// Heat bath (run.heat_bath, core/heat_bath.hpp): Andersen's collisions are events of their own,
// the N bodies' Poisson processes of rate ν drawn as one of rate Nν whose every event picks a body
// at random; the body is then handled as one side of a collision (brought to now, its orbit
// refreshed, its events invalidated and its pairs predicted afresh). CSVR rescales every body by
// its exact propagator's factor at the end of every advanceTo (the run's samples and equilibration
// ticks), over the time since the last: velocities change only there, so the flow between is the
// NVE one, and since both the flow and the rescale leave the canonical distribution of the
// terraced model invariant, the run samples it exactly, whatever the interval.
// Units: Å, g/mol, kJ/mol, time unit 100 fs.
#include "core/engine.hpp"
#include "core/free_orbit.hpp"
#include "core/gather_in_place.hpp"
#include "core/heat_bath.hpp"
#include "core/snapshot.hpp"
#include "core/system.hpp"
#include "dmd/body_clocks.hpp"
#include "dmd/cell_list.hpp"
#include "dmd/collision_rule.hpp"
#include "dmd/engine_start.hpp"
#include "dmd/engine_state.hpp"
#include "dmd/event.hpp"
#include "dmd/neighbour_lists.hpp"
#include "dmd/pair_prediction.hpp"
#include "dmd/prefetch.hpp"
#include "dmd/root_search.hpp"
#include "dmd/schedule.hpp"
#include "dmd/settings.hpp"
#include "dmd/stall_watch.hpp"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

namespace terrace::dmd {

struct EventCounts {
    std::uint64_t up = 0, down = 0, reflect = 0, virtualEvents = 0, cell = 0, relist = 0,
                  sample = 0, thermostat = 0;
    std::uint64_t total() const {
        return up + down + reflect + virtualEvents + cell + relist + sample + thermostat;
    }
};

namespace testing {
struct Probe;
}

template <BodyKind K, PairPotential P> class Engine {
    using Shared = EngineState<K, P>;        // what the parts share, dmd/engine_state.hpp
    using Prediction = PairPrediction<K, P>; // the searches, dmd/pair_prediction.hpp
    using Moving = typename Prediction::Moving;

public:
    using State = typename K::State;

    /// An engine of the bodies `initial` under `settings`; `seed` (the scene's) starts the
    /// horizon stream.
    Engine(System<K, P> initial, DmdSettings settings, std::uint64_t seed)
        : Engine(initial, std::move(settings), seed, nullptr, nullptr) {}
    /// Resumes from a checkpoint() taken with every clock at one time (right after advanceTo):
    /// `initial` holds the bodies at that time. The pairs keep the terraces they had (never
    /// re-derived from U, which may sit exactly on a level) and the horizon stream goes on where
    /// it stood; calendars, lists and cells are built afresh, as at the start. A run that is
    /// continued from a restart file and one that rebuilds its engine the same way at the same
    /// instant then undergo the same events.
    Engine(System<K, P> initial, DmdSettings settings, std::uint64_t seed,
           const nlohmann::json& checkpoint)
        : Engine(initial, std::move(settings), seed, &checkpoint, nullptr) {}
    /// The same, and the checkpoint's pair terraces are freed as soon as they are read, before
    /// the pairs are predicted: kept, they would sit beside the new engine at its largest (the
    /// peak of a run's rebuilds; ~100 B a body for LJ spheres). `checkpoint` is then spent.
    Engine(System<K, P> initial, DmdSettings settings, std::uint64_t seed,
           nlohmann::json&& checkpoint)
        : Engine(initial, std::move(settings), seed, &checkpoint, &checkpoint) {}

private:
    Engine(System<K, P>& initial, DmdSettings settings, std::uint64_t seed,
           const nlohmann::json* resume, nlohmann::json* spent)
        : s_(std::move(initial), std::move(settings)),
          predict_(s_.settings, s_.sys.potential, seed, s_.sys.size()),
          listedBefore_(s_.sys.size(), 0), scanned_(64), seed_(seed), bathState_(seed) {
        checkBodies(s_.sys);
        if (s_.settings.sortBodies) sortBodiesByCell();
        if (resume) resumeClocks(s_, predict_.jitter(), *resume);
        startBath(resume);
        cacheOrbits(s_);
        s_.schedule.openCalendar(s_.settings.queue, s_.settings.horizon, s_.time);
        for (int i = 0; i < s_.sys.size(); ++i)
            s_.cells.insert(i, s_.sys.bodies[i].r);
        for (int i = 0; i < s_.sys.size(); ++i)
            rebuildList(i);
        if (resume)
            resumeTerraces(s_, *resume);
        else
            assignInitialTerraces(s_, predict_.search().levelTolerance);
        if (spent) *spent = nlohmann::json(); // resume points to it: read no more from here on
        countTerraces();
        visitQueue([&](auto& q) { predict_.predictAll(s_, q); });
        s_.schedule.retuneBins(s_.time);
        anchorOrder();
    }

public:
    // ---- the Engine contract (core/engine.hpp) ----

    /// Process every event before t, then bring all clocks to t. The bodies are numbered afresh
    /// first where their cell order has decayed (renumberBodies).
    void advanceTo(double t) {
        if (!(t >= s_.time)) throw std::invalid_argument("dmd: advanceTo into the past");
        requireEvents();
        if (orderHasDecayed()) renumberBodies();
        visitQueue([&](auto& q) {
            if (s_.settings.bath.kind == HeatBath::Kind::Andersen)
                while (bathState_.clock < t) {
                    runUntil(q, bathState_.clock);
                    andersenCollision(q);
                }
            Event sample;
            sample.time = t;
            sample.kind = EventKind::Sample;
            q.push(sample);
            while (step(q)) {
            }
        });
        synchronise(s_, t);
        if (s_.settings.bath.kind == HeatBath::Kind::Csvr) csvrRescale();
        // A pass over the bodies like the one just made, and only when most spills are idle.
        s_.schedule.compactSpills();
        s_.lists.compactSpills();
        ++counts_.sample;
    }
    double time() const { return s_.time; }
    /// The bodies as they are now, in the scene's order; built body by body, without a copy of
    /// the whole system (a sample of 10⁶ bodies would hold both at once).
    Snapshot snapshot() const {
        const int n = s_.sys.size();
        Snapshot s = emptySnapshot<K>(s_.time, s_.sys.box.length, static_cast<std::size_t>(n));
        for (int b = 0; b < n; ++b)
            appendBody<K>(s, stateNow(s_, s_.engineIndex(b)), s_.sys.body);
        return s;
    }
    /// The bodies `bodies` (the scene's numbers) as they are now, in that order.
    Snapshot snapshot(std::span<const int> bodies) const {
        Snapshot s = emptySnapshot<K>(s_.time, s_.sys.box.length, bodies.size());
        for (const int b : bodies)
            appendBody<K>(s, stateNow(s_, s_.engineIndex(b)), s_.sys.body);
        return s;
    }
    /// Body b's position now (b: the scene's number).
    Vec3 position(int b) const { return positionNow(s_, s_.engineIndex(b)); }
    /// Every body's position now, in the scene's order (the snapshot's other fields empty).
    Snapshot positions() const {
        const int n = s_.sys.size();
        Snapshot s = positionsOnly(s_.time, s_.sys.box.length, static_cast<std::size_t>(n));
        for (int b = 0; b < n; ++b)
            s.position.push_back(position(b));
        return s;
    }
    double kineticEnergy() const { return totalKinetic(s_.sys); } // constant in free flight
    double potentialEnergy() const {
        if (s_.settings.levels.isUniform())
            return static_cast<double>(terraceSum_) * s_.settings.levels.step();
        // Explicit levels: Σ count × V over the terraces, the same sum whatever the order in
        // which the pairs reached them.
        const auto& L = s_.settings.levels;
        const std::size_t slots = terraceSlots();
        double e = 0.0;
        for (std::size_t s = 0; s < terraceCount_.size(); ++s)
            if (terraceCount_[s] != 0)
                e += static_cast<double>(terraceCount_[s]) * classEnergyScale(s / slots) *
                     L.energy(L.lowestTerrace() + int(s % slots));
        return e;
    }
    Vec3 totalMomentum() const { return terrace::totalMomentum(s_.sys); }
    /// ½ m Σ v² (kJ/mol): velocities change only at events, so the stored ones are those of now.
    double translationalKineticEnergy() const { return translationalKinetic(s_.sys); }
    /// Σ r_ij·Δp_i over every collision (transmission or reflection) since the run began, Δp_i
    /// the impulse on i (kJ/mol × time unit). Over an interval Δt the pressure is
    /// P = (2 K_trans + ΔW/Δt)/(3V): the impulse form of the virial (Alder & Wainwright,
    /// J. Chem. Phys. 33, 1439 (1960); Allen & Tildesley, 2nd ed., sec. 3.7).
    static constexpr VirialKind virialKind = VirialKind::Impulse;
    double virial() const { return s_.impulseVirial; }
    /// The continuous model's U and W = Σ r_ij·F_ij at time() (kJ/mol) on the engine's
    /// configuration, un-terraced: the smoothed potential over every pair within its range, or
    /// for a bare one (no cutoff) within r_m, the range terraced. Each pair's e^{−β(U−V)}, V its
    /// terraced energy, goes into *profile when given (core/continuous_sums.hpp). O(N) by a cell
    /// list of its own; for the configurational estimators, not for the dynamics.
    ContinuousSums continuousSums(TerracingProfile* profile = nullptr) const {
        const System<K, P> s = system();
        double range = s_.settings.rm;
        if constexpr (requires { s_.sys.potential.range(); })
            if (std::isfinite(s_.sys.potential.range())) range = s_.sys.potential.range();
        CellList cells(s.box.length, range, s.size());
        for (int i = 0; i < s.size(); ++i)
            cells.insert(i, s.bodies[i].r);
        const TerraceLevels& levels = s_.settings.levels;
        ContinuousSums sums;
        for (int i = 0; i < s.size(); ++i)
            cells.forEachNeighbour(i, [&](int j) {
                if (j <= i) return;
                const Vec3 rij = s.box.minimumImage(s.bodies[i].r - s.bodies[j].r);
                const double r2 = rij.squaredNorm();
                if (r2 >= range * range) return;
                if constexpr (isSteppedModel<P>) {
                    // The model is the table itself; its virial is all impulses (virial()).
                    const double V =
                        stepPairEnergy(s.potential, std::sqrt(r2), orientationOf<P, K>(s.bodies[i]),
                                       orientationOf<P, K>(s.bodies[j]));
                    sums.potential += V;
                    if (profile) profile->add(std::sqrt(r2), 0.0);
                    return;
                }
                const PairForce f = s.potential.evaluate(rij, orientationOf<P, K>(s.bodies[i]),
                                                         orientationOf<P, K>(s.bodies[j]));
                sums.potential += f.U;
                sums.virial += rij.dot(f.F);
                if (profile)
                    profile->add(std::sqrt(r2), f.U - levels.energy(levels.terraceOf(f.U)));
            });
        // A step table has no configurational virial: its forces act only at the steps.
        if constexpr (isSteppedModel<P>) sums.virial = std::numeric_limits<double>::quiet_NaN();
        return sums;
    }
    void rescaleTemperature(double kT) {
        requireEvents();
        synchronise(s_, s_.time);
        rescaleToTemperature(s_.sys, kT);
        for (int i = 0; i < s_.sys.size(); ++i)
            refreshOrbit(s_, i);
        predict_.repredictAll(s_);
    }
    nlohmann::json statistics() const {
        nlohmann::json j;
        j["events"] = {{"total", counts_.total()},
                       {"up", counts_.up},
                       {"down", counts_.down},
                       {"reflect", counts_.reflect},
                       {"virtual", counts_.virtualEvents},
                       {"cell", counts_.cell},
                       {"relist", counts_.relist},
                       {"sample", counts_.sample}};
        if (s_.settings.bath.kind == HeatBath::Kind::Andersen)
            j["events"]["thermostat"] = counts_.thermostat;
        j["dV_kJ_per_mol"] = s_.settings.levels.isUniform() ? nlohmann::json(s_.terraceHeight())
                                                            : nlohmann::json(nullptr);
        j["r_m_angstrom"] = s_.settings.rm;
        if constexpr (requires { s_.sys.potential.range(); })
            j["model"] = std::isfinite(s_.sys.potential.range()) ? "smoothed" : "bare";
        j["queue"] = queueName(s_.settings.queue);
        j["invalidation"] = s_.settings.eager ? "eager" : "lazy";
        j["max_queue_size"] = s_.schedule.maxQueueSize();
        j["cleanups"] = s_.schedule.cleanups();
        j["stale_events"] = staleEvents_;
        j["stale_in_agendas"] = s_.schedule.staleInAgendas();
        j["cells_per_side"] = s_.cells.cellsPerSide();
        const double n = static_cast<double>(s_.sys.bodies.size());
        const auto sched = s_.schedule.memory(); // one pass over the agendas
        j["agenda_events_per_body"] = static_cast<double>(sched.agendaEvents) / n;
        std::size_t listed = 0;
        int longest = 0;
        for (int i = 0; i < s_.sys.size(); ++i) {
            listed += static_cast<std::size_t>(s_.lists.size(i));
            longest = std::max(longest, s_.lists.size(i));
        }
        j["list_partners_per_body"] = static_cast<double>(listed) / n;
        j["list_partners_max"] = longest;
        j["list_capacity"] = s_.lists.capacity();
        j["lists_spilled"] = s_.lists.spilled();
        // What a body costs in memory now, by part (bytes per body).
        for (const auto& [part, bytes] : memoryByPart(sched))
            j["memory_bytes_per_body"][part] = static_cast<double>(bytes) / n;
        j["search_evaluations"] = predict_.evaluations;
        j["searches_screened"] = predict_.screened;
        j["resorts"] = resorts_;
        return j;
    }
    /// What a resumed engine needs beyond the bodies (dmd/engine_start.hpp).
    nlohmann::json checkpoint() const {
        nlohmann::json c = checkpointOf(s_, predict_.jitter());
        if (s_.settings.bath.on()) c["heat_bath"] = bathState_.save();
        return c;
    }
    /// Kinetic energy the heat bath has taken out since the run began (kJ/mol; 0 without one).
    double thermostatEnergy() const { return bathState_.removed; }
    /// All bodies brought to time(): the system as it is now, its bodies in the scene's order.
    System<K, P> system() const {
        System<K, P> s = s_.sys;
        for (int i = 0; i < s.size(); ++i)
            s.bodies[s_.sceneIndex(i)] = stateNow(s_, i);
        return s;
    }
    /// The bodies and the checkpoint, moved out: what the event loop alone needs is freed first
    /// (shed), then the checkpoint takes its room, then the bodies leave without a copy beside
    /// them, so that a restart point adds nothing to the run's peak. The engine is then spent.
    Released<System<K, P>> release() && {
        shed();
        nlohmann::json c = checkpoint();
        return {releaseBodies(s_), std::move(c)};
    }

private:
    // Tests, benchmarks and tools look inside through this one friend (dmd/testing.hpp); what
    // runs use is the Engine contract above.
    friend struct testing::Probe;

    /// Whether pairs are screened by their hold time before a search (on by default; off only to
    /// measure what the screen saves, or to check that it changes no event). Every pair is
    /// predicted afresh.
    void setHoldScreen(bool on) {
        requireEvents();
        predict_.holdScreen = on;
        synchronise(s_, s_.time);
        predict_.repredictAll(s_);
    }
    /// Whether the cell order of the bodies has decayed as the liquid diffused: the RMS
    /// displacement, since they were numbered, of a fixed sample of them (every anchorStride_-th
    /// in the engine's order, so spread over the box) has reached dmd.resort_cells cell widths
    /// (auto: 1 from prefetchFromBodies bodies on, never below).
    /// Neighbours in space are then no longer neighbours in memory; advanceTo then renumbers
    /// them (renumberBodies). Always false when the bodies are not sorted.
    bool orderHasDecayed() const {
        if (orderAnchors_.empty()) return false;
        double sum = 0.0;
        for (std::size_t k = 0; k < orderAnchors_.size(); ++k) {
            const int i = static_cast<int>(k) * anchorStride_;
            sum += s_.sys.box.minimumImage(positionNow(s_, i) - orderAnchors_[k], s_.inverseBox)
                       .squaredNorm();
        }
        return sum >= resortSquared_ * static_cast<double>(orderAnchors_.size());
    }
    /// Frees what only the event loop needs (the calendar, the agendas and the orbits, ~0.4 KB a
    /// body) from an engine about to be dropped at a restart or re-sort point, so that its
    /// checkpoint, then the next engine, take their room instead of adding to the run's peak. The
    /// bodies, clocks, lists and terraces stay: checkpoint(), the reads of the bodies
    /// (system, release) and destruction may follow, and no advanceTo.
    void shed() {
        s_.schedule.shed();
        BodyArray<FreeOrbit<K>>().swap(s_.orbit);
        shed_ = true;
    }
    /// Bytes the engine holds, by part (the heap blocks' own overhead not counted), from the
    /// schedule's (one pass over the agendas).
    std::vector<std::pair<const char*, std::size_t>>
    memoryByPart(const typename Schedule<Shared>::Memory& sched) const {
        return {
            {"states", s_.sys.bodies.capacity() * sizeof(State)},
            {"orbits", s_.orbit.capacity() * sizeof(FreeOrbit<K>)},
            {"books", sched.books},
            {"agendas", sched.agendas},
            {"calendar", sched.calendar},
            {"lists", s_.lists.bytesReserved()}, // and the pairs' terraces
            {"cells", s_.cells.bytesReserved()},
            {"other", (listedBefore_.capacity() + scanned_.capacity()) * sizeof(int) +
                          terraceCount_.capacity() * sizeof(std::int64_t) +
                          (s_.sceneNumber.capacity() + s_.engineNumber.capacity()) * sizeof(int) +
                          orderAnchors_.capacity() * sizeof(Vec3) + predict_.predictionBytes()}};
    }

    template <class F> void visitQueue(F&& f) { s_.schedule.visitQueue(std::forward<F>(f)); }

    /// Numbers the bodies in the Morton (Z-order) order of their cells, those of one cell in the
    /// scene's order: bodies close in space then lie close in every per-body array (states,
    /// orbits, books, agendas, lists), and an event's partners are mostly a few cache lines or
    /// pages apart instead of anywhere in the whole system. Done before anything else is built
    /// from the bodies, so at every start and every rebuild from a checkpoint (restart points, and
    /// the re-sort points that orderHasDecayed calls for): the order follows the liquid as it
    /// diffuses from one rebuild to the next. Outside the engine the bodies keep the scene's
    /// numbering (system, snapshot, checkpoint, terrace, messages).
    void sortBodiesByCell() {
        const int n = s_.sys.size();
        if (s_.cells.single() || n < 2) return;
        std::vector<std::pair<std::uint64_t, int>> key(n);
        for (int b = 0; b < n; ++b)
            key[b] = {s_.cells.mortonCode(s_.sys.bodies[b].r), b};
        std::sort(key.begin(), key.end());
        s_.sceneNumber.resize(n);
        s_.engineNumber.resize(n);
        for (int i = 0; i < n; ++i) {
            s_.sceneNumber[i] = key[i].second;
            s_.engineNumber[key[i].second] = i;
        }
        std::vector<std::pair<std::uint64_t, int>>().swap(key);
        // In place: the engine's other arrays are allocated by now (not yet filled), and a sorted
        // copy beside them (96 B a rod) was a restart point's peak.
        gatherInPlace(s_.sys.bodies, [&](int i) { return s_.sceneNumber[i]; });
    }

    /// Numbers the bodies afresh in the cell order of where they are now, by rebuilding the engine
    /// from its bodies and checkpoint at this instant, exactly as a restart point does: the same
    /// events follow as after a restart point here. The old engine is gone before the new one is
    /// built (the two side by side would double the peak); counters and switches carry over.
    void renumberBodies() {
        const EventCounts counts = counts_;
        const std::uint64_t stale = staleEvents_, resorts = resorts_ + 1;
        const auto evaluations = predict_.evaluations, screened = predict_.screened;
        const bool holdScreen = predict_.holdScreen;
        const std::uint64_t stallLimit = stallWatch_.limit();
        const std::uint64_t seed = seed_;
        DmdSettings settings = s_.settings;
        Released<System<K, P>> kept = std::move(*this).release();
        { const Engine dropped = std::move(*this); }
        *this = Engine(kept.system, std::move(settings), seed, &kept.checkpoint, &kept.checkpoint);
        counts_ = counts;
        staleEvents_ = stale;
        resorts_ = resorts;
        predict_.evaluations = evaluations;
        predict_.screened = screened;
        stallWatch_.setLimit(stallLimit);
        if (holdScreen != predict_.holdScreen) setHoldScreen(holdScreen);
    }

    // ---- the heat bath (core/heat_bath.hpp) ----

    /// The bath's state: from the checkpoint when resuming, else fresh at the start (Andersen's
    /// first event drawn, CSVR's interval starting now).
    void startBath(const nlohmann::json* resume) {
        const HeatBath& bath = s_.settings.bath;
        if (!bath.on()) return;
        if (resume) {
            if (!resume->contains("heat_bath"))
                throw SceneError("restart: the DMD checkpoint holds no heat bath state, and the "
                                 "scene asks for one (run.heat_bath)");
            bathState_.restore(resume->at("heat_bath"));
            return;
        }
        bathState_.clock = s_.time;
        if (bath.kind == HeatBath::Kind::Andersen) bathState_.clock += andersenWait();
    }
    double andersenWait() {
        return exponentialWait(s_.settings.bath.rate * s_.sys.size(), bathState_.rng);
    }

    /// Every event before t processed, the engine's time at t; the clocks stay where they are.
    template <class Q> void runUntil(Q& q, double t) {
        Event stop;
        stop.time = t;
        stop.kind = EventKind::Sample;
        q.push(stop);
        while (step(q)) {
        }
        s_.time = t;
    }

    /// One of Andersen's collisions now: a body drawn at random (by its scene number) gets fresh
    /// Maxwell–Boltzmann velocities, and its events are predicted again as after a collision.
    template <class Q> void andersenCollision(Q& q) {
        std::uniform_int_distribution<int> pick(0, s_.sys.size() - 1);
        const int i = s_.engineIndex(pick(bathState_.rng));
        bringToNow(s_, i);
        bathState_.removed += terrace::andersenCollision<K>(s_.sys.bodies[i], s_.sys.body,
                                                            s_.settings.bath.kT, bathState_.rng);
        refreshOrbit(s_, i);
        ++counts_.thermostat;
        s_.schedule.invalidate(q, i, s_.prefetching);
        predict_.predictBody(s_, i, -1);
        s_.schedule.settle(q, s_.time);
        s_.schedule.afterEvent(q, s_.time);
        bathState_.clock += andersenWait();
    }

    /// CSVR over the time since its last rescale: every clock at s_.time.
    void csvrRescale() {
        const double dt = s_.time - bathState_.clock;
        const double now = kineticEnergy();
        bathState_.clock = s_.time;
        if (!(dt > 0.0) || !(now > 0.0)) return;
        const HeatBath& bath = s_.settings.bath;
        const int f = heatBathDof(bath.kind, totalRotationalDof(s_.sys), s_.sys.size());
        double sign = 1.0;
        const double next =
            csvrKinetic(now, 0.5 * f * bath.kT, f, std::exp(-dt / bath.tau), bathState_.rng, sign);
        const double alpha = sign * std::sqrt(next / now);
        for (int i = 0; i < s_.sys.size(); ++i) {
            s_.sys.bodies[i].v *= alpha;
            K::scaleAngularVelocity(s_.sys.bodies[i], s_.sys.body, alpha);
            refreshOrbit(s_, i);
        }
        predict_.repredictAll(s_);
        bathState_.removed += now - next;
    }

    /// After shed() only the bodies, the checkpoint and destruction are left.
    void requireEvents() const {
        if (shed_) throw std::logic_error("dmd: the engine shed its events (a restart point)");
    }

    /// Where the sample that orderHasDecayed follows stands now, just numbered (every clock is
    /// at s_.time when an engine is built).
    void anchorOrder() {
        const int n = s_.sys.size();
        const double cells = s_.settings.resortCells.value_or(n >= prefetchFromBodies ? 1.0 : 0.0);
        if (!s_.settings.sortBodies || s_.cells.single() || !(cells > 0.0)) return;
        anchorStride_ = std::max(1, (n + orderSampleSize - 1) / orderSampleSize);
        orderAnchors_.clear();
        for (int i = 0; i < n; i += anchorStride_)
            orderAnchors_.push_back(s_.sys.bodies[i].r);
        const double width = s_.sys.box.length / s_.cells.cellsPerSide();
        resortSquared_ = cells * width * cells * width;
    }

    // ---- the event loop: pop → discard if stale → resolve → invalidate → predict ----

    /// Processes the next valid event; false when it was the sample event of advanceTo.
    template <class Q> bool step(Q& q) {
        for (;;) {
            // Only runEvents() can drain the calendar: advanceTo() queues its sample event.
            if (q.empty()) throw std::logic_error("dmd: no event left (nothing moves)");
            const Event e = q.top();
            q.pop();
            if (s_.prefetching && !q.empty()) prefetchNext(q);
            if (e.kind == EventKind::Sample) return false;
            if (!s_.schedule.isCurrentEntry(e)) { // superseded, or its owner has been invalidated
                ++staleEvents_;
                continue;
            }
            s_.schedule.takeFromAgenda(e);
            if (e.j >= 0 && s_.schedule.book(e.j).counter != e.countJ) {
                // the partner has moved on since
                ++staleEvents_;
                s_.schedule.settle(q, s_.time);
                continue;
            }
            stallWatch_.check(s_.time, e.time, e.i, e.j, [&](int k) { return s_.sceneIndex(k); });
            s_.time = e.time;
            switch (e.kind) {
            case EventKind::Collision:
                collide(q, e);
                break;
            case EventKind::Virtual:
                ++counts_.virtualEvents;
                resume(q, e);
                break;
            case EventKind::CellCrossing:
                ++counts_.cell;
                crossCell(e);
                break;
            case EventKind::Relist:
                ++counts_.relist;
                relist(e.i);
                break;
            case EventKind::Sample:
                break;
            }
            s_.schedule.settle(q, s_.time);
            s_.schedule.afterEvent(q, s_.time);
            return true;
        }
    }

    /// Asks the caches for what the next event reads first of its bodies. It is known (the
    /// calendar's top) while this one is resolved, and in a large system its bodies are anywhere
    /// in memory: without this, each of its first reads would wait for memory in turn.
    /// The tree names the next event's bodies at its root, so that their data, its leaf and the
    /// lower levels of the paths its pop and the bodies' new entries walk are asked for at once,
    /// with no read waited on (at N = 10⁶ waiting for the top's leaf alone took ~0.7 µs of an
    /// event's 4–6); another queue's top is read first.
    template <class Q> [[gnu::always_inline]] void prefetchNext(const Q& q) const {
        if constexpr (requires { q.topBodies(); }) {
            const auto [i, partner] = q.topBodies();
            q.prefetchTop();
            prefetchEvent(i, partner);
            if (partner >= 0) q.prefetchPath(static_cast<std::size_t>(partner));
        } else {
            const Event& next = q.top();
            if (next.kind != EventKind::Sample) prefetchEvent(next.i, rootPartner(next));
        }
    }
    /// An event of owner i (none: i < 0) reads i's book, agenda, motion and list record. Of its
    /// partner, as rootPartner tells it (dmd/event.hpp), a collision reads as much, and another
    /// event of a pair only the motion and book that the pair's prediction reads: asking for the
    /// partner's agenda, list record and calendar path too, as all pair events once did, fetched
    /// 7–8 lines and 11 levels of a path that nothing read, some 3 % of the time at 10⁶ rods. The
    /// bodies' plans and cells are read by every event but a pair's virtual one (resume), which
    /// only searches on from where the pair's last search ended.
    [[gnu::always_inline]] void prefetchEvent(int i, int partner) const {
        if (i < 0) return;
        prefetchShared(i);
        if (partner <= -2) {
            predict_.prefetchBody(s_, pairPartnerOfRootCode(partner));
            return;
        }
        prefetchOwn(i);
        if (partner < 0) return;
        prefetchShared(partner);
        prefetchOwn(partner);
    }
    [[gnu::always_inline]] void prefetchShared(int i) const {
        s_.schedule.prefetch(i);
        predict_.prefetchBody(s_, i);
        s_.lists.prefetch(i);
    }
    [[gnu::always_inline]] void prefetchOwn(int i) const {
        predict_.prefetchPlan(i);
        s_.cells.prefetch(i);
    }

    template <class Q> void collide(Q& q, const Event& e) {
        const int i = e.i, j = e.j;
        bringToNow(s_, i);
        bringToNow(s_, j);
        State &bi = s_.sys.bodies[i], &bj = s_.sys.bodies[j];
        const Vec3 rij = s_.sys.box.minimumImage(bi.r - bj.r);
        const PairForce f =
            s_.sys.potential.evaluate(rij, orientationOf<P, K>(bi), orientationOf<P, K>(bj));
        const int n = s_.lists.terrace(i, j);
        const int target = n + (e.side > 0 ? 1 : -1);
        double dE = s_.settings.levels.energy(target) - s_.settings.levels.energy(n);
        if constexpr (scalesPairEnergies<P>)
            dE *=
                pairEnergyScale(s_.sys.potential, orientationOf<P, K>(bi), orientationOf<P, K>(bj));
        const Impulse impulse =
            solveCrossing(impulseCoefficients<K>(f, bi, bj, s_.sys.body), dE, e.side > 0);
        applyImpulse<K>(bi, bj, f, impulse.S, s_.sys.body);
        s_.impulseVirial += impulse.S * rij.dot(f.F); // Δp_i = S F_ij
        refreshOrbit(s_, i);
        refreshOrbit(s_, j);
        switch (impulse.outcome) {
        case Outcome::Up:
            ++counts_.up;
            break;
        case Outcome::Down:
            ++counts_.down;
            break;
        case Outcome::Reflect:
            ++counts_.reflect;
            break;
        }
        if (impulse.outcome != Outcome::Reflect) moveTerrace(i, j, target);
        s_.schedule.invalidate(q, i, s_.prefetching);
        s_.schedule.invalidate(q, j, s_.prefetching);
        // The pair's own search starts from the evaluation above: U and the force are those of
        // now, only the rate changes with the new velocities.
        const PairSample start{0.0, f.U,
                               dUdt(f, bi.v - bj.v, K::angularVelocity(bi, s_.sys.body),
                                    K::angularVelocity(bj, s_.sys.body))};
        predict_.predictBody(s_, i, -1, j, &start);
        predict_.predictBody(s_, j, i, -1);
    }

    template <class Q> void resume(Q& q, const Event& e) {
        if (e.j < 0) { // a body's entry event: some pair of i comes within r_m now
            s_.schedule.invalidate(q, e.i, s_.prefetching);
            predict_.predictBody(s_, e.i, -1);
            return;
        }
        // A pair dropped from the lists since: relist predicts it afresh if it comes back.
        const auto& listed = s_.lists.partners(e.i);
        if (std::find(listed.begin(), listed.end(), e.j) == listed.end()) return;
        // The search starts afresh here (dmd/event.hpp: a virtual event keeps no U).
        const double entry =
            predict_.predictPair(s_, predict_.movingNow(s_, e.i), e.i, e.j, nullptr);
        if (std::isfinite(entry))
            s_.schedule.schedule(e.i, predict_.pairEvent(s_, EventKind::Virtual, e.j, entry));
    }

    /// The cell only serves list rebuilds: nothing about i's pairs changes.
    void crossCell(const Event& e) {
        bringToNow(s_, e.i);
        s_.cells.cross(e.i, e.side / 2, e.side % 2 ? 1 : -1);
        predict_.planCellCrossing(s_, e.i);
        predict_.scheduleBodyEvent(s_, e.i);
    }

    /// i has moved its relist distance: partners may have come within reach. Its motion is
    /// unchanged, so the queued events of the pairs it keeps stand and only partners new to its
    /// list are predicted (one entering r_m beyond the horizon gets a fresh-start virtual event
    /// there). A dropped pair (now farther apart than r_m + skin) keeps its queued events, which
    /// remain true to the motion, but its chain of virtual events ends (resume).
    void relist(int i) {
        // The old partners' records are rewritten at the end (i leaves them, and joins those it
        // keeps): asked for now, they come while the cells are scanned.
        if (s_.prefetching)
            for (const int j : s_.lists.partners(i))
                s_.lists.prefetch(j);
        bringToNow(s_, i);
        if (++listStamp_ == 0) { // wrapped: no stamp of an earlier rebuild may match
            std::fill(listedBefore_.begin(), listedBefore_.end(), 0u);
            listStamp_ = 1;
        }
        for (const int j : s_.lists.partners(i))
            listedBefore_[j] = listStamp_;
        rebuildList(i);
        const Moving mi = predict_.movingNow(s_, i);
        for (const int j : s_.lists.partners(i)) {
            if (listedBefore_[j] == listStamp_) continue;
            const double entry = predict_.predictPair(s_, mi, i, j, nullptr);
            if (std::isfinite(entry))
                s_.schedule.schedule(i, predict_.pairEvent(s_, EventKind::Virtual, j, entry));
        }
        predict_.planRelist(s_, i);
        predict_.scheduleBodyEvent(s_, i);
    }

    /// i's list from the cells: every j within r_m + skin now, listed on both sides.
    void rebuildList(int i) {
        const Vec3 ri = positionNow(s_, i);
        const double reach = s_.settings.rm + s_.lists.skin();
        // First the candidates (~110 in the dense rods, one in eight within reach), then their
        // distances, each body's position and clock asked of the caches `ahead` bodies early:
        // a cell's bodies are a chain through memory, and one body fetched at a time would keep
        // every miss of a large system waiting on the one before.
        std::size_t scanned = 0;
        s_.cells.forEachNeighbourWithin(i, &ri, reach, [&](int j) {
            if (scanned == scanned_.size()) scanned_.resize(2 * scanned);
            scanned_[scanned++] = j;
        });
        constexpr std::size_t ahead = 8;
        for (std::size_t k = 0; s_.prefetching && k < std::min(ahead, scanned); ++k)
            prefetchWhere(scanned_[k]);
        // Every candidate is written and the count advanced by the test, without a branch:
        // whether one is within reach is a coin toss. The order is the scan's.
        std::size_t within = 0;
        for (std::size_t k = 0; k < scanned; ++k) {
            if (s_.prefetching && k + ahead < scanned) prefetchWhere(scanned_[k + ahead]);
            const int j = scanned_[k];
            scanned_[within] = j;
            within +=
                s_.sys.box.minimumImage(ri - positionNow(s_, j), s_.inverseBox).squaredNorm() <=
                reach * reach;
        }
        s_.lists.rebuild(i, std::span<const int>(scanned_.data(), within), ri);
    }

    /// Puts the pair (i, j) on terrace n, keeping the energy's sums.
    void moveTerrace(int i, int j, int n) {
        const int was = s_.lists.terrace(i, j);
        s_.lists.setTerrace(i, j, n);
        terraceSum_ += n - was;
        if (!terraceCount_.empty()) {
            if (was != 0) --terraceCount_[countIndex(i, j, was)];
            if (n != 0) ++terraceCount_[countIndex(i, j, n)];
        }
    }
    /// The energy's sums from every pair's terrace (the start, a resumption): kept since by
    /// moveTerrace, so that a sample does not visit every list.
    void countTerraces() {
        terraceSum_ = 0; // an integer sum: exact however many events
        const auto& L = s_.settings.levels;
        if (!L.isUniform()) terraceCount_.assign(pairClasses * terraceSlots(), 0);
        s_.lists.forEachPairOffZero([&](int i, int j, int n) {
            terraceSum_ += n;
            if (!terraceCount_.empty()) ++terraceCount_[countIndex(i, j, n)];
        });
    }
    // Explicit levels count the pairs per terrace; where the potential scales each pair's
    // terrace energies (a step mixture's ε_ab, core/step_mixture.hpp), per terrace and pair of
    // species, so that the energy is a sum of whole counts times fixed energies whatever the
    // order of the events.
    static constexpr std::size_t pairClasses =
        scalesPairEnergies<P> ? std::size_t(maxSpecies * maxSpecies) : 1;
    std::size_t terraceSlots() const {
        const auto& L = s_.settings.levels;
        return std::size_t(L.highestTerrace() - L.lowestTerrace() + 1);
    }
    /// The count of pair (i, j) (engine indices) on terrace n.
    std::size_t countIndex(int i, int j, int n) const {
        const auto slot = std::size_t(n - s_.settings.levels.lowestTerrace());
        if constexpr (scalesPairEnergies<P>) {
            const int a = orientationOf<P, K>(s_.sys.bodies[i]);
            const int b = orientationOf<P, K>(s_.sys.bodies[j]);
            const auto c = std::size_t(std::min(a, b) * maxSpecies + std::max(a, b));
            return c * terraceSlots() + slot;
        }
        return slot;
    }
    /// The factor of the terrace energies of the pairs counted in class c.
    double classEnergyScale(std::size_t c) const {
        if constexpr (scalesPairEnergies<P>)
            return pairEnergyScale(s_.sys.potential, int(c) / maxSpecies, int(c) % maxSpecies);
        return 1.0;
    }

    /// Asks the caches for what positionNow(s_, j) reads: its position, velocity and clock.
    [[gnu::always_inline]] void prefetchWhere(int j) const {
        prefetchLines(&s_.sys.bodies[j], 2 * sizeof(Vec3)); // r and v lead the state
        s_.schedule.prefetchBook(j);
    }

    Shared s_;                    // bodies, settings, schedule, lists, cells, orbits, time
    Prediction predict_;          // the searches' own: settings, horizon stream, plans, counters
    std::int64_t terraceSum_ = 0; // Σ of the pairs' terrace indices
    std::vector<std::int64_t> terraceCount_;  // pairs per terrace (explicit levels only)
    std::vector<std::uint32_t> listedBefore_; // relist: stamp of the list being rebuilt
    std::vector<int> scanned_; // rebuildList: scanned bodies, those within reach first
    std::uint32_t listStamp_ = 0;
    // orderHasDecayed's sample: where every anchorStride_-th body was when numbered (Å), and the
    // square of the RMS displacement that ends the order (Å²). ≤ 4 096 bodies give the RMS to ~1 %.
    static constexpr int orderSampleSize = 4096;
    std::vector<Vec3> orderAnchors_;
    int anchorStride_ = 1;
    double resortSquared_ = 0.0;
    StallWatch stallWatch_;
    std::uint64_t seed_;        // the scene's: the horizon stream's, kept for renumberBodies
    std::uint64_t resorts_ = 0; // renumberBodies since the start or the checkpoint
    bool shed_ = false;         // shed(): fit only for a checkpoint, the bodies and destruction
    EventCounts counts_;
    std::uint64_t staleEvents_ = 0;
    HeatBathState bathState_; // the bath's stream, energy and clock (unused without a bath)
};

} // namespace terrace::dmd
