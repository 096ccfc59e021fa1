#pragma once
// A look inside the DMD engine (dmd/engine.hpp) for tests, benchmarks and experiment tools: what
// they read and set beyond the Engine contract (core/engine.hpp), which is all that runs use.
// Each probe behaves as the engine's own member did; bodies are named by the scene's numbers
// unless said otherwise. Nothing in the product includes this header.
#include "core/system.hpp"
#include "dmd/body_clocks.hpp"
#include "dmd/engine.hpp"
#include "dmd/engine_start.hpp"
#include "dmd/neighbour_lists.hpp"
#include "dmd/terrace_levels.hpp"
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

namespace terrace::dmd::testing {

/// The engine's one friend. Called as Probe::counts(engine), and so on.
struct Probe {
    template <BodyKind K, PairPotential P> using E = Engine<K, P>;

    /// Process n events (samples excluded); clocks stay local, time() is the last event's time.
    template <BodyKind K, PairPotential P> static void runEvents(E<K, P>& e, std::uint64_t n) {
        e.requireEvents();
        e.visitQueue([&](auto& q) {
            for (std::uint64_t k = 0; k < n; ++k)
                if (!e.step(q)) throw std::logic_error("dmd: sample event outside advanceTo");
        });
    }
    /// Whether pairs are screened by their hold time before a search (on by default; off only to
    /// measure what the screen saves, or to check that it changes no event). Every pair is
    /// predicted afresh.
    template <BodyKind K, PairPotential P> static void setHoldScreen(E<K, P>& e, bool on) {
        e.setHoldScreen(on);
    }
    /// Consecutive events at one instant tolerated before the clock counts as stopped.
    template <BodyKind K, PairPotential P> static void setStallLimit(E<K, P>& e, std::uint64_t n) {
        e.stallWatch_.setLimit(n);
    }

    /// The terrace index the engine holds for the pair (i, j).
    template <BodyKind K, PairPotential P> static int terrace(const E<K, P>& e, int i, int j) {
        return e.s_.lists.terrace(e.s_.engineIndex(i), e.s_.engineIndex(j));
    }
    /// Puts the pair (i, j) on terrace n whatever its U: bookkeeping corrupted on purpose, to test
    /// that the engine reports it.
    template <BodyKind K, PairPotential P>
    static void overrideTerrace(E<K, P>& e, int i, int j, int n) {
        e.moveTerrace(e.s_.engineIndex(i), e.s_.engineIndex(j), n);
    }
    /// The lists and the pairs' terraces, in the engine's numbering of the bodies (sceneIndex).
    template <BodyKind K, PairPotential P>
    static const NeighbourLists& neighbourLists(const E<K, P>& e) {
        return e.s_.lists;
    }
    /// The partners listed for body b, in the scene's numbering.
    template <BodyKind K, PairPotential P>
    static std::vector<int> listedPartners(const E<K, P>& e, int b) {
        std::vector<int> p;
        for (const int j : e.s_.lists.partners(e.s_.engineIndex(b)))
            p.push_back(e.s_.sceneIndex(j));
        return p;
    }

    template <BodyKind K, PairPotential P> static int cellsPerSide(const E<K, P>& e) {
        return e.s_.cells.cellsPerSide();
    }
    template <BodyKind K, PairPotential P> static const TerraceLevels& levels(const E<K, P>& e) {
        return e.s_.settings.levels;
    }
    /// r_m (Å).
    template <BodyKind K, PairPotential P> static double interactionRange(const E<K, P>& e) {
        return e.s_.settings.rm;
    }
    template <BodyKind K, PairPotential P> static const EventCounts& counts(const E<K, P>& e) {
        return e.counts_;
    }
    template <BodyKind K, PairPotential P> static std::size_t queueSize(const E<K, P>& e) {
        return e.s_.schedule.queueSize();
    }

    /// Whether the cell order of the bodies has decayed (the engine then renumbers them at its
    /// next advanceTo).
    template <BodyKind K, PairPotential P> static bool orderHasDecayed(const E<K, P>& e) {
        return e.orderHasDecayed();
    }
    /// The number of bodies orderHasDecayed follows (0: none; every anchorStride_-th, ≤ 4 096).
    template <BodyKind K, PairPotential P> static std::size_t orderSampleBodies(const E<K, P>& e) {
        return e.orderAnchors_.size();
    }
    /// The RMS displacement at which orderHasDecayed (Å; 0: never).
    template <BodyKind K, PairPotential P> static double resortDistance(const E<K, P>& e) {
        return e.orderAnchors_.empty() ? 0.0 : std::sqrt(e.resortSquared_);
    }
    /// The engine's number of the scene's body b, and the scene's number of the engine's body i.
    template <BodyKind K, PairPotential P> static int engineIndex(const E<K, P>& e, int b) {
        return e.s_.engineIndex(b);
    }
    template <BodyKind K, PairPotential P> static int sceneIndex(const E<K, P>& e, int i) {
        return e.s_.sceneIndex(i);
    }

    /// Terraced energy recomputed from scratch from U of every pair (all pairs, O(N²)). On a
    /// level this rounds by U alone, so compare with potentialEnergy() only away from levels.
    template <BodyKind K, PairPotential P>
    static double terracedEnergyFromScratch(const E<K, P>& e) {
        const System<K, P> s = e.system();
        const TerraceLevels& levels = e.s_.settings.levels;
        double energy = 0.0;
        for (int i = 0; i < s.size(); ++i)
            for (int j = i + 1; j < s.size(); ++j) {
                const Vec3 rij = s.box.minimumImage(s.bodies[i].r - s.bodies[j].r);
                if (rij.norm() > e.s_.settings.rm) continue;
                const auto si = orientationOf<P, K>(s.bodies[i]);
                const auto sj = orientationOf<P, K>(s.bodies[j]);
                const double U = s.potential.energy(rij, si, sj);
                energy += pairEnergyScale(s.potential, si, sj) * levels.energy(levels.terraceOf(U));
            }
        return energy;
    }

    /// Bytes the engine holds, by part (the heap blocks' own overhead not counted), and in all.
    template <BodyKind K, PairPotential P>
    static std::vector<std::pair<const char*, std::size_t>> memoryByPart(const E<K, P>& e) {
        return e.memoryByPart(e.s_.schedule.memory());
    }
    template <BodyKind K, PairPotential P> static std::size_t bytesReserved(const E<K, P>& e) {
        std::size_t b = 0;
        for (const auto& part : memoryByPart(e))
            b += part.second;
        return b;
    }

    /// Frees what only the event loop needs, as a restart point does before its checkpoint: only
    /// checkpoint(), the reads of the bodies and destruction may follow.
    template <BodyKind K, PairPotential P> static void shed(E<K, P>& e) { e.shed(); }
    /// The bodies at time(), in the scene's order, as system() gives them, but moved out of the
    /// engine rather than copied beside it. The engine is then fit only to be destroyed.
    template <BodyKind K, PairPotential P> static System<K, P> releaseSystem(E<K, P>&& e) {
        return releaseBodies(e.s_);
    }
};

} // namespace terrace::dmd::testing
