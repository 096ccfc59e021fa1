#pragma once
// SMD engine: rigid-body molecular dynamics on the continuous smoothed pair potential g(r)·U
// (core/smoothed_potential.hpp: the model DMD terraces) with the
// symplectic, time-reversible splitting of van Zon & Schofield, Phys. Rev. E 75, 056701 (2007),
// the integrator of the paper's SMD runs ("Comparison between standard molecular dynamics and
// event-driven simulations"; DESIGN.md "SMD engine"). One step of length dt:
//     kick   p += F dt/2,  L += τ dt/2
//     drift  exact free motion over dt (straight line, the body kind's exact rotation)
//     force  F, τ at the new positions (Verlet list, rebuilt when a body moved > skin/2)
//     kick   p += F dt/2,  L += τ dt/2
// or, with smd.scheme, one of the longer symmetric splittings of smd/splitting.hpp (kicks and
// drifts of other lengths, a force evaluation after every drift).
// Time only advances in whole steps: advanceTo(t) stops at the first grid point t0 + k dt >= t,
// so every step is the same symplectic map (the run driver samples on multiples of dt).
// Body order (on unless TERRACE_MEASURE=no-sort-smd, core/measure.hpp): inside the engine the
// bodies are kept in the list's slot order (cells, see smd/neighbour_list.hpp) and re-sorted at
// every list build, so that the kicks, drifts and the gather of positions into slots stream through
// memory instead of jumping around it as the liquid mixes. The slots are filled in the scene's
// order within each cell whatever the engine's own order, so the pair sums, and with them the
// trajectory, are the same bit for bit with and without the sort; outside the engine (snapshot(),
// system(), the sums over all bodies) everything is in the scene's numbering. Units: Å, g/mol,
// kJ/mol, time unit 100 fs.
// Heat bath (run.heat_bath, core/heat_bath.hpp): applied at the step boundary after every whole
// step (not split into half-steps around it): Andersen gives each body, with probability
// 1 − e^{−ν dt}, fresh velocities; CSVR rescales all of them by the factor of its exact
// kinetic-energy propagator over dt. The bodies are visited in the scene's order, so the draws do
// not depend on the engine's own order.
#include "core/engine.hpp"
#include "core/heat_bath.hpp"
#include "core/measure.hpp"
#include "core/overlap.hpp"
#include "core/snapshot.hpp"
#include "core/system.hpp"
#include "smd/neighbour_list.hpp"
#include "smd/pair_forces.hpp"
#include "smd/parameters.hpp"
#include "smd/splitting.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numeric>
#include <span>
#include <sstream>
#include <vector>

