#pragma once
// Prediction of the DMD engine's events (paper, "Implementation of the event-driven simulation";
// DESIGN.md "DMD engine"): when a pair's continuous U next reaches a level bounding its terrace,
// and when a body next crosses a cell face, needs its list rebuilt, or sees a pair enter r_m.
//
// A pair is predicted from now: screened with r_m (dmd/shell_screening.hpp); screened by its hold
// time (dmd/terrace_hold.hpp) — a pair sure to stay on its terrace past the horizon, by bounds on
// its free motion, gets a sample-less virtual event at the end of that hold instead; otherwise
// searched adaptively (dmd/root_search.hpp) up to a jittered horizon (dmd/horizon_jitter.hpp),
// a truncated search leaving a virtual event that holds its end point. Bodies are seen through
// the free orbits cached at their clocks (dmd/body_clocks.hpp), brought to now without touching
// their stored states. Of a body's own events — cell crossing, relist, entry — only the earliest
// is planned in its agenda. Every event found is filed in the schedule (dmd/schedule.hpp).
//
// Apart from the engine (dmd/engine.hpp), whose event loop calls it after every event. It owns
// what only prediction uses: the search settings, the horizon stream, the bands and ceiling of the
// hold screen, the bodies' plans and the search counters; the bodies, orbits, clocks, lists, cells
// and terraces it reads from the engine's shared state (dmd/engine_state.hpp), handed to every
// call by reference. The engine holds both by value: in the pair loop no pointer is followed and
// no call is virtual. Units: Å, kJ/mol, time unit 100 fs.
#include "core/free_orbit.hpp"
#include "core/system.hpp"
#include "core/units.hpp"
#include "dmd/body_clocks.hpp"
#include "dmd/cell_list.hpp"
#include "dmd/engine_state.hpp"
#include "dmd/event.hpp"
#include "dmd/horizon_jitter.hpp"
#include "dmd/neighbour_lists.hpp"
#include "dmd/prefetch.hpp"
#include "dmd/root_search.hpp"
#include "dmd/schedule.hpp"
#include "dmd/settings.hpp"
#include "dmd/shell_screening.hpp"
#include "dmd/terrace_hold.hpp"
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
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
/// The range hold screen keeps this fraction of a terrace height clear of each level.
inline constexpr double rangeMargin = 1e-9;
/// Extrema of the interpolant within this fraction of a terrace height of a level are examined.
inline constexpr double grazeFraction = 0.25;
/// Distance from a level, as a fraction of the terrace height, below which U counts as on it:
/// far above the round-off of U (~1e-15 kJ/mol), far below any physical energy.
inline constexpr double levelTolerance = 1e-10;
/// A pair found farther than this fraction of the terrace height beyond a level of its terrace
/// has missed an event (checkOnTerrace).
inline constexpr double missedEventMargin = 1e-6;
/// A list is rebuilt a hair before the body has moved its relist distance (skin/3), so that
/// round-off in the rebuild time can never let an unlisted pair inside r_m.
inline constexpr double relistMargin = 1e-6;

/// A body's own events, planned (absolute times, +∞: none); only the earliest is scheduled.
struct BodyPlan {
    double cell = std::numeric_limits<double>::infinity();
    double relist = std::numeric_limits<double>::infinity();
    double entry = std::numeric_limits<double>::infinity(); // virtual: a pair enters r_m
    std::int8_t cellSide = 0;                               // as Event::side
};

