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
//   bookkeeping: local clocks (a body is brought to the current time only when it takes part in
//   an event); per-body agendas of pending events with one calendar entry per body, its earliest
//   event (a collision makes some 20 predicted events stale, which then mostly never reach the
//   calendar); per-body event counters captured in each pair event (lazy invalidation; `eager`
//   erases the calendar entries of an invalidated body and those about it through stored
//   handles instead); a cell list with crossing events from which per-body candidate lists with
//   a skin are rebuilt by relist events (dmd/neighbour_lists.hpp; a body's pairs are screened
//   from its list only; of a body's own events — cell crossing, relist, entry — only the
//   earliest is planned in its agenda); a free orbit per body cached at its clock
//   (core/free_orbit.hpp) for the searches; a screen in front of every search: a pair sure to
//   stay on its terrace past the horizon, by bounds on its free motion (dmd/terrace_hold.hpp),
//   gets a sample-less virtual event at the end of that hold instead; virtual events at a
//   jittered horizon (dmd/horizon_jitter.hpp) that resume a truncated search from its stored end
//   point; sample events that synchronise all clocks; a cleanup of stale entries when the
//   calendar grows beyond a multiple of its size after the previous cleanup; bins of the bounded
//   queue tuned from the measured push rate (dmd/bin_tuning.hpp).
// A clock that stops advancing (a Zeno-like cascade of events at one instant) raises an error
// (dmd/stall_watch.hpp).
// Units: Å, g/mol, kJ/mol, time unit 100 fs.
#include "core/branch_free.hpp"
#include "core/engine.hpp"
#include "core/free_orbit.hpp"
#include "core/overlap.hpp"
#include "core/scene.hpp"
#include "core/snapshot.hpp"
#include "core/system.hpp"
#include "dmd/bin_tuning.hpp"
#include "dmd/binary_heap_queue.hpp"
#include "dmd/bounded_priority_queue.hpp"
#include "dmd/cell_list.hpp"
#include "dmd/collision_rule.hpp"
#include "dmd/event.hpp"
#include "dmd/horizon_jitter.hpp"
#include "dmd/neighbour_lists.hpp"
#include "dmd/pair_terraces.hpp"
#include "dmd/root_search.hpp"
#include "dmd/settings.hpp"
#include "dmd/shell_screening.hpp"
#include "dmd/stall_watch.hpp"
#include "dmd/terrace_hold.hpp"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <type_traits>
#include <variant>
#include <vector>

