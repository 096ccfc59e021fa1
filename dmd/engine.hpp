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
// only); sample events that synchronise all clocks. The schedule is a member; the other three are
// mixins (CRTP bases of the engine: one object, no indirection in the pair loop).
// A clock that stops advancing (a Zeno-like cascade of events at one instant) raises an error
// (dmd/stall_watch.hpp).
// Units: Å, g/mol, kJ/mol, time unit 100 fs.
#include "core/engine.hpp"
#include "core/free_orbit.hpp"
#include "core/gather_in_place.hpp"
#include "core/scene.hpp"
#include "core/snapshot.hpp"
#include "core/system.hpp"
#include "dmd/body_clocks.hpp"
#include "dmd/cell_list.hpp"
#include "dmd/collision_rule.hpp"
#include "dmd/engine_start.hpp"
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
                  sample = 0;
    std::uint64_t total() const {
        return up + down + reflect + virtualEvents + cell + relist + sample;
    }
};

/// From this many bodies on, the engine's data (~1 KB a body) outgrow the caches, and the engine
/// asks for bodies ahead of their use.
inline constexpr int prefetchFromBodies = 16384;

template <BodyKind K, PairPotential P>
class Engine : private PairPrediction<K, P, Engine<K, P>>,
               private BodyClocks<K, P, Engine<K, P>>,
               private EngineStart<K, P, Engine<K, P>> {
    // The engine's mixins: parts of this one object, each in its own header (no virtual call,
    // no pointer between them); each reads and sets the engine's members, as a friend.
    using Prediction = PairPrediction<K, P, Engine>; // the searches, dmd/pair_prediction.hpp
    using Clocks = BodyClocks<K, P, Engine>;         // clocks and orbits, dmd/body_clocks.hpp
    using Start = EngineStart<K, P, Engine>;         // start and restart, dmd/engine_start.hpp
    friend Prediction;
    friend Clocks;
    friend Start;

public:
    using State = typename K::State;

    /// An engine of the bodies `initial` under `settings`; `seed` (the scene's) starts the
    /// horizon stream.
    Engine(System<K, P> initial, DmdSettings settings, std::uint64_t seed)
        : Engine(initial, std::move(settings), seed, nullptr, nullptr) {}
    /// The settings read from the scene's dmd section (readDmdSettings), and its seed.
    Engine(System<K, P> initial, const Scene& scene) : Engine(std::move(initial), scene, nullptr) {}

    /// Resumes from a checkpoint() taken with every clock at one time (right after advanceTo):
    /// `initial` holds the bodies at that time. The pairs keep the terraces they had (never
    /// re-derived from U, which may sit exactly on a level) and the horizon stream goes on where
    /// it stood; calendars, lists and cells are built afresh, as at the start. A run that is
    /// continued from a restart file and one that rebuilds its engine the same way at the same
    /// instant then undergo the same events.
    Engine(System<K, P> initial, const Scene& scene, const nlohmann::json& checkpoint)
        : Engine(std::move(initial), scene, &checkpoint) {}
    /// The same, and the checkpoint's pair terraces are freed as soon as they are read, before
    /// the pairs are predicted: kept, they would sit beside the new engine at its largest (the
    /// peak of a run's rebuilds; ~100 B a body for LJ spheres). `checkpoint` is then spent.
    Engine(System<K, P> initial, const Scene& scene, nlohmann::json&& checkpoint)
        : Engine(std::move(initial), scene, &checkpoint, &checkpoint) {}
    Engine(System<K, P> initial, DmdSettings settings, std::uint64_t seed,
           nlohmann::json&& checkpoint)
        : Engine(initial, std::move(settings), seed, &checkpoint, &checkpoint) {}

private:
    Engine(System<K, P> initial, const Scene& scene, const nlohmann::json* resume,
           nlohmann::json* spent = nullptr)
        : Engine(initial,
                 readDmdSettings(scene.dmd, initial.potential, initial.kT, initial.box.length),
                 scene.seed, resume, spent) {}
    // The settings are read before anything is built: the prediction base, built first, needs them.
    Engine(System<K, P>& initial, DmdSettings settings, std::uint64_t seed,
           const nlohmann::json* resume, nlohmann::json* spent)
        : Prediction(settings, initial.potential, seed, initial.size()), sys_(std::move(initial)),
          settings_(std::move(settings)), lists_(makeLists(settings_.rm, sys_)),
          cells_(sys_.box.length, settings_.rm + lists_.skin(), sys_.size()),
          schedule_(sys_.size(), settings_.eager, settings_.horizon), listedBefore_(sys_.size(), 0),
          scanned_(64), seed_(seed) {
        checkBodies();
        if (settings_.sortBodies) sortBodiesByCell();
        if (resume) resumeClocks(*resume);
        cacheOrbits();
        schedule_.openCalendar(settings_.queue, settings_.horizon, time_);
        for (int i = 0; i < sys_.size(); ++i)
            cells_.insert(i, sys_.bodies[i].r);
        for (int i = 0; i < sys_.size(); ++i)
            rebuildList(i);
        if (resume)
            resumeTerraces(*resume);
        else
            assignInitialTerraces();
        if (spent) *spent = nlohmann::json(); // resume points to it: read no more from here on
        countTerraces();
        visitQueue([&](auto& q) { this->predictAll(q); }); // (this->: g++ 12 needs it here)
        schedule_.retuneBins(time_);
        anchorOrder();
    }

public:
    // ---- the Engine contract (core/engine.hpp) ----

    /// Process every event before t, then bring all clocks to t. The bodies are numbered afresh
    /// first where their cell order has decayed (renumberBodies).
    void advanceTo(double t) {
        if (!(t >= time_)) throw std::invalid_argument("dmd: advanceTo into the past");
        requireEvents();
        if (orderHasDecayed()) renumberBodies();
        visitQueue([&](auto& q) {
            Event sample;
            sample.time = t;
            sample.kind = EventKind::Sample;
            q.push(sample);
            while (step(q)) {
            }
        });
        synchronise(t);
        // A pass over the bodies like the one just made, and only when most spills are idle.
        schedule_.compactSpills();
        lists_.compactSpills();
        ++counts_.sample;
    }
    double time() const { return time_; }
    /// The bodies as they are now, in the scene's order; built body by body, without a copy of
    /// the whole system (a sample of 10⁶ bodies would hold both at once).
    Snapshot snapshot() const {
        const int n = sys_.size();
        Snapshot s = emptySnapshot<K>(time_, sys_.box.length, static_cast<std::size_t>(n));
        for (int b = 0; b < n; ++b)
            appendBody<K>(s, stateNow(engineIndex(b)), sys_.body);
        return s;
    }
    /// The bodies `bodies` (the scene's numbers) as they are now, in that order.
    Snapshot snapshot(std::span<const int> bodies) const {
        Snapshot s = emptySnapshot<K>(time_, sys_.box.length, bodies.size());
        for (const int b : bodies)
            appendBody<K>(s, stateNow(engineIndex(b)), sys_.body);
        return s;
    }
    /// Body b's position now (b: the scene's number).
    Vec3 position(int b) const { return positionNow(engineIndex(b)); }
    /// Every body's position now, in the scene's order (the snapshot's other fields empty).
    Snapshot positions() const {
        const int n = sys_.size();
        Snapshot s = positionsOnly(time_, sys_.box.length, static_cast<std::size_t>(n));
        for (int b = 0; b < n; ++b)
            s.position.push_back(position(b));
        return s;
    }
    double kineticEnergy() const { return totalKinetic(sys_); } // constant in free flight
    double potentialEnergy() const {
        if (settings_.levels.isUniform())
            return static_cast<double>(terraceSum_) * settings_.levels.step();
        // Explicit levels: Σ count × V over the terraces, the same sum whatever the order in
        // which the pairs reached them.
        const auto& L = settings_.levels;
        double e = 0.0;
        for (std::size_t s = 0; s < terraceCount_.size(); ++s)
            if (terraceCount_[s] != 0)
                e += static_cast<double>(terraceCount_[s]) * L.energy(L.lowestTerrace() + int(s));
        return e;
    }
    Vec3 totalMomentum() const { return terrace::totalMomentum(sys_); }
    /// ½ m Σ v² (kJ/mol): velocities change only at events, so the stored ones are those of now.
    double translationalKineticEnergy() const { return translationalKinetic(sys_); }
    /// Σ r_ij·Δp_i over every collision (transmission or reflection) since the run began, Δp_i
    /// the impulse on i (kJ/mol × time unit). Over an interval Δt the pressure is
    /// P = (2 K_trans + ΔW/Δt)/(3V): the impulse form of the virial (Alder & Wainwright,
    /// J. Chem. Phys. 33, 1439 (1960); Allen & Tildesley, 2nd ed., sec. 3.7).
    static constexpr VirialKind virialKind = VirialKind::Impulse;
    double virial() const { return impulseVirial_; }
    /// The continuous U of the model at time() (kJ/mol), un-terraced: the smoothed potential over
    /// every pair within its range, or for a bare one (no cutoff) within r_m, the range terraced.
    /// O(N) by a cell list of its own; for output, not for the dynamics.
    double continuousPotentialEnergy() const {
        const System<K, P> s = system();
        double range = settings_.rm;
        if constexpr (requires { sys_.potential.range(); })
            if (std::isfinite(sys_.potential.range())) range = sys_.potential.range();
        CellList cells(s.box.length, range, s.size());
        for (int i = 0; i < s.size(); ++i)
            cells.insert(i, s.bodies[i].r);
        double u = 0.0;
        for (int i = 0; i < s.size(); ++i)
            cells.forEachNeighbour(i, [&](int j) {
                if (j <= i) return;
                const Vec3 rij = s.box.minimumImage(s.bodies[i].r - s.bodies[j].r);
                if (rij.squaredNorm() < range * range)
                    u += s.potential.energy(rij, orientationOf<P, K>(s.bodies[i]),
                                            orientationOf<P, K>(s.bodies[j]));
            });
        return u;
    }
    void rescaleTemperature(double kT) {
        requireEvents();
        synchronise(time_);
        rescaleToTemperature(sys_, kT);
        for (int i = 0; i < sys_.size(); ++i)
            refreshOrbit(i);
        repredictAll();
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
        j["dV_kJ_per_mol"] = settings_.levels.isUniform() ? nlohmann::json(terraceHeight())
                                                          : nlohmann::json(nullptr);
        j["r_m_angstrom"] = settings_.rm;
        if constexpr (requires { sys_.potential.range(); })
            j["model"] = std::isfinite(sys_.potential.range()) ? "smoothed" : "bare";
        j["queue"] = queueName(settings_.queue);
        j["invalidation"] = settings_.eager ? "eager" : "lazy";
        j["max_queue_size"] = schedule_.maxQueueSize();
        j["cleanups"] = schedule_.cleanups();
        j["stale_events"] = staleEvents_;
        j["stale_in_agendas"] = schedule_.staleInAgendas();
        j["cells_per_side"] = cells_.cellsPerSide();
        const double n = static_cast<double>(sys_.bodies.size());
        const auto sched = schedule_.memory(); // one pass over the agendas
        j["agenda_events_per_body"] = static_cast<double>(sched.agendaEvents) / n;
        std::size_t listed = 0;
        int longest = 0;
        for (int i = 0; i < sys_.size(); ++i) {
            listed += static_cast<std::size_t>(lists_.size(i));
            longest = std::max(longest, lists_.size(i));
        }
        j["list_partners_per_body"] = static_cast<double>(listed) / n;
        j["list_partners_max"] = longest;
        j["list_capacity"] = lists_.capacity();
        j["lists_spilled"] = lists_.spilled();
        // What a body costs in memory now, by part (bytes per body).
        for (const auto& [part, bytes] : memoryByPart(sched))
            j["memory_bytes_per_body"][part] = static_cast<double>(bytes) / n;
        j["search_evaluations"] = evaluations_;
        j["searches_screened"] = screened_;
        j["resorts"] = resorts_;
        return j;
    }
    /// What a resumed engine needs beyond the bodies (dmd/engine_start.hpp).
    using Start::checkpoint;
    /// All bodies brought to time(): the system as it is now, its bodies in the scene's order.
    System<K, P> system() const {
        System<K, P> s = sys_;
        for (int i = 0; i < s.size(); ++i)
            s.bodies[sceneIndex(i)] = stateNow(i);
        return s;
    }
    /// The bodies and the checkpoint, moved out: what the event loop alone needs is freed first
    /// (shed), then the checkpoint takes its room, then the bodies leave without a copy beside
    /// them, so that a restart point adds nothing to the run's peak. The engine is then spent.
    Released<System<K, P>> release() && {
        shed();
        nlohmann::json c = checkpoint();
        return {releaseSystem(std::move(*this)), std::move(c)};
    }

    // ---- for tests and benchmarks ----

    /// Process n events (samples excluded); clocks stay local, time() is the last event's time.
    void runEvents(std::uint64_t n) {
        requireEvents();
        visitQueue([&](auto& q) {
            for (std::uint64_t k = 0; k < n; ++k)
                if (!step(q)) throw std::logic_error("dmd: sample event outside advanceTo");
        });
    }
    /// Whether pairs are screened by their hold time before a search (on by default; off only to
    /// measure what the screen saves, or to check that it changes no event). Every pair is
    /// predicted afresh.
    void setHoldScreen(bool on) {
        requireEvents();
        holdScreen_ = on;
        synchronise(time_);
        repredictAll();
    }
    /// Consecutive events at one instant tolerated before the clock counts as stopped.
    void setStallLimit(std::uint64_t n) { stallWatch_.setLimit(n); }
    /// The terrace index the engine holds for the pair (i, j) (the scene's numbering).
    int terrace(int i, int j) const { return lists_.terrace(engineIndex(i), engineIndex(j)); }
    /// Puts the pair (i, j) on terrace n whatever its U: bookkeeping corrupted on purpose, to test
    /// that the engine reports it.
    void overrideTerrace(int i, int j, int n) { moveTerrace(engineIndex(i), engineIndex(j), n); }
    /// The lists and the pairs' terraces, in the engine's numbering of the bodies (sceneIndex).
    const NeighbourLists& neighbourLists() const { return lists_; }
    int cellsPerSide() const { return cells_.cellsPerSide(); }
    const TerraceLevels& levels() const { return settings_.levels; }
    double interactionRange() const { return settings_.rm; }
    const EventCounts& counts() const { return counts_; }
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
            sum +=
                sys_.box.minimumImage(positionNow(i) - orderAnchors_[k], inverseBox_).squaredNorm();
        }
        return sum >= resortSquared_ * static_cast<double>(orderAnchors_.size());
    }
    /// The number of bodies orderHasDecayed follows (0: none; every anchorStride_-th, ≤ 4 096).
    std::size_t orderSampleBodies() const { return orderAnchors_.size(); }
    /// Frees what only the event loop needs (the calendar, the agendas and the orbits, ~0.4 KB a
    /// body) from an engine about to be dropped at a restart or re-sort point, so that its
    /// checkpoint, then the next engine, take their room instead of adding to the run's peak. The
    /// bodies, clocks, lists and terraces stay: checkpoint(), the reads of the bodies
    /// (system, releaseSystem) and destruction may follow, and no advanceTo.
    void shed() {
        schedule_.shed();
        BodyArray<FreeOrbit<K>>().swap(orbit_);
        shed_ = true;
    }
    /// The RMS displacement at which orderHasDecayed (Å; 0: never).
    double resortDistance() const {
        return orderAnchors_.empty() ? 0.0 : std::sqrt(resortSquared_);
    }
    /// The engine's body i as it is at time(), its stored state moved freely from its clock.
    State stateNow(int i) const {
        State b = sys_.bodies[i];
        freeMove<K>(b, sys_.body, time_ - schedule_.book(i).clock);
        return b;
    }
    /// The engine's number of the scene's body b, and the scene's number of the engine's body i:
    /// inside, the bodies are numbered in the Morton order of their cells (sortBodiesByCell).
    int engineIndex(int b) const { return engineIndex_.empty() ? b : engineIndex_[b]; }
    int sceneIndex(int i) const { return sceneIndex_.empty() ? i : sceneIndex_[i]; }
    /// The partners listed for the scene's body b, in the scene's numbering.
    std::vector<int> listedPartners(int b) const {
        std::vector<int> p;
        for (const int j : lists_.partners(engineIndex(b)))
            p.push_back(sceneIndex(j));
        return p;
    }
    /// Terraced energy recomputed from scratch from U of every pair (all pairs, O(N²)). On a
    /// level this rounds by U alone, so compare with potentialEnergy() only away from levels.
    double terracedEnergyFromScratch() const {
        const System<K, P> s = system();
        double e = 0.0;
        for (int i = 0; i < s.size(); ++i)
            for (int j = i + 1; j < s.size(); ++j) {
                const Vec3 rij = s.box.minimumImage(s.bodies[i].r - s.bodies[j].r);
                if (rij.norm() > settings_.rm) continue;
                const double U = s.potential.energy(rij, orientationOf<P, K>(s.bodies[i]),
                                                    orientationOf<P, K>(s.bodies[j]));
                e += settings_.levels.energy(settings_.levels.terraceOf(U));
            }
        return e;
    }
    std::size_t queueSize() const { return schedule_.queueSize(); }
    /// Bytes the engine holds, by part (the heap blocks' own overhead not counted).
    std::vector<std::pair<const char*, std::size_t>> memoryByPart() const {
        return memoryByPart(schedule_.memory());
    }
    std::vector<std::pair<const char*, std::size_t>>
    memoryByPart(const typename Schedule<Engine>::Memory& sched) const {
        return {{"states", sys_.bodies.capacity() * sizeof(State)},
                {"orbits", orbit_.capacity() * sizeof(FreeOrbit<K>)},
                {"books", sched.books},
                {"agendas", sched.agendas},
                {"calendar", sched.calendar},
                {"lists", lists_.bytesReserved()}, // and the pairs' terraces
                {"cells", cells_.bytesReserved()},
                {"other", (listedBefore_.capacity() + scanned_.capacity()) * sizeof(int) +
                              terraceCount_.capacity() * sizeof(std::int64_t) +
                              (sceneIndex_.capacity() + engineIndex_.capacity()) * sizeof(int) +
                              orderAnchors_.capacity() * sizeof(Vec3) + this->predictionBytes()}};
    }
    std::size_t bytesReserved() const {
        std::size_t b = 0;
        for (const auto& part : memoryByPart())
            b += part.second;
        return b;
    }