template <BodyKind K, PairPotential P> class PairPrediction {
public:
    using State = typename K::State;
    using Shared = EngineState<K, P>;

    /// The search's settings from the engine's: its largest step the horizon, its tolerances
    /// fractions of the terrace height.
    PairPrediction(const DmdSettings& settings, const P& potential, std::uint64_t seed, int bodies)
        : jitter_(settings.horizon, horizonJitter, seed), plans_(bodies),
          ceiling_(bandCeiling(potential, settings.rm)) {
        const double terraceHeight = settings.levels.smallestStep();
        holdScreen = settings.holdScreen;
        search_.maxStep = settings.horizon;
        search_.nudge = nudgeFraction * settings.horizon;
        search_.grazeWindow = grazeFraction * terraceHeight;
        search_.levelTolerance = levelTolerance * terraceHeight;
    }

    /// A body brought to now without touching its stored state: the search's view of it, with
    /// its orbit re-based to now so that the search's samples turn it by small angles only.
    struct Moving {
        Vec3 r, v;
        FreeOrbit<K> orbit;                  // from now on
        typename FreeOrbit<K>::Attitude now; // orbit.at(0)
    };

    /// Predicts every pair of every body from now and gives each body its calendar entry.
    template <class Q> void predictAll(Shared& s, Q& q) {
        for (int i = 0; i < s.sys.size(); ++i) {
            double entry = std::numeric_limits<double>::infinity();
            const Moving mi = movingNow(s, i);
            for (const int j : s.lists.partners(i))
                if (j > i) entry = std::min(entry, predictPair(s, mi, i, j, nullptr));
            scheduleBodyEvents(s, i, entry);
        }
        s.schedule.settle(q, s.time);
        s.schedule.resetCleanupThreshold(q.size());
    }

    /// Forgets every pending event and predicts all pairs from now (all clocks at now).
    void repredictAll(Shared& s) {
        s.schedule.visitQueue([&](auto& q) {
            s.schedule.forgetAll(q);
            predictAll(s, q);
        });
    }

    /// Predicts every pair of i except (i, exclude); (i, partner) has just been resolved.
    /// partnerStart: the sample of (i, partner) now, when the caller has it.
    void predictBody(Shared& s, int i, int exclude, int partner = -1,
                     const PairSample* partnerStart = nullptr) {
        double entry = std::numeric_limits<double>::infinity();
        const Moving mi = movingNow(s, i);
        const auto partners = s.lists.partners(i);
        // The partners' states are fetched `ahead` predictions before theirs: they are scattered
        // in memory, each prediction starts by reading its partner, and one prediction (~0.1–0.2
        // µs) is shorter than a miss of a large system's memory (~0.4 µs on a virtual machine).
        constexpr std::size_t ahead = 3;
        if (s.prefetching)
            for (std::size_t k = 0; k < std::min(ahead, partners.size()); ++k)
                prefetchBody(s, partners[k]);
        for (std::size_t k = 0; k < partners.size(); ++k) {
            if (s.prefetching && k + ahead < partners.size()) prefetchBody(s, partners[k + ahead]);
            const int j = partners[k];
            if (j != exclude)
                entry = std::min(entry, j == partner
                                            ? predictPair(s, mi, i, j, partnerStart, true, int(k))
                                            : predictPair(s, mi, i, j, nullptr, false, int(k)));
        }
        scheduleBodyEvents(s, i, entry);
    }

    /// Asks the caches for body i's plan, which i's events read and rewrite (all but the virtual
    /// events of its pairs).
    [[gnu::always_inline]] void prefetchPlan(int i) const { __builtin_prefetch(&plans_[i]); }

    /// Asks the caches for what predictPair reads of body j first.
    [[gnu::always_inline]] void prefetchBody(const Shared& s, int j) const {
        prefetchLines(&s.sys.bodies[j], sizeof(State));
        if constexpr (keepsOrbit<K>)
            prefetchLines(&s.orbit[j], sizeof(s.orbit[j])); // none kept: none asked for
        __builtin_prefetch(&s.schedule.book(j));
    }

    /// Body i's own events: its next cell crossing, its next list rebuild and, when some pair of i
    /// enters r_m only beyond the horizon, a virtual event at the earliest such entry (one per
    /// body instead of one per approaching pair; should i have no event before then, it
    /// re-predicts all its pairs). Only the earliest of the three is scheduled: most are overtaken
    /// by a collision of i, and the others are planned again when it is processed.
    void scheduleBodyEvents(Shared& s, int i, double entry) {
        plans_[i].entry = entry;
        planCellCrossing(s, i);
        planRelist(s, i);
        scheduleBodyEvent(s, i);
    }

    /// Queues the earliest of i's planned body events (ties: cell, relist, entry).
    void scheduleBodyEvent(Shared& s, int i) {
        const BodyPlan& p = plans_[i];
        if (p.cell <= p.relist && p.cell <= p.entry) {
            if (!std::isfinite(p.cell)) return;
            PendingEvent e = bodyEvent(EventKind::CellCrossing, p.cell);
            e.side = p.cellSide;
            schedule(s, i, e);
        } else if (p.relist <= p.entry) {
            schedule(s, i, bodyEvent(EventKind::Relist, p.relist));
        } else {
            schedule(s, i, bodyEvent(EventKind::Virtual, p.entry));
        }
    }

    /// When i will have moved (1 − relistMargin) of the relist distance from its list's anchor.
    void planRelist(const Shared& s, int i) {
        const double radius = s.lists.relistDistance() * (1.0 - relistMargin);
        const Vec3 moved = positionNow(s, i) - s.lists.anchor(i);
        // Already out (an event tied with the rebuild came first): rebuild now.
        const double dt = moved.squaredNorm() >= radius * radius
                              ? 0.0
                              : shellWindow(moved, s.sys.bodies[i].v, radius).exit;
        plans_[i].relist = s.time + dt;
    }

    void planCellCrossing(const Shared& s, int i) {
        const State& b = s.sys.bodies[i];
        int axis = 0, dir = 0;
        const double dt = s.cells.crossingTime(i, b.r + b.v * (s.time - s.schedule.book(i).clock),
                                               b.v, axis, dir);
        plans_[i].cell = s.time + dt;
        plans_[i].cellSide = static_cast<std::int8_t>(2 * axis + (dir > 0 ? 1 : 0));
    }

    /// Next event of the pair (i, j) from now: screening with r_m, then the adaptive search up to
    /// the jittered horizon; a truncated search leaves a virtual event holding its end point.
    /// A pair entering r_m only beyond the horizon is not searched: its entry time (absolute) is
    /// returned for the caller to schedule; +∞ otherwise.
    /// mi is body i brought to now (movingNow(s, i)), prepared once for all pairs of i; slot: where
    /// j likely sits in i's list (−1: unknown).
    double predictPair(Shared& s, const Moving& mi, int i, int j, const PairSample* resumeFrom,
                       bool afterEvent = false, int slot = -1) {
        constexpr double none = std::numeric_limits<double>::infinity();
        const State& bj0 = s.sys.bodies[j];
        const double dtj = s.time - s.schedule.book(j).clock;
        const Vec3 r0 = s.sys.box.minimumImage(mi.r - translated(bj0.r, bj0.v, dtj), s.inverseBox);
        const Vec3 w = mi.v - bj0.v;
        // Only a pair inside r_m (up to round-off) can be bound; skip the lookup for the rest.
        constexpr double boundSlack = 1.0 + 1e-6;
        const bool maybeBound = r0.squaredNorm() <= s.settings.rm * s.settings.rm * boundSlack;
        const int n = maybeBound ? s.lists.terrace(i, j, slot) : 0;
        // A bound pair must reach a level before |r_ij| = r_m; in the worst orientation it does
        // so exactly there, so the shell must not cut its search short.
        const ShellWindow win = n != 0 ? ShellWindow{0.0, std::numeric_limits<double>::infinity()}
                                       : shellWindow(r0, w, s.settings.rm);
        if (win.empty()) return none;
        const double horizon = jitter_.next();
        if (win.enter > horizon) return s.time + win.enter;
        // Body j's attitude now serves the hold screen; its orbit from now is built only for a
        // search. Its orbit at its clock (built, for a rotor) gives both: taken once.
        const auto& orbitJAtClock = orbitOf(s, j);
        const auto ajNow = orbitJAtClock.startOf(dtj);
        const auto sampleWith = [&](double tau, const auto& attitudes) {
            const auto& [ai, aj] = attitudes;
            const EnergyRate e =
                energyAndRate(s.sys.potential, translated(r0, w, tau), w, orientationOf<P>(ai),
                              ai.w, orientationOf<P>(aj), aj.w);
            return PairSample{tau, e.U, e.dUdt};
        };
        const std::array now{mi.now, ajNow};
        if constexpr (HoldScreenable<P>)
            // Not for the pair just resolved: it sits on a level, where the screen answers 0 (it
            // could hold only a root found farther from the level than the screen's edge margin;
            // a search is right either way).
            if (holdScreen && !afterEvent) {
                // No level within reach for a while: no samples now, a fresh search then.
                const double hold = holdOnTerrace(s, now, i, j, r0, w, n, horizon, win.exit);
                if (hold == none) return none; // out of r_m before it could change terrace
                if (hold > 0.0) {
                    schedule(s, i, pairEvent(s, EventKind::Virtual, j, s.time + hold));
                    ++screened;
                    return none;
                }
            }
        if constexpr (!HoldScreenable<P> && RangeBounded<P>)
            if (holdScreen && !afterEvent) { // as above, with the potential's own bounds
                const double hold = holdInRange(s, now, i, j, r0, w, n, horizon, win.exit);
                if (hold == none) return none;
                if (hold > 0.0) {
                    schedule(s, i, pairEvent(s, EventKind::Virtual, j, s.time + hold));
                    ++screened;
                    return none;
                }
            }
        const FreeOrbit<K> orbitJ = orbitJAtClock.from(dtj);
        auto eval = [&](double tau) { return sampleWith(tau, attitudesAt(mi.orbit, orbitJ, tau)); };
        PairSample start;
        if (resumeFrom && win.enter == 0.0) {
            start = *resumeFrom;
        } else {
            start = win.enter == 0.0 ? sampleWith(0.0, now) : eval(win.enter);
            ++evaluations;
            if (!afterEvent) checkOnTerrace(s, start.U, i, j, n);
        }
        const double tEnd = std::min(win.exit, horizon);
        const SearchResult r = findTerraceExit(
            eval, start, s.settings.levels.lower(n), s.settings.levels.upper(n), tEnd,
            pairSearch(s, w, s.schedule.book(i).axisRate + s.schedule.book(j).axisRate),
            afterEvent);
        evaluations += r.evaluations;
        if (r.side != ExitSide::None) {
            PendingEvent e = pairEvent(s, EventKind::Collision, j, s.time + r.t);
            e.side = static_cast<std::int8_t>(r.side);
            schedule(s, i, e);
        } else if (win.exit > horizon) {
            schedule(s, i, pairEvent(s, EventKind::Virtual, j, s.time + r.end.t));
        }
        return none;
    }

    /// A pair sampled beyond a level of its own terrace has crossed it unseen: the bookkeeping no
    /// longer describes the system (a defect, never a property of the dynamics). Reported at
    /// once, rather than left to loop on a reflection at one instant until the stall detector
    /// fires. A pair can sit past a level by round-off only (an event due now), far below the
    /// margin.
    void checkOnTerrace(const Shared& s, double U, int i, int j, int n) const {
        const double margin = missedEventMargin * s.terraceHeight();
        if (U >= s.settings.levels.lower(n) - margin && U <= s.settings.levels.upper(n) + margin)
            return;
        throw std::logic_error("dmd: bodies " + std::to_string(s.sceneIndex(i)) + " and " +
                               std::to_string(s.sceneIndex(j)) + " have U = " + std::to_string(U) +
                               " kJ/mol at t = " + std::to_string(units::toFs(s.time)) +
                               " fs, beyond the levels of " + "their terrace " + std::to_string(n) +
                               ": an event was missed");
    }

    /// How long from now the pair (i, j) on terrace n, at separation r0 and relative velocity w,
    /// with attitudes `now`, is sure to stay on it (dmd/terrace_hold.hpp): +∞ when until it leaves
    /// r_m at windowExit; otherwise the longest of horizon, 2·horizon, … up to maxHoldHorizons
    /// horizons, or 0 when not even through the horizon (then the search must look).
    template <class Attitudes>
    double holdOnTerrace(const Shared& s, const Attitudes& now, int i, int j, const Vec3& r0,
                         const Vec3& w, int n, double horizon, double windowExit) {
        const auto& [ai, aj] = now;
        PairMotion m;
        m.speedSquared = w.x() * w.x() + w.y() * w.y() + w.z() * w.z();
        m.r = std::sqrt(r0.x() * r0.x() + r0.y() * r0.y() + r0.z() * r0.z());
        m.rRate = (r0.x() * w.x() + r0.y() * w.y() + r0.z() * w.z()) / m.r;
        if constexpr (isOrientational<P>) {
            const Vec3 &si = ai.axis, &sj = aj.axis;
            m.c = si.x() * sj.x() + si.y() * sj.y() + si.z() * sj.z();
            const Vec3 spin = ai.w - aj.w;
            m.cRate = spin.x() * (si.y() * sj.z() - si.z() * sj.y()) +
                      spin.y() * (si.z() * sj.x() - si.x() * sj.z()) +
                      spin.z() * (si.x() * sj.y() - si.y() * sj.x());
            m.turn = s.schedule.book(i).axisRate + s.schedule.book(j).axisRate;
            // |s̈| = |ω|² for a linear rotor (uniform rotation), so |c̈| ≤ Ω²; a top's ω wanders.
            if constexpr (isLinearRotorKind<K>) m.turnCurvature = m.turn * m.turn;
        }
        const auto& form = bandPotential(s.sys.potential);
        const double x = form.effectiveDistance(m.r, m.c);
        const TerraceBands& b = bands_.of(n, form, s.settings.levels);
        const BandHold hold(x <= b.bottom ? b.wall : b.tail, m, form.alignmentLength(), ceiling_);
        const double longest = maxHoldHorizons * horizon;
        if (windowExit <= longest && hold.through(windowExit))
            return std::numeric_limits<double>::infinity();
        return holdTime(hold, horizon, longest);
    }

    /// holdOnTerrace for a potential that bounds its own values (core/pair_potential.hpp
    /// RangeBounded): over [0, T] the centres' separation moves by at most |w|T and the bodies
    /// turn by at most their angular-speed bounds times T (the same bounds the search's step
    /// uses), so U stays in energyRange(…, |w|T, Ω_i T, Ω_j T); the pair holds through T while
    /// that range lies inside its terrace. The range only widens with T.
    template <class Attitudes>
    double holdInRange(const Shared& s, const Attitudes& now, int i, int j, const Vec3& r0,
                       const Vec3& w, int n, double horizon, double windowExit) const {
        const auto& [ai, aj] = now;
        const double speed = w.norm();
        const double spinI = s.schedule.book(i).axisRate;
        const double spinJ = s.schedule.book(j).axisRate;
        const TerraceLevels& levels = s.settings.levels;
        // Far from round-off in U and in g(r), far below any terrace.
        const double margin = rangeMargin * s.terraceHeight();
        const double lower = levels.lower(n) + margin, upper = levels.upper(n) - margin;
        // ai and aj captured by name: clang before 16 cannot capture a structured binding.
        const auto through = [&, &ai = ai, &aj = aj](double T) {
            const EnergyRange u = s.sys.potential.energyRange(
                r0, orientationOf<P>(ai), orientationOf<P>(aj), speed * T, spinI * T, spinJ * T);
            return u.lo > lower && u.hi < upper;
        };
        const double longest = maxHoldHorizons * horizon;
        if (windowExit <= longest && through(windowExit))
            return std::numeric_limits<double>::infinity();
        // The longest rung first, then the first: most pairs hold through all or fail at once,
        // and a bound costs several samples of U, so the rungs between are not tried.
        if (through(longest)) return longest;
        return through(horizon) ? horizon : 0.0;
    }

    /// The search settings for a pair with relative velocity w and summed angular speed turn: the
    /// step shortened where the pair would move more than stepShiftFraction r_m or turn more
    /// than stepTurn in one, or where a body's extent would carry its sites or ends farther.
    SearchSettings pairSearch(const Shared& s, const Vec3& w, double turn) const {
        SearchSettings search = search_;
        const double shift = stepShiftFraction * s.settings.rm;
        const double w2 = w.squaredNorm();
        if (w2 * search.maxStep * search.maxStep > shift * shift)
            search.maxStep = shift / std::sqrt(w2);
        if (turn * search.maxStep > stepTurn) search.maxStep = stepTurn / turn;
        // Where U is shaped by points off the centres (a molecule's sites, an ellipsoid's ends),
        // those move by up to extent·turn per time unit besides: the same shift bounds them.
        if constexpr (requires { bandPotential(s.sys.potential).extent(); }) {
            const double arm = bandPotential(s.sys.potential).extent() * turn;
            if (arm * search.maxStep > shift) search.maxStep = shift / arm;
        }
        return search;
    }

    /// Body i as the search sees it now, from its orbit cached at its clock: the stored state is
    /// not touched.
    Moving movingNow(const Shared& s, int i) const {
        const State& b = s.sys.bodies[i];
        const double dt = s.time - s.schedule.book(i).clock;
        Moving m{translated(b.r, b.v, dt), b.v, orbitOf(s, i).from(dt), {}};
        m.now = m.orbit.at(0.0);
        return m;
    }

    PendingEvent bodyEvent(EventKind kind, double t) const {
        PendingEvent e;
        e.time = t;
        e.kind = kind;
        return e;
    }

    /// An event of a pair with partner j, stamped with j's counter as of now.
    PendingEvent pairEvent(const Shared& s, EventKind kind, int j, double t) const {
        PendingEvent e = bodyEvent(kind, t);
        e.j = j;
        e.countJ = s.schedule.book(j).counter;
        return e;
    }

    /// Files e in the agenda of its owner i (dmd/schedule.hpp).
    void schedule(Shared& s, int i, const PendingEvent& e) { s.schedule.schedule(i, e); }

    std::size_t predictionBytes() const {
        return plans_.capacity() * sizeof(BodyPlan) + bands_.bytesReserved();
    }

    /// The search's settings and the horizon stream (the start and checkpoint read them).
    const SearchSettings& search() const { return search_; }
    HorizonJitter& jitter() { return jitter_; }
    const HorizonJitter& jitter() const { return jitter_; }

    // What the engine's statistics report; carried over when the engine is rebuilt.
    std::uint64_t evaluations = 0, screened = 0;
    bool holdScreen = true; // whether pairs are screened by their hold time before a search

private:
    SearchSettings search_;
    HorizonJitter jitter_;
    BodyArray<BodyPlan> plans_;
    TerraceBandTable bands_; // effective-distance bands of the terraces (hold screen)
    // The hold screen's ceiling on r (dmd/terrace_hold.hpp bandCeiling), Å.
    double ceiling_;
};

} // namespace terrace::dmd