namespace terrace::dmd {

/// Relative jitter of the virtual-event horizon, so that virtual events do not coincide (paper).
inline constexpr double horizonJitter = 0.1;
/// The search's nudge δt as a fraction of its largest step.
inline constexpr double nudgeFraction = 1.0 / 32.0;
/// A search step never moves the pair farther than these, so that its cubic interpolants follow
/// U however hot the system: the relative displacement of the centres, as a fraction of r_m, and
/// the sum of the two bodies' turns (rad). On the paper's rods at T* = 1.4 they hardly bind below
/// the 4 fs step (a thermal pair shifts ~0.05 Å and turns ~0.2 rad in 4 fs; the evaluations per
/// collision stay within 0.2 %); at T* = 50 they cut it two- to three-fold, where a 4 fs cubic
/// missed whole excursions over a level on the repulsive wall (Conservation.HotPairsOnTheWall...).
inline constexpr double stepShiftFraction = 0.03;
inline constexpr double stepTurn = 0.5;
/// A pair screened by its hold time (dmd/terrace_hold.hpp) is looked at again after at most this
/// many horizons: by then one of its bodies has usually collided (every ~5 fs in the dense liquid).
inline constexpr double maxHoldHorizons = 8.0;
/// Extrema of the interpolant within this fraction of a terrace height of a level are examined.
inline constexpr double grazeFraction = 0.25;
/// Distance from a level, as a fraction of the terrace height, below which U counts as on it:
/// far above the round-off of U (~1e-15 kJ/mol), far below any physical energy.
inline constexpr double levelTolerance = 1e-10;
/// A pair found farther than this fraction of the terrace height beyond a level of its terrace
/// has missed an event (checkOnTerrace).
inline constexpr double missedEventMargin = 1e-6;
/// The queue is cleaned of stale events when it exceeds this multiple of its size after the last
/// cleanup (and at least cleanupMinimumPerBody entries per body).
inline constexpr double cleanupGrowth = 3.0;
inline constexpr double cleanupMinimumPerBody = 16.0;
/// A body's list of the owners of calendar entries about it is pruned from this size on.
inline constexpr std::size_t aboutPruneSize = 32;
/// A restart file's pair off terrace 0 may sit this fraction beyond r_m (round-off of r at the
/// instant it reached r_m); farther out, the file does not belong to the bodies.
inline constexpr double resumeRangeTolerance = 1e-9;
/// A list is rebuilt a hair before the body has moved its relist distance (skin/3), so that
/// round-off in the rebuild time can never let an unlisted pair inside r_m.
inline constexpr double relistMargin = 1e-6;

struct EventCounts {
    std::uint64_t up = 0, down = 0, reflect = 0, virtualEvents = 0, cell = 0, relist = 0,
                  sample = 0;
    std::uint64_t total() const {
        return up + down + reflect + virtualEvents + cell + relist + sample;
    }
};

template <BodyKind K, PairPotential P> class Engine {
public:
    using State = typename K::State;

    Engine(System<K, P> initial, const Scene& scene) : Engine(std::move(initial), scene, nullptr) {}

    /// Resumes from a checkpoint() taken with every clock at one time (right after advanceTo):
    /// `initial` holds the bodies at that time. The pairs keep the terraces they had (never
    /// re-derived from U, which may sit exactly on a level) and the horizon stream goes on where
    /// it stood; calendars, lists and cells are built afresh, as at the start. A run that is
    /// continued from a restart file and one that rebuilds its engine the same way at the same
    /// instant then undergo the same events.
    Engine(System<K, P> initial, const Scene& scene, const nlohmann::json& checkpoint)
        : Engine(std::move(initial), scene, &checkpoint) {}

    /// What a resumed engine needs beyond the bodies: the time, every pair off terrace 0, and the
    /// horizon stream's position. Clocks must all be at time() (call right after advanceTo).
    nlohmann::json checkpoint() const {
        for (int i = 0; i < sys_.size(); ++i)
            if (book_[i].clock != time_)
                throw std::logic_error("dmd: checkpoint with clocks not at one time");
        nlohmann::json pairs = nlohmann::json::array();
        terraces_.forEachPair([&](int i, int j, int n) {
            if (n != 0) pairs.push_back({i, j, n});
        });
        const auto stream = jitter_.position();
        return {{"time", time_},
                {"terraces", std::move(pairs)},
                {"horizon_stream", {{"state", stream.state}, {"ready", stream.ready}}}};
    }

private:
    Engine(System<K, P> initial, const Scene& scene, const nlohmann::json* resume)
        : sys_(std::move(initial)),
          settings_(readDmdSettings(scene.dmd, sys_.potential, sys_.kT, sys_.box.length)),
          lists_(sys_.size(),
                 listSkin(settings_.rm, sys_.size() / sys_.box.volume(), sys_.box.length)),
          cells_(sys_.box.length, settings_.rm + lists_.skin(), sys_.size()),
          terraces_(sys_.size()), book_(sys_.size()), listedBefore_(sys_.size(), 0),
          scanned_(sys_.size()), plans_(sys_.size()), agenda_(sys_.size()),
          entry_(settings_.eager ? sys_.size() : 0), about_(sys_.size()),
          jitter_(settings_.horizon, horizonJitter, scene.seed), tuning_(settings_.horizon) {
        search_.maxStep = settings_.horizon;
        search_.nudge = nudgeFraction * settings_.horizon;
        search_.grazeWindow = grazeFraction * terraceHeight();
        search_.levelTolerance = levelTolerance * terraceHeight();
        checkBodies();
        if (resume) resumeClocks(*resume);
        orbit_.reserve(sys_.bodies.size());
        for (int i = 0; i < sys_.size(); ++i) {
            orbit_.emplace_back(sys_.bodies[i], sys_.body);
            book_[i].axisRate = axisRateBound(sys_.bodies[i]);
        }
        if (settings_.queue == QueueKind::Heap)
            queue_.template emplace<BinaryHeapQueue<Event>>();
        else
            queue_.template emplace<BoundedPriorityQueue<Event>>(settings_.horizon / 16.0, 1024,
                                                                 time_);
        for (int i = 0; i < sys_.size(); ++i)
            cells_.insert(i, sys_.bodies[i].r);
        for (int i = 0; i < sys_.size(); ++i)
            rebuildList(i);
        if (resume)
            resumeTerraces(*resume);
        else
            assignInitialTerraces();
        visitQueue([&](auto& q) { predictAll(q); });
        if (auto* bpq = std::get_if<BoundedPriorityQueue<Event>>(&queue_))
            tuning_.retune(*bpq, time_);
    }

public:
    // ---- the Engine contract (core/engine.hpp) ----

    /// Process every event before t, then bring all clocks to t.
    void advanceTo(double t) {
        if (!(t >= time_)) throw std::invalid_argument("dmd: advanceTo into the past");
        visitQueue([&](auto& q) {
            Event sample;
            sample.time = t;
            sample.kind = EventKind::Sample;
            q.push(sample);
            while (step(q)) {
            }
        });
        synchronise(t);
        ++counts_.sample;
    }
    double time() const { return time_; }
    Snapshot snapshot() const { return makeSnapshot(synchronisedCopy(), time_); }
    double kineticEnergy() const { return totalKinetic(sys_); } // constant in free flight
    double potentialEnergy() const {
        if (settings_.levels.isUniform()) {
            std::int64_t sum = 0; // an integer sum: exact however many events
            terraces_.forEachPair([&](int, int, int n) { sum += n; });
            return static_cast<double>(sum) * settings_.levels.step();
        }
        double e = 0.0;
        terraces_.forEachPair([&](int, int, int n) { e += settings_.levels.energy(n); });
        return e;
    }
    Vec3 totalMomentum() const { return terrace::totalMomentum(sys_); }
    void rescaleTemperature(double kT) {
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
        j["queue"] = settings_.queue == QueueKind::Heap ? "heap" : "bpq";
        j["invalidation"] = settings_.eager ? "eager" : "lazy";
        j["max_queue_size"] = maxQueueSize_;
        j["cleanups"] = cleanups_;
        j["stale_events"] = staleEvents_;
        j["stale_in_agendas"] = staleInAgendas_;
        j["cells_per_side"] = cells_.cellsPerSide();
        j["search_evaluations"] = evaluations_;
        j["searches_screened"] = screened_;
        return j;
    }

    // ---- for tests and benchmarks ----

    /// Process n events (samples excluded); clocks stay local, time() is the last event's time.
    void runEvents(std::uint64_t n) {
        visitQueue([&](auto& q) {
            for (std::uint64_t k = 0; k < n; ++k)
                if (!step(q)) throw std::logic_error("dmd: sample event outside advanceTo");
        });
    }
    /// Whether pairs are screened by their hold time before a search (on by default; off only to
    /// measure what the screen saves, or to check that it changes no event). Every pair is
    /// predicted afresh.
    void setHoldScreen(bool on) {
        holdScreen_ = on;
        synchronise(time_);
        repredictAll();
    }
    /// Consecutive events at one instant tolerated before the clock counts as stopped.
    void setStallLimit(std::uint64_t n) { stallWatch_.setLimit(n); }
    /// The terrace index the engine holds for the pair (i, j).
    int terrace(int i, int j) const { return terraces_.get(i, j); }
    /// Puts the pair (i, j) on terrace n whatever its U: bookkeeping corrupted on purpose, to test
    /// that the engine reports it.
    void overrideTerrace(int i, int j, int n) { terraces_.set(i, j, n); }
    const PairTerraces& pairTerraces() const { return terraces_; }
    const NeighbourLists& neighbourLists() const { return lists_; }
    int cellsPerSide() const { return cells_.cellsPerSide(); }
    const TerraceLevels& levels() const { return settings_.levels; }
    double interactionRange() const { return settings_.rm; }
    const EventCounts& counts() const { return counts_; }
    /// All bodies brought to time(): the system as it is now.
    System<K, P> synchronisedCopy() const {
        System<K, P> s = sys_;
        for (int i = 0; i < s.size(); ++i)
            freeMove<K>(s.bodies[i], s.body, time_ - book_[i].clock);
        return s;
    }
    /// Terraced energy recomputed from scratch from U of every pair (all pairs, O(N²)). On a
    /// level this rounds by U alone, so compare with potentialEnergy() only away from levels.
    double terracedEnergyFromScratch() const {
        const System<K, P> s = synchronisedCopy();
        double e = 0.0;
        for (int i = 0; i < s.size(); ++i)
            for (int j = i + 1; j < s.size(); ++j) {
                const Vec3 rij = s.box.minimumImage(s.bodies[i].r - s.bodies[j].r);
                if (rij.norm() > settings_.rm) continue;
                const double U =
                    s.potential.energy(rij, K::axis(s.bodies[i]), K::axis(s.bodies[j]));
                e += settings_.levels.energy(settings_.levels.terraceOf(U));
            }
        return e;
    }
    std::size_t queueSize() const {
        return std::visit([](const auto& q) { return q.size(); }, queue_);
    }
    std::size_t bytesReserved() const {
        std::size_t b = std::visit([](const auto& q) { return q.bytesReserved(); }, queue_);
        b += sys_.bodies.capacity() * sizeof(State) + cells_.bytesReserved() +
             terraces_.bytesReserved() + book_.capacity() * sizeof(BodyBook) +
             lists_.bytesReserved() + listedBefore_.capacity() * sizeof(std::uint64_t) +
             scanned_.capacity() * sizeof(int) + plans_.capacity() * sizeof(BodyPlan) +
             orbit_.capacity() * sizeof(FreeOrbit<K>) + bands_.bytesReserved();
        b += agenda_.capacity() * sizeof(agenda_[0]) + entry_.capacity() * sizeof(QueueHandle) +
             about_.capacity() * sizeof(about_[0]);
        for (const auto& a : agenda_)
            b += a.capacity() * sizeof(Event);
        for (const auto& h : about_)
            b += h.capacity() * sizeof(int);
        return b;
    }

private:
    /// A body brought to now without touching its stored state: the search's view of it, with
    /// its orbit re-based to now so that the search's samples turn it by small angles only.
    struct Moving {
        Vec3 r, v;
        FreeOrbit<K> orbit;                  // from now on
        typename FreeOrbit<K>::Attitude now; // orbit.at(0)
    };
    using Queue = std::variant<BinaryHeapQueue<Event>, BoundedPriorityQueue<Event>>;

    template <class F> void visitQueue(F&& f) { std::visit(std::forward<F>(f), queue_); }

    double terraceHeight() const { return settings_.levels.smallestStep(); }

    // ---- setup ----

    void checkBodies() const {
        for (int i = 0; i < sys_.size(); ++i) {
            const State& b = sys_.bodies[i];
            if (!b.r.allFinite() || !b.v.allFinite() || !K::axis(b).allFinite() ||
                !K::angularVelocity(b, sys_.body).allFinite())
                throw SceneError("state: body " + std::to_string(i) + " has a non-finite value");
        }
        if (!(sys_.body.mass > 0.0)) throw SceneError("body.mass: must be > 0");
    }

    /// Terrace of every pair from U at the start; a pair on a level (within the search's level
    /// tolerance) goes to the terrace it is heading into, so that the start holds no zero-time
    /// event.
    void assignInitialTerraces() {
        const double uMin = sys_.potential.minimumEnergy();
        for (int i = 0; i < sys_.size(); ++i)
            cells_.forEachNeighbour(i, [&](int j) {
                if (j < i) return;
                const State &bi = sys_.bodies[i], &bj = sys_.bodies[j];
                const Vec3 rij = sys_.box.minimumImage(bi.r - bj.r);
                if (rij.norm() > settings_.rm) return;
                const PairForce f = sys_.potential.evaluate(rij, K::axis(bi), K::axis(bj));
                if (overlapsAtStart(f.U, uMin)) throwOverlap(i, j, f.U);
                const double rate = dUdt(f, bi.v - bj.v, K::angularVelocity(bi, sys_.body),
                                         K::angularVelocity(bj, sys_.body));
                terraces_.set(i, j, settings_.levels.terraceOf(f.U, rate, search_.levelTolerance));
            });
    }

    void resumeClocks(const nlohmann::json& c) {
        time_ = c.at("time").get<double>();
        if (!std::isfinite(time_) || time_ < 0.0)
            throw SceneError("restart: the DMD time is not a finite time >= 0");
        for (auto& b : book_)
            b.clock = time_;
        const auto& stream = c.at("horizon_stream");
        jitter_.resumeAt(
            {stream.at("state").get<std::uint64_t>(), stream.at("ready").get<double>()});
    }

    /// The terraces of a checkpoint; pairs it does not list are on terrace 0. A pair listed
    /// beyond r_m, or out of range, means the file does not belong to these bodies.
    void resumeTerraces(const nlohmann::json& c) {
        for (const auto& p : c.at("terraces")) {
            const int i = p.at(0).get<int>(), j = p.at(1).get<int>(), n = p.at(2).get<int>();
            if (i < 0 || j < 0 || i >= sys_.size() || j >= sys_.size() || i == j)
                throw SceneError("restart: terrace of a pair of bodies that do not exist");
            // A pair leaves terrace 0 at r_m exactly: a sample there may read r a round-off
            // beyond it.
            const Vec3 rij = sys_.box.minimumImage(sys_.bodies[i].r - sys_.bodies[j].r);
            if (rij.norm() > settings_.rm * (1.0 + resumeRangeTolerance))
                throw SceneError("restart: bodies " + std::to_string(i) + " and " +
                                 std::to_string(j) + " are held on terrace " + std::to_string(n) +
                                 " beyond the interaction range");
            terraces_.set(std::min(i, j), std::max(i, j), n);
        }
    }

    /// Forgets every pending event and predicts all pairs from now (all clocks at now).
    void repredictAll() {
        visitQueue([&](auto& q) {
            q.clear();
            for (int i = 0; i < sys_.size(); ++i) {
                ++book_[i].counter;
                forgetAgenda(i);
            }
            for (auto& h : about_)
                h.clear();
            predictAll(q);
        });
    }

    template <class Q> void predictAll(Q& q) {
        for (int i = 0; i < sys_.size(); ++i) {
            double entry = std::numeric_limits<double>::infinity();
            const Moving mi = movingNow(i);
            for (const int j : lists_.partners(i))
                if (j > i) entry = std::min(entry, predictPair(mi, i, j, nullptr));
            scheduleBodyEvents(i, entry);
        }
        settle(q);
        cleanupThreshold_ = std::max(cleanupMinimumPerBody * sys_.size(),
                                     cleanupGrowth * static_cast<double>(q.size()));
    }

    // ---- the event loop: pop → discard if stale → resolve → invalidate → predict ----

    /// Processes the next valid event; false when it was the sample event of advanceTo.
    template <class Q> bool step(Q& q) {
        for (;;) {
            // Only runEvents() can drain the calendar: advanceTo() queues its sample event.
            if (q.empty()) throw std::logic_error("dmd: no event left (nothing moves)");
            const Event e = q.top();
            q.pop();
            if (e.kind == EventKind::Sample) return false;
            if (!isCurrentEntry(e)) { // superseded, or its owner has been invalidated
                ++staleEvents_;
                continue;
            }
            takeFromAgenda(e);
            if (e.j >= 0 && book_[e.j].counter != e.countJ) { // the partner has moved on since
                ++staleEvents_;
                settle(q);
                continue;
            }
            stallWatch_.check(time_, e.time, e.i, e.j);
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
            settle(q);
            afterEvent(q);
            return true;
        }
    }

    /// Whether a calendar entry is its owner's current one (only the stamp can tell, in either
    /// mode: the partner's counter is checked once the entry is taken).
    bool isCurrentEntry(const Event& e) const { return e.stamp == book_[e.i].entryStamp; }

    template <class Q> void collide(Q& q, const Event& e) {
        const int i = e.i, j = e.j;
        bringToNow(i);
        bringToNow(j);
        State &bi = sys_.bodies[i], &bj = sys_.bodies[j];
        const Vec3 rij = sys_.box.minimumImage(bi.r - bj.r);
        const PairForce f = sys_.potential.evaluate(rij, K::axis(bi), K::axis(bj));
        const int n = terraces_.get(i, j);
        const int target = n + (e.side > 0 ? 1 : -1);
        const double dE = settings_.levels.energy(target) - settings_.levels.energy(n);
        const Impulse impulse = solveImpulse(impulseCoefficients<K>(f, bi, bj, sys_.body), dE);
        applyImpulse<K>(bi, bj, f, impulse.S, sys_.body);
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
        if (impulse.outcome != Outcome::Reflect) terraces_.set(i, j, target);
        invalidate(q, i);
        invalidate(q, j);
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
            invalidate(q, e.i);
            predictBody(e.i, -1);
            return;
        }
        // A pair dropped from the lists since: relist predicts it afresh if it comes back.
        const auto& listed = lists_.partners(e.i);
        if (std::find(listed.begin(), listed.end(), e.j) == listed.end()) return;
        const PairSample start{0.0, e.U, e.dUdt};
        const double entry =
            predictPair(movingNow(e.i), e.i, e.j, std::isnan(e.U) ? nullptr : &start);
        if (std::isfinite(entry)) schedule(pairEvent(EventKind::Virtual, e.i, e.j, entry));
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
        bringToNow(i);
        ++listStamp_;
        for (const int j : lists_.partners(i))
            listedBefore_[j] = listStamp_;
        rebuildList(i);
        const Moving mi = movingNow(i);
        for (const int j : lists_.partners(i)) {
            if (listedBefore_[j] == listStamp_) continue;
            const double entry = predictPair(mi, i, j, nullptr);
            if (std::isfinite(entry)) schedule(pairEvent(EventKind::Virtual, i, j, entry));
        }
        planRelist(i);
        scheduleBodyEvent(i);
    }

