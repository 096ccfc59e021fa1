#pragma once
// The state the DMD engine's parts share (dmd/engine.hpp): the bodies, the settings, each body's
// book, agenda and calendar entry, the neighbour lists with the pairs' terraces, the cells, the
// free orbits, the time, the engine's numbering of the scene's bodies and the impulse virial.
//
// Every part — the clocks (dmd/body_clocks.hpp), the prediction (dmd/pair_prediction.hpp), the
// start and checkpoint (dmd/engine_start.hpp) and the event loop itself — reads and sets these
// through a reference handed to it: one object that the engine holds by value, so that the pair
// loop follows no pointer and the engine stays movable (renumberBodies rebuilds it in place).
// What only one part uses stays in that part. Units: Å, kJ/mol, time unit 100 fs.
#include "core/free_orbit.hpp"
#include "core/huge_pages.hpp"
#include "core/system.hpp"
#include "dmd/cell_list.hpp"
#include "dmd/neighbour_lists.hpp"
#include "dmd/schedule.hpp"
#include "dmd/settings.hpp"
#include <utility>
#include <vector>

namespace terrace::dmd {

/// From this many bodies on, the engine's data (~1 KB a body) outgrow the caches, and the engine
/// asks for bodies ahead of their use.
inline constexpr int prefetchFromBodies = 16384;

template <BodyKind K, PairPotential P> struct EngineState {
    EngineState(System<K, P>&& initial, DmdSettings s)
        : sys(std::move(initial)), settings(std::move(s)), lists(makeLists(settings.rm, sys)),
          cells(sys.box.length, settings.rm + lists.skin(), sys.size()),
          schedule(sys.size(), settings.eager, settings.horizon) {}

    /// The engine's number of the scene's body b, and the scene's number of the engine's body i:
    /// inside, the bodies are numbered in the Morton order of their cells (the engine's
    /// sortBodiesByCell).
    int engineIndex(int b) const { return engineNumber.empty() ? b : engineNumber[b]; }
    int sceneIndex(int i) const { return sceneNumber.empty() ? i : sceneNumber[i]; }

    double terraceHeight() const { return settings.levels.smallestStep(); }

    System<K, P> sys; // the bodies, each stored at its own clock (its book's)
    DmdSettings settings;
    NeighbourLists lists; // and the pairs' terraces; before cells: the cell width follows the skin
    CellList cells;
    // Each body's book (clock, counter), agenda and calendar entry (dmd/schedule.hpp).
    Schedule<EngineState> schedule;
    // Each body's free orbit from its state at its clock, where kept (dmd/body_clocks.hpp
    // keepsOrbit); else empty.
    BodyArray<FreeOrbit<K>> orbit;
    // The scene's number of each engine body and the engine's number of each scene body (empty:
    // the same numbering, the bodies not sorted).
    std::vector<int> sceneNumber, engineNumber;
    double time = 0.0;
    double impulseVirial = 0.0;               // Σ r_ij·Δp_i over collisions, kJ/mol × time unit
    double inverseBox = 1.0 / sys.box.length; // 1/L (Å⁻¹) for minimum images; NVE: L is fixed
    // Whether the engine asks the caches for bodies ahead of their use: only where its data
    // outgrow them (at N = 512, where everything is cached, the prefetches cost ~2 %).
    bool prefetching = sys.size() >= prefetchFromBodies;

private:
    static NeighbourLists makeLists(double rm, const System<K, P>& sys) {
        const double density = sys.size() / sys.box.volume();
        const double skin = listSkin(rm, density, sys.box.length);
        return NeighbourLists(sys.size(), skin, listCapacity(rm + skin, density, sys.size()));
    }
};

} // namespace terrace::dmd