private:
    // What the engine takes of its bases (the rest of them is their own).
    using Clocks::orbit_, Clocks::orbitOf, Clocks::cacheOrbits, Clocks::positionNow,
        Clocks::bringToNow, Clocks::refreshOrbit, Clocks::synchronise;
    using Prediction::predictAll, Prediction::repredictAll, Prediction::predictBody,
        Prediction::predictPair, Prediction::movingNow, Prediction::pairEvent, Prediction::schedule,
        Prediction::scheduleBodyEvent, Prediction::planCellCrossing, Prediction::planRelist;
    using Prediction::search_, Prediction::jitter_, Prediction::holdScreen_,
        Prediction::evaluations_, Prediction::screened_;
    using Start::checkBodies, Start::assignInitialTerraces, Start::resumeClocks,
        Start::resumeTerraces;
    using typename Prediction::Moving;

    template <class F> void visitQueue(F&& f) { schedule_.visitQueue(std::forward<F>(f)); }

    double terraceHeight() const { return settings_.levels.smallestStep(); }

    /// Numbers the bodies in the Morton (Z-order) order of their cells, those of one cell in the
    /// scene's order: bodies close in space then lie close in every per-body array (states,
    /// orbits, books, agendas, lists), and an event's partners are mostly a few cache lines or
    /// pages apart instead of anywhere in the whole system. Done before anything else is built
    /// from the bodies, so at every start and every rebuild from a checkpoint (restart points, and
    /// the re-sort points that orderHasDecayed calls for): the order follows the liquid as it
    /// diffuses from one rebuild to the next. Outside the engine the bodies keep the scene's
    /// numbering (system, snapshot, checkpoint, terrace, messages).
    void sortBodiesByCell() {
        const int n = sys_.size();
        if (cells_.single() || n < 2) return;
        std::vector<std::pair<std::uint64_t, int>> key(n);
        for (int b = 0; b < n; ++b)
            key[b] = {cells_.mortonCode(sys_.bodies[b].r), b};
        std::sort(key.begin(), key.end());
        sceneIndex_.resize(n);
        engineIndex_.resize(n);
        for (int i = 0; i < n; ++i) {
            sceneIndex_[i] = key[i].second;
            engineIndex_[key[i].second] = i;
        }
        std::vector<std::pair<std::uint64_t, int>>().swap(key);
        // In place: the engine's other arrays are allocated by now (not yet filled), and a sorted
        // copy beside them (96 B a rod) was a restart point's peak.
        gatherInPlace(sys_.bodies, [&](int i) { return sceneIndex_[i]; });
    }

    /// Numbers the bodies afresh in the cell order of where they are now, by rebuilding the engine
    /// from its bodies and checkpoint at this instant, exactly as a restart point does: the same
    /// events follow as after a restart point here. The old engine is gone before the new one is
    /// built (the two side by side would double the peak); counters and switches carry over.
    void renumberBodies() {
        const EventCounts counts = counts_;
        const std::uint64_t stale = staleEvents_, resorts = resorts_ + 1;
        const auto evaluations = evaluations_, screened = screened_;
        const bool holdScreen = holdScreen_;
        const std::uint64_t stallLimit = stallWatch_.limit();
        const std::uint64_t seed = seed_;
        DmdSettings settings = settings_;
        Released<System<K, P>> kept = std::move(*this).release();
        { const Engine dropped = std::move(*this); }
        *this = Engine(kept.system, std::move(settings), seed, &kept.checkpoint, &kept.checkpoint);
        counts_ = counts;
        staleEvents_ = stale;
        resorts_ = resorts;
        evaluations_ = evaluations;
        screened_ = screened;
        stallWatch_.setLimit(stallLimit);
        if (holdScreen != holdScreen_) setHoldScreen(holdScreen);
    }

    /// After shed() only the bodies, the checkpoint and destruction are left.
    void requireEvents() const {
        if (shed_) throw std::logic_error("dmd: the engine shed its events (a restart point)");
    }

    /// Where the sample that orderHasDecayed follows stands now, just numbered (every clock is
    /// at time_ when an engine is built).
    void anchorOrder() {
        const int n = sys_.size();
        const double cells = settings_.resortCells.value_or(n >= prefetchFromBodies ? 1.0 : 0.0);
        if (!settings_.sortBodies || cells_.single() || !(cells > 0.0)) return;
        anchorStride_ = std::max(1, (n + orderSampleSize - 1) / orderSampleSize);
        orderAnchors_.clear();
        for (int i = 0; i < n; i += anchorStride_)
            orderAnchors_.push_back(sys_.bodies[i].r);
        const double width = sys_.box.length / cells_.cellsPerSide();
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
            if (prefetching_ && !q.empty()) prefetchNext(q);
            if (e.kind == EventKind::Sample) return false;
            if (!schedule_.isCurrentEntry(e)) { // superseded, or its owner has been invalidated
                ++staleEvents_;
                continue;
            }
            schedule_.takeFromAgenda(e);
            if (e.j >= 0 && schedule_.book(e.j).counter != e.countJ) {
                // the partner has moved on since
                ++staleEvents_;
                schedule_.settle(q, time_);
                continue;
            }
            stallWatch_.check(time_, e.time, e.i, e.j, [&](int k) { return sceneIndex(k); });
            time_ = e.time;
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
            schedule_.settle(q, time_);
            schedule_.afterEvent(q, time_);
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
            this->prefetchBody(pairPartnerOfRootCode(partner));
            return;
        }
        prefetchOwn(i);
        if (partner < 0) return;
        prefetchShared(partner);
        prefetchOwn(partner);
    }
    [[gnu::always_inline]] void prefetchShared(int i) const {
        schedule_.prefetch(i);
        this->prefetchBody(i);
        lists_.prefetch(i);
    }
    [[gnu::always_inline]] void prefetchOwn(int i) const {
        this->prefetchPlan(i);
        cells_.prefetch(i);
    }

    template <class Q> void collide(Q& q, const Event& e) {
        const int i = e.i, j = e.j;
        bringToNow(i);
        bringToNow(j);
        State &bi = sys_.bodies[i], &bj = sys_.bodies[j];
        const Vec3 rij = sys_.box.minimumImage(bi.r - bj.r);
        const PairForce f =
            sys_.potential.evaluate(rij, orientationOf<P, K>(bi), orientationOf<P, K>(bj));
        const int n = lists_.terrace(i, j);
        const int target = n + (e.side > 0 ? 1 : -1);
        const double dE = settings_.levels.energy(target) - settings_.levels.energy(n);
        const Impulse impulse = solveImpulse(impulseCoefficients<K>(f, bi, bj, sys_.body), dE);
        applyImpulse<K>(bi, bj, f, impulse.S, sys_.body);
        impulseVirial_ += impulse.S * rij.dot(f.F); // Δp_i = S F_ij
        refreshOrbit(i);
        refreshOrbit(j);
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
        schedule_.invalidate(q, i, prefetching_);
        schedule_.invalidate(q, j, prefetching_);
        // The pair's own search starts from the evaluation above: U and the force are those of
        // now, only the rate changes with the new velocities.
        const PairSample start{0.0, f.U,
                               dUdt(f, bi.v - bj.v, K::angularVelocity(bi, sys_.body),
                                    K::angularVelocity(bj, sys_.body))};
        predictBody(i, -1, j, &start);
        predictBody(j, i, -1);
    }

    template <class Q> void resume(Q& q, const Event& e) {
        if (e.j < 0) { // a body's entry event: some pair of i comes within r_m now
            schedule_.invalidate(q, e.i, prefetching_);
            predictBody(e.i, -1);
            return;
        }
        // A pair dropped from the lists since: relist predicts it afresh if it comes back.
        const auto& listed = lists_.partners(e.i);
        if (std::find(listed.begin(), listed.end(), e.j) == listed.end()) return;
        // The search starts afresh here (dmd/event.hpp: a virtual event keeps no U).
        const double entry = predictPair(movingNow(e.i), e.i, e.j, nullptr);
        if (std::isfinite(entry)) schedule(e.i, pairEvent(EventKind::Virtual, e.j, entry));
    }

    /// The cell only serves list rebuilds: nothing about i's pairs changes.
    void crossCell(const Event& e) {
        bringToNow(e.i);
        cells_.cross(e.i, e.side / 2, e.side % 2 ? 1 : -1);
        planCellCrossing(e.i);
        scheduleBodyEvent(e.i);
    }

    /// i has moved its relist distance: partners may have come within reach. Its motion is
    /// unchanged, so the queued events of the pairs it keeps stand and only partners new to its
    /// list are predicted (one entering r_m beyond the horizon gets a fresh-start virtual event
    /// there). A dropped pair (now farther apart than r_m + skin) keeps its queued events, which
    /// remain true to the motion, but its chain of virtual events ends (resume).
    void relist(int i) {
        // The old partners' records are rewritten at the end (i leaves them, and joins those it
        // keeps): asked for now, they come while the cells are scanned.
        if (prefetching_)
            for (const int j : lists_.partners(i))
                lists_.prefetch(j);
        bringToNow(i);
        if (++listStamp_ == 0) { // wrapped: no stamp of an earlier rebuild may match
            std::fill(listedBefore_.begin(), listedBefore_.end(), 0u);
            listStamp_ = 1;
        }
        for (const int j : lists_.partners(i))
            listedBefore_[j] = listStamp_;
        rebuildList(i);
        const Moving mi = movingNow(i);
        for (const int j : lists_.partners(i)) {
            if (listedBefore_[j] == listStamp_) continue;
            const double entry = predictPair(mi, i, j, nullptr);
            if (std::isfinite(entry)) schedule(i, pairEvent(EventKind::Virtual, j, entry));
        }
        planRelist(i);
        scheduleBodyEvent(i);
    }

    /// i's list from the cells: every j within r_m + skin now, listed on both sides.
    void rebuildList(int i) {
        const Vec3 ri = positionNow(i);
        const double reach = settings_.rm + lists_.skin();
        // First the candidates (~110 in the dense rods, one in eight within reach), then their
        // distances, each body's position and clock asked of the caches `ahead` bodies early:
        // a cell's bodies are a chain through memory, and one body fetched at a time would keep
        // every miss of a large system waiting on the one before.
        std::size_t scanned = 0;
        cells_.forEachNeighbourWithin(i, &ri, reach, [&](int j) {
            if (scanned == scanned_.size()) scanned_.resize(2 * scanned);
            scanned_[scanned++] = j;
        });
        constexpr std::size_t ahead = 8;
        for (std::size_t k = 0; prefetching_ && k < std::min(ahead, scanned); ++k)
            prefetchWhere(scanned_[k]);
        // Every candidate is written and the count advanced by the test, without a branch:
        // whether one is within reach is a coin toss. The order is the scan's.
        std::size_t within = 0;
        for (std::size_t k = 0; k < scanned; ++k) {
            if (prefetching_ && k + ahead < scanned) prefetchWhere(scanned_[k + ahead]);
            const int j = scanned_[k];
            scanned_[within] = j;
            within += sys_.box.minimumImage(ri - positionNow(j), inverseBox_).squaredNorm() <=
                      reach * reach;
        }
        lists_.rebuild(i, std::span<const int>(scanned_.data(), within), ri);
    }

    /// Puts the pair (i, j) on terrace n, keeping the energy's sums.
    void moveTerrace(int i, int j, int n) {
        const int was = lists_.terrace(i, j);
        lists_.setTerrace(i, j, n);
        terraceSum_ += n - was;
        if (!terraceCount_.empty()) {
            const int lowest = settings_.levels.lowestTerrace();
            if (was != 0) --terraceCount_[was - lowest];
            if (n != 0) ++terraceCount_[n - lowest];
        }
    }
    /// The energy's sums from every pair's terrace (the start, a resumption): kept since by
    /// moveTerrace, so that a sample does not visit every list.
    void countTerraces() {
        terraceSum_ = 0; // an integer sum: exact however many events
        const auto& L = settings_.levels;
        if (!L.isUniform()) terraceCount_.assign(L.highestTerrace() - L.lowestTerrace() + 1, 0);
        lists_.forEachPairOffZero([&](int, int, int n) {
            terraceSum_ += n;
            if (!terraceCount_.empty()) ++terraceCount_[n - L.lowestTerrace()];
        });
    }

    /// Asks the caches for what positionNow(j) reads: its position, velocity and clock.
    [[gnu::always_inline]] void prefetchWhere(int j) const {
        prefetchLines(&sys_.bodies[j], 2 * sizeof(Vec3)); // r and v lead the state
        schedule_.prefetchBook(j);
    }

    static NeighbourLists makeLists(double rm, const System<K, P>& sys) {
        const double density = sys.size() / sys.box.volume();
        const double skin = listSkin(rm, density, sys.box.length);
        return NeighbourLists(sys.size(), skin, listCapacity(rm + skin, density, sys.size()));
    }

    System<K, P> sys_;
    DmdSettings settings_;
    NeighbourLists
        lists_; // and the pairs' terraces; before cells_: the cell width follows the skin
    CellList cells_;
    Schedule<Engine> schedule_;   // each body's book, agenda and calendar entry (dmd/schedule.hpp)
    std::int64_t terraceSum_ = 0; // Σ of the pairs' terrace indices
    std::vector<std::int64_t> terraceCount_;  // pairs per terrace (explicit levels only)
    std::vector<std::uint32_t> listedBefore_; // relist: stamp of the list being rebuilt
    std::vector<int> scanned_; // rebuildList: scanned bodies, those within reach first
    std::uint32_t listStamp_ = 0;
    // Whether the engine asks the caches for bodies ahead of their use: only where its data
    // outgrow them (at N = 512, where everything is cached, the prefetches cost ~2 %).
    bool prefetching_ = sys_.size() >= prefetchFromBodies;
    // The scene's number of each body and the engine's number of each scene body (empty: the
    // same numbering, sortBodiesByCell not applied).
    std::vector<int> sceneIndex_, engineIndex_;
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
    double time_ = 0.0;
    double impulseVirial_ = 0.0; // Σ r_ij·Δp_i over collisions, kJ/mol × time unit
    double inverseBox_ = 1.0 / sys_.box.length; // 1/L (Å⁻¹) for minimum images; NVE: L is fixed
    EventCounts counts_;
    std::uint64_t staleEvents_ = 0;
};

} // namespace terrace::dmd