    /// i's list from the cells: every j within r_m + skin now, listed on both sides.
    void rebuildList(int i) {
        lists_.detach(i);
        const Vec3 ri = positionNow(i);
        const double reach = settings_.rm + lists_.skin();
        // Every scanned body is written and the count advanced by the test, without a branch:
        // about one in eight is within reach, at random.
        std::size_t within = 0;
        cells_.forEachNeighbourWithin(i, &ri, reach, [&](int j) {
            scanned_[within] = j;
            within += sys_.box.minimumImage(ri - positionNow(j), inverseBox_).squaredNorm() <=
                      reach * reach;
        });
        for (std::size_t k = 0; k < within; ++k)
            lists_.link(i, scanned_[k]);
        lists_.setAnchor(i, ri);
    }

    Vec3 positionNow(int i) const {
        return translated(sys_.bodies[i].r, sys_.bodies[i].v, time_ - book_[i].clock);
    }

    template <class Q> void afterEvent(Q& q) {
        if (!settings_.eager && static_cast<double>(q.size()) > cleanupThreshold_) {
            q.removeIf([this](const Event& e) {
                return e.kind != EventKind::Sample && !isCurrentEntry(e);
            });
            ++cleanups_;
            cleanupThreshold_ = std::max(cleanupMinimumPerBody * sys_.size(),
                                         cleanupGrowth * static_cast<double>(q.size()));
        }
        if constexpr (std::is_same_v<Q, BoundedPriorityQueue<Event>>)
            if (tuning_.due()) tuning_.retune(q, time_);
    }