namespace terrace::smd {

/// P: the smoothed model (Smoothed<bare potential>), with a finite range r_u.
template <BodyKind K, PairPotential P> class Engine {
    static_assert(
        requires(const P p) {
            p.range();
            p.bare;
            p.cut;
        },
        "SMD integrates a smoothed potential (core/smoothed_potential.hpp)");

public:
    Engine(System<K, P> initial, SmdSettings settings)
        : Engine(initial, std::move(settings), true) {}

private:
    void resumeSteps(const nlohmann::json& checkpoint) {
        steps_ = checkpoint.at("steps").get<long>();
        if (steps_ < 0) throw SceneError("restart: a negative SMD step count");
        if (!bath_.on()) return;
        if (!checkpoint.contains("heat_bath"))
            throw SceneError("restart: the SMD checkpoint holds no heat bath state, and the scene "
                             "asks for run.heat_bath " +
                             std::string(bath_.kind == HeatBath::Kind::Csvr ? "csvr" : "andersen"));
        bathState_.restore(checkpoint.at("heat_bath"));
    }
    // `initial` is moved from: a reference, so that the settings may be read from it first.
    Engine(System<K, P>& initial, SmdSettings settings, bool isStart)
        : sys_(std::move(initial)), par_(settings.par), scheme_(std::move(settings.scheme)),
          sigmaUnit_(settings.sigma), sortBodies_(settings.sortBodies), bath_(settings.bath),
          bathState_(settings.seed) {
        for (const auto& b : sys_.bodies)
            if (!b.r.allFinite() || !b.v.allFinite() || !K::axis(b).allFinite() ||
                !K::angularVelocity(b, sys_.body).allFinite())
                throw SceneError("state: a body has a non-finite position, velocity, orientation "
                                 "or angular velocity");
        if (!(sys_.body.mass > 0.0)) throw SceneError("body.mass: must be > 0");
        if constexpr (MassPerBody<K>)
            for (const auto& b : sys_.bodies)
                if (!(bodyMass<K>(b, sys_.body) > 0.0))
                    throw SceneError("species: every species' mass must be > 0");
        list_.reach = sys_.potential.range() + par_.skin;
        list_.skin = par_.skin;
        const std::size_t n = sys_.bodies.size();
        position_.resize(n);
        local_.resize(n);
        if (readsBodies<P>) orientation_.resize(n);
        if (sortBodies_) {
            sceneOf_.resize(n);
            std::iota(sceneOf_.begin(), sceneOf_.end(), 0);
            engineOf_ = sceneOf_;
        }
        gatherPositions();
        buildList();
        computeForces();
        if (isStart) checkOverlap();
    }

public:
    /// Resumes from a checkpoint() with `initial` holding the bodies at that time: the step count
    /// (and so the time grid) goes on; forces and the Verlet list are computed afresh, as at the
    /// start, so a continued run and one that rebuilds its engine at the same step agree bit for
    /// bit.
    /// The bodies came from a running engine: the start's overlap check is not repeated (a hot
    /// run may hold pairs far up the wall that no start would be allowed).
    Engine(System<K, P> initial, SmdSettings settings, const nlohmann::json& checkpoint)
        : Engine(initial, std::move(settings), false) {
        resumeSteps(checkpoint);
    }

    /// The step count: with the bodies, all a resumed engine needs.
    /// The step count (and the heat bath's state when there is one): with the bodies, all a
    /// resumed engine needs.
    nlohmann::json checkpoint() const {
        nlohmann::json c{{"steps", steps_}};
        if (bath_.on()) c["heat_bath"] = bathState_.save();
        return c;
    }

    /// Kinetic energy the heat bath has taken out since the run began (kJ/mol; 0 without one).
    double thermostatEnergy() const { return bathState_.removed; }

    /// Whole dt steps up to the first grid point at or after t (time units).
    void advanceTo(double t) {
        const double remaining = (t - time()) / par_.dt;
        if (remaining <= 0.0) return;
        // A target within round-off of a grid point means that grid point, not one step more.
        const long steps = static_cast<long>(std::ceil(remaining - gridTolerance));
        for (long k = 0; k < steps; ++k) {
            step();
            if (bath_.on()) applyBath();
        }
    }

    /// The heat bath over one step dt, at the step boundary.
    void applyBath() {
        const int n = sys_.size();
        auto& rng = bathState_.rng;
        if (bath_.kind == HeatBath::Kind::Andersen) {
            // Each body's Poisson process of rate ν fires within dt with this probability.
            const double p = -std::expm1(-bath_.rate * par_.dt);
            std::uniform_real_distribution<double> uniform(0.0, 1.0);
            for (int b = 0; b < n; ++b)
                if (uniform(rng) < p)
                    bathState_.removed += andersenCollision<K>(
                        sys_.bodies[sortBodies_ ? engineOf_[b] : b], sys_.body, bath_.kT, rng);
            return;
        }
        const double now = kineticEnergy();
        if (!(now > 0.0)) return;
        const int f = heatBathDof(bath_.kind, totalRotationalDof(sys_), n);
        double sign = 1.0;
        const double next =
            csvrKinetic(now, 0.5 * f * bath_.kT, f, std::exp(-par_.dt / bath_.tau), rng, sign);
        const double alpha = sign * std::sqrt(next / now);
        for (auto& b : sys_.bodies) {
            b.v *= alpha;
            K::scaleAngularVelocity(b, sys_.body, alpha);
        }
        bathState_.removed += now - next;
    }

    /// One splitting step: kick, then (drift, force, kick) once per drift of the scheme.
    void step() {
        using Clock = std::chrono::steady_clock;
        auto t0 = Clock::now();
        kick(scheme_.kick[0] * par_.dt);
        for (std::size_t k = 0; k < scheme_.drift.size(); ++k) {
            const auto t1 = Clock::now();
            const double h = scheme_.drift[k] * par_.dt;
            for (auto& b : sys_.bodies)
                freeMove<K>(b, sys_.body, h);
            gatherPositions();
            const auto t2 = Clock::now();
            const double moved2 = maxSquaredDisplacement(list_, position_);
            if (!(moved2 <= 0.25 * list_.skin * list_.skin)) {
                checkStable(moved2);
                buildList();
                ++list_.rebuilds;
            }
            const auto t3 = Clock::now();
            computeForces();
            const auto t4 = Clock::now();
            kick(scheme_.kick[k + 1] * par_.dt);
            const auto t5 = Clock::now();
            seconds_.kick += seconds(t0, t1) + seconds(t4, t5);
            seconds_.drift += seconds(t1, t2);
            seconds_.neighbour += seconds(t2, t3);
            seconds_.force += seconds(t3, t4);
            t0 = t5;
        }
        ++steps_;
    }

    double time() const { return steps_ * par_.dt; }
    Snapshot snapshot() const {
        if (!sortBodies_) return makeSnapshot(sys_, time());
        Snapshot s = emptySnapshot<K>(time(), sys_.box.length, sys_.bodies.size());
        for (const int i : engineOf_)
            appendBody<K>(s, sys_.bodies[i], sys_.body);
        return s;
    }
    /// The bodies `bodies` (the scene's numbers) at time(), in that order.
    Snapshot snapshot(std::span<const int> bodies) const {
        Snapshot s = emptySnapshot<K>(time(), sys_.box.length, bodies.size());
        for (const int b : bodies)
            appendBody<K>(s, sys_.bodies[sortBodies_ ? engineOf_[b] : b], sys_.body);
        return s;
    }
    /// Body b's position at time() (b: the scene's number).
    Vec3 position(int b) const { return sys_.bodies[sortBodies_ ? engineOf_[b] : b].r; }
    /// Every body's position at time(), in the scene's order (the snapshot's other fields empty).
    Snapshot positions() const {
        const std::size_t n = sys_.bodies.size();
        Snapshot s = positionsOnly(time(), sys_.box.length, n);
        for (std::size_t b = 0; b < n; ++b)
            s.position.push_back(position(static_cast<int>(b)));
        return s;
    }
    // The sums over all bodies go in the scene's order, as without the sort: the same round-off.
    double kineticEnergy() const {
        if (!sortBodies_) return totalKinetic(sys_);
        double e = 0.0;
        for (const int i : engineOf_)
            e += terrace::kineticEnergy<K>(sys_.bodies[i], sys_.body);
        return e;
    }
    /// The smoothed continuous potential energy at time(): the model's U, which SMD integrates.
    double potentialEnergy() const { return forces_.potential; }
    /// The model's U and W at time(): SMD moves on the continuous model, so these are its own
    /// (no terracing: nothing for a profile).
    ContinuousSums continuousSums(TerracingProfile* = nullptr) const {
        return {forces_.potential, forces_.virial};
    }
    /// The molecular virial W = Σ_pairs r_ij·F_ij at time() (kJ/mol): P = (2 K_trans + W)/(3V).
    static constexpr VirialKind virialKind = VirialKind::Instantaneous;
    double virial() const { return forces_.virial; }
    /// ½ m Σ v² at time() (kJ/mol): the kinetic term of the pressure.
    double translationalKineticEnergy() const {
        if (!sortBodies_) return translationalKinetic(sys_);
        double e = 0.0;
        if constexpr (MassPerBody<K>) {
            for (const int i : engineOf_)
                e += K::mass(sys_.bodies[i], sys_.body) * sys_.bodies[i].v.squaredNorm();
            return 0.5 * e;
        }
        for (const int i : engineOf_)
            e += sys_.bodies[i].v.squaredNorm();
        return 0.5 * sys_.body.mass * e;
    }
    Vec3 totalMomentum() const {
        if (!sortBodies_) return terrace::totalMomentum(sys_);
        Vec3 p = Vec3::Zero();
        for (const int i : engineOf_)
            p += bodyMass<K>(sys_.bodies[i], sys_.body) * sys_.bodies[i].v;
        return p;
    }

    /// Scale v and ω so that the kinetic energy is ½ degreesOfFreedom(sys) kT.
    void rescaleTemperature(double kT) {
        if (!sortBodies_) return rescaleToTemperature(sys_, kT);
        const double target = 0.5 * degreesOfFreedom(sys_) * kT;
        const double now = kineticEnergy();
        if (now <= 0.0) return;
        const double f = std::sqrt(target / now);
        for (auto& b : sys_.bodies) {
            b.v *= f;
            K::scaleAngularVelocity(b, sys_.body, f);
        }
    }

    /// Flip every velocity and angular velocity: the step map is then run backwards in time.
    void reverseMotion() {
        for (auto& b : sys_.bodies) {
            b.v = -b.v;
            K::scaleAngularVelocity(b, sys_.body, -1.0);
        }
    }

    /// Counters since construction (steps, neighbour_rebuilds, pair_evaluations = pairs found
    /// within r_u), the parameters (dt_fs; skin, r_l, r_u in σ), the current list size, and the
    /// wall-clock seconds spent in each phase of the step since construction.
    nlohmann::json statistics() const {
        const double sigma = sigmaUnit_;
        return {{"steps", steps_},
                {"neighbour_rebuilds", list_.rebuilds},
                {"pair_evaluations", evaluations_},
                {"dt_fs", units::toFs(par_.dt)},
                {"force_evaluations", steps_ * scheme_.forceEvaluations()},
                {"skin_sigma", par_.skin / sigma},
                {"r_l_sigma", sys_.potential.cut.inner() / sigma},
                {"r_u_sigma", sys_.potential.range() / sigma},
                // A double, not a count: the run driver reports integers as production increases.
                {"listed_pairs_per_body", double(list_.pairCount()) / std::max(1, sys_.size())},
                {"phase_seconds",
                 {{"kick", seconds_.kick},
                  {"drift", seconds_.drift},
                  {"neighbour", seconds_.neighbour},
                  {"force", seconds_.force}}}};
    }

    /// The bodies in the scene's numbering (a copy).
    System<K, P> system() const {
        if (!sortBodies_) return sys_;
        System<K, P> out{sys_.box, sys_.body, sys_.potential, {}, sys_.kT};
        out.bodies.reserve(sys_.bodies.size());
        for (const int i : engineOf_)
            out.bodies.push_back(sys_.bodies[i]);
        return out;
    }
    /// The bodies (in the scene's numbering) and the checkpoint, moved out; the engine is spent.
    Released<System<K, P>> release() && {
        nlohmann::json c = checkpoint();
        if (!sortBodies_) return {std::move(sys_), std::move(c)};
        return {system(), std::move(c)};
    }
    const Parameters& parameters() const { return par_; }
    long steps() const { return steps_; }
    long neighbourRebuilds() const { return list_.rebuilds; }
    long pairEvaluations() const { return evaluations_; }
    /// The scene number of the body the engine keeps at `engineIndex` (the same without the sort).
    int sceneIndex(int engineIndex) const {
        return sortBodies_ ? sceneOf_[engineIndex] : engineIndex;
    }

private:
    /// Between two list checks a body moves one step. A jump past the whole skin, or a position
    /// that is no longer finite, means the time step is far too long for the forces met (pairs
    /// would be missed, then NaN spreads): stop with an error instead.
    void checkStable(double moved2) const {
        const double skin = list_.skin;
        if (std::isfinite(moved2) && (skin == 0.0 || moved2 <= skin * skin)) return;
        std::ostringstream msg;
        msg << "smd: the integration became unstable at t = " << units::toFs(time())
            << " fs: a body moved " << std::sqrt(moved2)
            << " Å since the last neighbour-list check (skin " << skin
            << " Å); smd.dt_fs = " << units::toFs(par_.dt)
            << " is too long for this state point, use a shorter one";
        throw std::runtime_error(msg.str());
    }

    static constexpr double gridTolerance = 1e-9; // in steps: far above round-off of t/dt

    /// Names the first overlapping pair at the start, instead of letting its huge forces end the
    /// run later as an "unstable time step".
    void checkOverlap() const {
        const double uMin = sys_.potential.minimumEnergy();
        const double outer2 = sys_.potential.range() * sys_.potential.range();
        const auto none = unusedOrientation<P>();
        for (std::size_t a = 0; a + 1 < list_.start.size(); ++a)
            for (std::size_t k = list_.start[a]; k < list_.start[a + 1]; ++k) {
                const std::uint32_t e = list_.entry[k];
                const std::size_t b = e >> NeighbourList::imageBits;
                const Vec3 rij =
                    local_[a] - local_[b] + list_.imageShift[e & NeighbourList::imageMask];
                if (!(rij.squaredNorm() < outer2)) continue;
                const double U = sys_.potential.energy(rij, readsBodies<P> ? orientation_[a] : none,
                                                       readsBodies<P> ? orientation_[b] : none);
                if (overlapsAtStart(U, uMin))
                    throwOverlap(sceneIndex(list_.order[a]), sceneIndex(list_.order[b]), U);
            }
    }

    template <class T> static double seconds(T a, T b) {
        return std::chrono::duration<double>(b - a).count();
    }

    /// Builds the list from position_. With the sort, the slots are filled in the scene's order
    /// within each cell, then the bodies (and position_, and the list's displacement reference)
    /// are moved into slot order, so that slot a holds body a.
    void buildList() {
        if (!sortBodies_) {
            build(list_, sys_.box, position_);
            return;
        }
        build(list_, sys_.box, position_, avx2Available(), engineOf_);
        const std::size_t n = sys_.bodies.size();
        // Body order[a] goes to a: each cycle of the permutation in turn, every body moved once.
        moved_.assign(n, 0);
        for (std::size_t a = 0; a < n; ++a) {
            if (moved_[a]) continue;
            auto held = std::move(sys_.bodies[a]);
            std::size_t to = a;
            for (std::size_t from = list_.order[a]; from != a; from = list_.order[from]) {
                sys_.bodies[to] = std::move(sys_.bodies[from]);
                moved_[to] = 1;
                to = from;
            }
            sys_.bodies[to] = std::move(held);
            moved_[to] = 1;
        }
        // Scene numbers follow their bodies; order becomes the identity.
        for (std::size_t a = 0; a < n; ++a) // engineOf_, read by build() only, is scratch here
            engineOf_[a] = sceneOf_[list_.order[a]];
        std::swap(sceneOf_, engineOf_);
        for (std::size_t a = 0; a < n; ++a) {
            engineOf_[sceneOf_[a]] = static_cast<int>(a);
            list_.order[a] = static_cast<int>(a);
        }
        gatherPositions();
        list_.builtAt.assign(position_.begin(), position_.end());
    }

    /// p += F h, L += τ h with the forces at the current positions.
    void kick(double h) {
        const double hm = h / sys_.body.mass;
        for (std::size_t a = 0; a < sys_.bodies.size(); ++a) { // forces are kept per list slot
            auto& b = sys_.bodies[list_.order[a]];
            if constexpr (MassPerBody<K>)
                b.v += (h / K::mass(b, sys_.body)) * forces_.force[a];
            else
                b.v += hm * forces_.force[a];
            if constexpr (K::rotationalDof > 0)
                K::addAngularMomentum(b, sys_.body, h * forces_.torque[a]);
        }
    }

    void gatherPositions() {
        for (std::size_t i = 0; i < sys_.bodies.size(); ++i)
            position_[i] = sys_.bodies[i].r;
    }

    void computeForces() {
        const std::size_t n = sys_.bodies.size();
        for (std::size_t a = 0; a < n; ++a) {
            const int i = list_.order[a];
            local_[a] = position_[i] - list_.offset[a];
            if constexpr (readsBodies<P>) orientation_[a] = orientationOf<P, K>(sys_.bodies[i]);
        }
        forces_.reset(n);
        accumulateListedPairs<typename P::Bare>(forces_, sys_.potential, list_, local_,
                                                orientation_);
        evaluations_ += forces_.evaluations;
    }

    struct PhaseSeconds {
        double kick = 0, drift = 0, neighbour = 0, force = 0;
    };

    System<K, P> sys_;
    Parameters par_;
    Splitting scheme_;
    double sigmaUnit_; // Å: σ of the scene, the unit of skin and cutoffs in statistics()
    NeighbourList list_;
    Forces forces_;              // per list slot (list_.order maps slots to bodies)
    std::vector<Vec3> position_; // per body, unwrapped
    std::vector<Vec3> local_;    // per list slot: r - offset
    std::vector<typename P::Orientation> orientation_; // per list slot, for a P that reads bodies
    long steps_ = 0;
    long evaluations_ = 0;
    PhaseSeconds seconds_;
    bool sortBodies_;
    std::vector<int> sceneOf_;        // with the sort: scene number of each body of sys_
    std::vector<int> engineOf_;       // with the sort: index in sys_ of each scene number
    std::vector<std::uint8_t> moved_; // scratch of the re-sort
    HeatBath bath_;
    HeatBathState bathState_;
};

} // namespace terrace::smd