    // ---- prediction ----

    /// Predicts every pair of i except (i, exclude); (i, partner) has just been resolved.
    /// partnerStart: the sample of (i, partner) now, when the caller has it.
    void predictBody(int i, int exclude, int partner = -1,
                     const PairSample* partnerStart = nullptr) {
        double entry = std::numeric_limits<double>::infinity();
        const Moving mi = movingNow(i);
        const std::vector<int>& partners = lists_.partners(i);
        for (std::size_t k = 0; k < partners.size(); ++k) {
            // The next partner's state is fetched while this one is predicted: the partners are
            // scattered in memory, and each prediction starts by reading its partner.
            if (k + 1 < partners.size()) prefetchBody(partners[k + 1]);
            const int j = partners[k];
            if (j != exclude)
                entry = std::min(entry, j == partner ? predictPair(mi, i, j, partnerStart, true)
                                                     : predictPair(mi, i, j, nullptr));
        }
        scheduleBodyEvents(i, entry);
    }

    /// Asks the caches for what predictPair reads of body j first.
    void prefetchBody(int j) const {
        const char* state = reinterpret_cast<const char*>(&sys_.bodies[j]);
        const char* orbit = reinterpret_cast<const char*>(&orbit_[j]);
        __builtin_prefetch(state);
        __builtin_prefetch(state + sizeof(State) - 1);
        __builtin_prefetch(orbit);
        __builtin_prefetch(orbit + sizeof(FreeOrbit<K>) - 1);
        __builtin_prefetch(&book_[j]);
    }

    /// Body i's own events: its next cell crossing, its next list rebuild and, when some pair of i
    /// enters r_m only beyond the horizon, a virtual event at the earliest such entry (one per
    /// body instead of one per approaching pair; should i have no event before then, it
    /// re-predicts all its pairs). Only the earliest of the three is scheduled: most are overtaken
    /// by a collision of i, and the others are planned again when it is processed.
    void scheduleBodyEvents(int i, double entry) {
        plans_[i].entry = entry;
        planCellCrossing(i);
        planRelist(i);
        scheduleBodyEvent(i);
    }

    /// Queues the earliest of i's planned body events (ties: cell, relist, entry).
    void scheduleBodyEvent(int i) {
        const BodyPlan& p = plans_[i];
        if (p.cell <= p.relist && p.cell <= p.entry) {
            if (!std::isfinite(p.cell)) return;
            Event e = bodyEvent(EventKind::CellCrossing, i, p.cell);
            e.side = p.cellSide;
            schedule(e);
        } else if (p.relist <= p.entry) {
            schedule(bodyEvent(EventKind::Relist, i, p.relist));
        } else {
            schedule(bodyEvent(EventKind::Virtual, i, p.entry));
        }
    }

    /// When i will have moved (1 − relistMargin) of the relist distance from its list's anchor.
    void planRelist(int i) {
        const double radius = lists_.relistDistance() * (1.0 - relistMargin);
        const Vec3 moved = positionNow(i) - lists_.anchor(i);
        // Already out (an event tied with the rebuild came first): rebuild now.
        const double dt = moved.squaredNorm() >= radius * radius
                              ? 0.0
                              : shellWindow(moved, sys_.bodies[i].v, radius).exit;
        plans_[i].relist = time_ + dt;
    }

    void planCellCrossing(int i) {
        const State& b = sys_.bodies[i];
        int axis = 0, dir = 0;
        const double dt =
            cells_.crossingTime(i, b.r + b.v * (time_ - book_[i].clock), b.v, axis, dir);
        plans_[i].cell = time_ + dt;
        plans_[i].cellSide = static_cast<std::int8_t>(2 * axis + (dir > 0 ? 1 : 0));
    }

    /// Next event of the pair (i, j) from now: screening with r_m, then the adaptive search up to
    /// the jittered horizon; a truncated search leaves a virtual event holding its end point.
    /// A pair entering r_m only beyond the horizon is not searched: its entry time (absolute) is
    /// returned for the caller to schedule; +∞ otherwise.
    /// mi is body i brought to now (movingNow(i)), prepared once for all pairs of i.
    double predictPair(const Moving& mi, int i, int j, const PairSample* resumeFrom,
                       bool afterEvent = false) {
        constexpr double none = std::numeric_limits<double>::infinity();
        const State& bj0 = sys_.bodies[j];
        const double dtj = time_ - book_[j].clock;
        const Vec3 r0 = sys_.box.minimumImage(mi.r - translated(bj0.r, bj0.v, dtj), inverseBox_);
        const Vec3 w = mi.v - bj0.v;
        // Only a pair inside r_m (up to round-off) can be bound; skip the lookup for the rest.
        constexpr double boundSlack = 1.0 + 1e-6;
        const bool maybeBound = r0.squaredNorm() <= settings_.rm * settings_.rm * boundSlack;
        const int n = maybeBound ? terraces_.get(i, j) : 0;
        // A bound pair must reach a level before |r_ij| = r_m; in the worst orientation it does
        // so exactly there, so the shell must not cut its search short.
        const ShellWindow win = n != 0 ? ShellWindow{0.0, std::numeric_limits<double>::infinity()}
                                       : shellWindow(r0, w, settings_.rm);
        if (win.empty()) return none;
        const double horizon = jitter_.next();
        if (win.enter > horizon) return time_ + win.enter;
        // Body j's attitude now serves the hold screen; its orbit is built only for a search.
        const auto ajNow = orbit_[j].startOf(dtj);
        const auto sampleWith = [&](double tau, const auto& attitudes) {
            const auto& [ai, aj] = attitudes;
            const EnergyRate e = energyAndRate(sys_.potential, translated(r0, w, tau), w, ai.axis,
                                               ai.w, aj.axis, aj.w);
            return PairSample{tau, e.U, e.dUdt};
        };
        const std::array now{mi.now, ajNow};
        if constexpr (EffectiveDistanceForm<P>)
            // Not for the pair just resolved: it sits on a level, where the screen answers 0 (it
            // could hold only a root found farther from the level than the screen's edge margin;
            // a search is right either way).
            if (holdScreen_ && !afterEvent) {
                // No level within reach for a while: no samples now, a fresh search then.
                const double hold = holdOnTerrace(now, i, j, r0, w, n, horizon, win.exit);
                if (hold == none) return none; // out of r_m before it could change terrace
                if (hold > 0.0) {
                    schedule(pairEvent(EventKind::Virtual, i, j, time_ + hold));
                    ++screened_;
                    return none;
                }
            }
        const FreeOrbit<K> orbitJ = orbit_[j].from(dtj);
        auto eval = [&](double tau) { return sampleWith(tau, attitudesAt(mi.orbit, orbitJ, tau)); };
        PairSample start;
        if (resumeFrom && win.enter == 0.0) {
            start = *resumeFrom;
        } else {
            start = win.enter == 0.0 ? sampleWith(0.0, now) : eval(win.enter);
            ++evaluations_;
            if (!afterEvent) checkOnTerrace(start.U, i, j, n);
        }
        const double tEnd = std::min(win.exit, horizon);
        const SearchResult r =
            findTerraceExit(eval, start, settings_.levels.lower(n), settings_.levels.upper(n), tEnd,
                            pairSearch(w, book_[i].axisRate + book_[j].axisRate), afterEvent);
        evaluations_ += r.evaluations;
        if (r.side != ExitSide::None) {
            Event e = pairEvent(EventKind::Collision, i, j, time_ + r.t);
            e.side = static_cast<std::int8_t>(r.side);
            schedule(e);
        } else if (win.exit > horizon) {
            Event e = pairEvent(EventKind::Virtual, i, j, time_ + r.end.t);
            e.U = r.end.U;
            e.dUdt = r.end.dUdt;
            schedule(e);
        }
        return none;
    }

    /// A pair sampled beyond a level of its own terrace has crossed it unseen: the bookkeeping no
    /// longer describes the system (a defect, never a property of the dynamics). Reported at
    /// once, rather than left to loop on a reflection at one instant until the stall detector
    /// fires. A pair can sit past a level by round-off only (an event due now), far below the
    /// margin.
    void checkOnTerrace(double U, int i, int j, int n) const {
        const double margin = missedEventMargin * terraceHeight();
        if (U >= settings_.levels.lower(n) - margin && U <= settings_.levels.upper(n) + margin)
            return;
        throw std::logic_error("dmd: bodies " + std::to_string(i) + " and " + std::to_string(j) +
                               " have U = " + std::to_string(U) + " kJ/mol at t = " +
                               std::to_string(units::toFs(time_)) + " fs, beyond the levels of " +
                               "their terrace " + std::to_string(n) + ": an event was missed");
    }

    /// How long from now the pair (i, j) on terrace n, at separation r0 and relative velocity w,
    /// with attitudes `now`, is sure to stay on it (dmd/terrace_hold.hpp): +∞ when until it leaves
    /// r_m at windowExit; otherwise the longest of horizon, 2·horizon, … up to maxHoldHorizons
    /// horizons, or 0 when not even through the horizon (then the search must look).
    template <class Attitudes>
    double holdOnTerrace(const Attitudes& now, int i, int j, const Vec3& r0, const Vec3& w, int n,
                         double horizon, double windowExit) {
        const auto& [ai, aj] = now;
        PairMotion m;
        m.speedSquared = w.x() * w.x() + w.y() * w.y() + w.z() * w.z();
        m.r = std::sqrt(r0.x() * r0.x() + r0.y() * r0.y() + r0.z() * r0.z());
        m.rRate = (r0.x() * w.x() + r0.y() * w.y() + r0.z() * w.z()) / m.r;
        if constexpr (P::orientational) {
            const Vec3 &si = ai.axis, &sj = aj.axis;
            m.c = si.x() * sj.x() + si.y() * sj.y() + si.z() * sj.z();
            const Vec3 spin = ai.w - aj.w;
            m.cRate = spin.x() * (si.y() * sj.z() - si.z() * sj.y()) +
                      spin.y() * (si.z() * sj.x() - si.x() * sj.z()) +
                      spin.z() * (si.x() * sj.y() - si.y() * sj.x());
            m.turn = book_[i].axisRate + book_[j].axisRate;
            // |s̈| = |ω|² for a linear rotor (uniform rotation), so |c̈| ≤ Ω²; a top's ω wanders.
            if constexpr (std::is_same_v<K, LinearRotor>) m.turnCurvature = m.turn * m.turn;
        }
        const double x = sys_.potential.effectiveDistance(m.r, m.c);
        const TerraceBands& b = bands_.of(n, sys_.potential, settings_.levels);
        const BandHold hold(x <= b.bottom ? b.wall : b.tail, m, sys_.potential.alignmentLength());
        const double longest = maxHoldHorizons * horizon;
        if (windowExit <= longest && hold.through(windowExit))
            return std::numeric_limits<double>::infinity();
        return holdTime(hold, horizon, longest);
    }

    /// The search settings for a pair with relative velocity w and summed angular speed turn: the
    /// step shortened where the pair would move more than stepShiftFraction r_m or turn more
    /// than stepTurn in one.
    SearchSettings pairSearch(const Vec3& w, double turn) const {
        SearchSettings s = search_;
        const double shift = stepShiftFraction * settings_.rm;
        const double w2 = w.squaredNorm();
        if (w2 * s.maxStep * s.maxStep > shift * shift) s.maxStep = shift / std::sqrt(w2);
        if (turn * s.maxStep > stepTurn) s.maxStep = stepTurn / turn;
        return s;
    }

    /// Body i as the search sees it now, from its orbit cached at its clock: the stored state is
    /// not touched.
    Moving movingNow(int i) const {
        const State& b = sys_.bodies[i];
        const double dt = time_ - book_[i].clock;
        Moving m{translated(b.r, b.v, dt), b.v, orbit_[i].from(dt), {}};
        m.now = m.orbit.at(0.0);
        return m;
    }

    Event bodyEvent(EventKind kind, int i, double t) const {
        Event e;
        e.time = t;
        e.kind = kind;
        e.i = i;
        return e;
    }

    Event pairEvent(EventKind kind, int i, int j, double t) const {
        Event e = bodyEvent(kind, i, t);
        e.j = j;
        e.countJ = book_[j].counter;
        return e;
    }

    // ---- bookkeeping ----

    /// Every event is filed in the agenda of the body it belongs to (e.i: the body whose
    /// prediction found it); the calendar (the queue) holds one entry per body, a copy of the
    /// earliest event of its agenda, put there by settle() once the body's predictions are done.
    /// A collision invalidates some 20 events of its two bodies; with one entry per body they
    /// mostly never reach the calendar, which then pushes and pops a third as many entries.
    [[gnu::flatten]] void schedule(const Event& e) { // (flat: push_back was a call per event)
        auto& agenda = agenda_[e.i];
        if (agenda.size() >= std::numeric_limits<std::uint16_t>::max())
            throw std::logic_error("dmd: a body's agenda overflowed");
        agenda.push_back(e);
        // The earliest is kept as events arrive, so that settling a body just refilled needs no
        // scan; ties keep the first, as the scan does. By a select, not a branch (whether it is
        // earlier is a coin toss); an unknown earliest has time −∞ and stays unknown.
        const bool earlier = e.time < book_[e.i].agendaFirstTime;
        const auto last = static_cast<std::uint16_t>(agenda.size() - 1);
        book_[e.i].agendaFirst = earlier ? last : book_[e.i].agendaFirst;
        book_[e.i].agendaFirstTime = lesser(e.time, book_[e.i].agendaFirstTime);
        if (e.time < book_[e.i].queuedAt) markUnsettled(e.i);
    }

    void markUnsettled(int i) {
        if (book_[i].unsettledRound == settleRound_) return;
        book_[i].unsettledRound = settleRound_;
        unsettled_.push_back(i);
    }

    /// Gives every body marked unsettled the calendar entry of its earliest valid agenda event.
    /// An earliest event whose partner has moved on since is dropped from the agenda and the
    /// search repeats (the others wait until they come first, or until the agenda is emptied);
    /// a drop moves another event, so the entry is then renewed too: it records its event's place.
    template <class Q> void settle(Q& q) {
        for (const int i : unsettled_) {
            auto& agenda = agenda_[i];
            bool moved = false;
            std::size_t best = 0;
            for (;;) {
                if (agenda.empty()) break;
                best = earliestInAgenda(i);
                const Event& a = agenda[best];
                if (a.j < 0 || book_[a.j].counter == a.countJ) break;
                ++staleInAgendas_;
                removeFromAgenda(i, best);
                moved = true;
            }
            if (agenda.empty()) {
                dropEntry(q, i);
                continue;
            }
            if (!moved && agenda[best].time >= book_[i].queuedAt)
                continue; // the queued entry stands
            dropEntry(q, i);
            Event entry = agenda[best];
            entry.stamp = ++book_[i].entryStamp;
            entry.slot = static_cast<std::uint16_t>(best);
            book_[i].queuedAt = entry.time;
            const QueueHandle h = q.push(entry);
            if (settings_.eager) entry_[i] = h;
            book_[i].entryPartner = entry.j;
            if (entry.j >= 0) keepAbout(entry.j, i);
            maxQueueSize_ = std::max<std::uint64_t>(maxQueueSize_, q.size());
            tuning_.pushed(entry.time - time_);
        }
        unsettled_.clear();
        ++settleRound_;
    }

    /// i's calendar entry no longer stands: the stamp makes it stale (lazy), or it is erased
    /// (eager).
    template <class Q> void dropEntry(Q& q, int i) {
        if (!std::isfinite(book_[i].queuedAt)) return;
        ++book_[i].entryStamp;
        book_[i].queuedAt = std::numeric_limits<double>::infinity();
        if (settings_.eager) q.erase(entry_[i]);
    }

    /// The entry just popped leaves its owner's agenda; the owner needs a new one.
    void takeFromAgenda(const Event& e) {
        removeFromAgenda(e.i, e.slot);
        ++book_[e.i].entryStamp;
        book_[e.i].queuedAt = std::numeric_limits<double>::infinity();
        markUnsettled(e.i);
    }

    /// Bodies whose calendar entry is about i (a pair event with partner i) are listed with i, so
    /// that invalidating i renews those entries at once. A body that rarely collides would pile
    /// up owners whose entries have moved on, and the same owner once per entry it renewed (a
    /// chain of virtual events); when its list reaches 32, 64, 128, … entries, it keeps only the
    /// owners whose entry is about i now, each once (amortised O(1) per entry).
    void keepAbout(int i, int owner) {
        auto& list = about_[i];
        if (list.size() >= aboutPruneSize && (list.size() & (list.size() - 1)) == 0) {
            std::erase_if(list, [&](int k) { return !entryIsAbout(k, i); });
            std::sort(list.begin(), list.end());
            list.erase(std::unique(list.begin(), list.end()), list.end());
        }
        list.push_back(owner);
    }
    bool entryIsAbout(int owner, int i) const {
        return std::isfinite(book_[owner].queuedAt) && book_[owner].entryPartner == i;
    }

    /// Index of the earliest event of i's non-empty agenda (the first of equals).
    std::size_t earliestInAgenda(int i) {
        auto& first = book_[i].agendaFirst;
        if (first == unknownFirst) {
            const auto& agenda = agenda_[i];
            std::size_t best = 0;
            for (std::size_t k = 1; k < agenda.size(); ++k)
                if (agenda[k].time < agenda[best].time) best = k;
            first = static_cast<std::uint16_t>(best);
            book_[i].agendaFirstTime = agenda[best].time;
        }
        return first;
    }
    /// Removes one event by moving the last into its place: the earliest must be found again.
    void removeFromAgenda(int i, std::size_t slot) {
        auto& agenda = agenda_[i];
        agenda[slot] = agenda.back();
        agenda.pop_back();
        book_[i].agendaFirst = unknownFirst;
        book_[i].agendaFirstTime = -std::numeric_limits<double>::infinity();
    }

    void forgetAgenda(int i) {
        agenda_[i].clear();
        book_[i].agendaFirst = 0; // the next event scheduled is the earliest
        book_[i].agendaFirstTime = std::numeric_limits<double>::infinity();
        ++book_[i].entryStamp;
        book_[i].queuedAt = std::numeric_limits<double>::infinity();
    }

    /// Body i's velocities changed: its pending events no longer hold. Its agenda is emptied, and
    /// the bodies whose calendar entry is about i get their next one at once: with lazy
    /// invalidation the old entries stay in the calendar, stale, with eager invalidation they are
    /// erased; either way the same entries are pushed in the same order, so both give the same
    /// trajectory. Other events about i that wait in agendas go stale by its counter and are
    /// dropped when they come first.
    template <class Q> void invalidate(Q& q, int i) {
        ++book_[i].counter;
        dropEntry(q, i);
        for (const int k : about_[i])
            if (entryIsAbout(k, i)) {
                dropEntry(q, k);
                markUnsettled(k);
            }
        about_[i].clear();
        forgetAgenda(i);
    }

    void bringToNow(int i) {
        const double dt = time_ - book_[i].clock;
        book_[i].clock = time_;
        if constexpr (std::is_same_v<K, LinearRotor>) {
            // A rotor's ω is constant in free flight: its cached orbit, turned on by dt, gives
            // its new axis and stays its orbit (FreeOrbit::advancedBy).
            State& b = sys_.bodies[i];
            b.r = translated(b.r, b.v, dt);
            orbit_[i] = orbit_[i].advancedBy(dt);
            b.s = orbit_[i].axis();
        } else {
            freeMove<K>(sys_.bodies[i], sys_.body, dt);
            refreshOrbit(i);
        }
    }
    /// The cached orbit is rebuilt after every change of a stored state other than a rotor's free
    /// flight, which bringToNow follows by turning the orbit itself (impulse, rescale, free motion
    /// of other kinds).
    void refreshOrbit(int i) {
        orbit_[i] = FreeOrbit<K>(sys_.bodies[i], sys_.body);
        book_[i].axisRate = axisRateBound(sys_.bodies[i]);
    }

    /// A bound on how fast the body's long axis turns in free flight, |ṡ| = |ω × s| ≤ |ω| (rad per
    /// time unit): |ω| itself for a linear rotor, whose ω is constant; for a top, whose |ω| varies,
    /// the largest |ω| its rotational energy allows, 2T = Σ I_k ω_k² ≥ I_min |ω|².
    double axisRateBound(const State& b) const {
        if constexpr (K::rotationalDof == 0) {
            return 0.0;
        } else if constexpr (std::is_same_v<K, LinearRotor>) {
            return b.w.norm();
        } else {
            return std::sqrt(2.0 * K::rotationalKinetic(b, sys_.body) /
                             sys_.body.inertia.minCoeff());
        }
    }

    void synchronise(double t) {
        time_ = t;
        for (int i = 0; i < sys_.size(); ++i)
            bringToNow(i);
    }

    /// A body's own events, planned (absolute times, +∞: none); only the earliest is scheduled.
    struct BodyPlan {
        double cell = std::numeric_limits<double>::infinity();
        double relist = std::numeric_limits<double>::infinity();
        double entry = std::numeric_limits<double>::infinity(); // virtual: a pair enters r_m
        std::int8_t cellSide = 0;                               // as Event::side
    };

    /// A body's scalars, in one cache line: an event reads most of them for its own body, and
    /// clock, axis rate and counter for each partner; in a large system, where an event's bodies
    /// are far apart in memory, that is one line fetched per body instead of one per array.
    struct alignas(64) BodyBook {
        double clock = 0.0;    // its local clock: the time its stored state is for
        double axisRate = 0.0; // axisRateBound at its clock (rad per time unit)
        // time of its earliest agenda event (+∞: agenda empty, −∞: unknown)
        double agendaFirstTime = std::numeric_limits<double>::infinity();
        // time of its calendar entry (+∞: none)
        double queuedAt = std::numeric_limits<double>::infinity();
        std::uint64_t unsettledRound = 0; // round in which it was last marked unsettled
        std::uint32_t counter = 0;        // bumped whenever its velocities change
        std::uint32_t entryStamp = 0;     // stamp of its current calendar entry
        std::int32_t entryPartner = -1;   // the partner of that entry (−1: a body event)
        std::uint16_t agendaFirst = 0;    // index of its earliest event (unknownFirst: scan)
    };
    static_assert(sizeof(BodyBook) == 64, "a body's scalars fill one cache line");

    System<K, P> sys_;
    DmdSettings settings_;
    NeighbourLists lists_; // before cells_: the cell width follows the skin
    CellList cells_;
    PairTerraces terraces_;
    std::vector<BodyBook> book_;
    std::vector<FreeOrbit<K>> orbit_; // each body's free orbit from its state at its clock
    TerraceBandTable bands_;          // effective-distance bands of the terraces (hold screen)
    std::vector<std::uint64_t> listedBefore_; // relist: stamp of the list being rebuilt
    std::vector<int> scanned_; // rebuildList: scanned bodies, those within reach first
    std::vector<BodyPlan> plans_;
    std::uint64_t listStamp_ = 0;
    std::vector<std::vector<Event>> agenda_; // each body's pending events (e.i = the body)
    static constexpr std::uint16_t unknownFirst = std::numeric_limits<std::uint16_t>::max();
    std::vector<QueueHandle> entry_;      // eager: the handle of each body's calendar entry
    std::vector<std::vector<int>> about_; // owners whose entry is about the body
    std::vector<int> unsettled_;          // bodies whose entry settle() must renew
    std::uint64_t settleRound_ = 1;
    Queue queue_;
    SearchSettings search_;
    HorizonJitter jitter_;
    BinTuning tuning_;
    StallWatch stallWatch_;
    double time_ = 0.0;
    double inverseBox_ = 1.0 / sys_.box.length; // 1/L (Å⁻¹) for minimum images; NVE: L is fixed
    EventCounts counts_;
    std::uint64_t maxQueueSize_ = 0, cleanups_ = 0, staleEvents_ = 0, staleInAgendas_ = 0,
                  evaluations_ = 0, screened_ = 0;
    double cleanupThreshold_ = 0.0;
    bool holdScreen_ = true;
};

} // namespace terrace::dmd
