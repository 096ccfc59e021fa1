#pragma once
// The DMD engine's parameters, read from `scene.dmd` and validated before any work (DESIGN.md
// "Interfaces", "Bad input"): every bad value is a SceneError naming its key.
//   dV            terrace height in units of kT (levels (n − ½) dV kT), > 0
//   levels        explicit levels in kJ/mol (override dV when non-empty)
//   queue         auto | heap | bpq | tree (auto: tree)
//   invalidation  lazy | eager
//   horizon_fs    virtual-event horizon and largest search step, fs, >= limits::minHorizonFs
//   hold_screen   whether pairs are screened by their hold time before a search (default true;
//                 false only to measure what the screen saves: it changes no event)
//   sort_bodies   whether the engine numbers the bodies in the Morton order of their cells
//                 (default true; false only to check that the order changes no observable)
//   resort_cells  RMS displacement, in cell widths, after which a run renumbers them afresh
//                 (0: only at the start and at restart points; auto, the default: 1 from
//                 prefetchFromBodies bodies on, 0 below)
#include "core/scene.hpp"
#include "core/units.hpp"
#include "dmd/terrace_design.hpp"
#include "dmd/terrace_levels.hpp"
#include <algorithm>
#include <cmath>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace terrace::dmd {

enum class QueueKind { Heap, BoundedPriority, Tree };

/// The calendars by their `dmd.queue` names (auto aside).
inline constexpr std::pair<const char*, QueueKind> queueKinds[] = {
    {"heap", QueueKind::Heap}, {"bpq", QueueKind::BoundedPriority}, {"tree", QueueKind::Tree}};
inline std::string queueName(QueueKind kind) {
    for (const auto& [name, k] : queueKinds)
        if (k == kind) return name;
    throw std::logic_error("dmd: a queue kind without a name");
}

/// dmd.queue = auto takes the tournament tree at every size: on the dense rods, alternated with
/// the queue auto took before, it cost 0.93 of the bounded queue's at N 512 and 0.96 at 32 768,
/// 0.98 of the heap's at 262 144 and 0.80-0.96 at 10^6 (medians; docs/PERFORMANCE.md "a tournament
/// tree for the calendar"), where the bounded queue had been 35-50 % slower than the heap.

struct DmdSettings {
    TerraceLevels levels;
    double rm = 0.0; // interaction range, Å
    QueueKind queue = QueueKind::Tree;
    bool eager = false;    // eager invalidation: erase a body's queued events at its event
    double horizon = 0.04; // time units
    bool holdScreen = true;
    bool sortBodies = true; // bodies numbered in the Morton order of their cells inside the engine
    // and renumbered after an RMS displacement of this many cells (0: never; unset: auto)
    std::optional<double> resortCells;
};

template <PairPotential P>
DmdSettings readDmdSettings(const Scene::Dmd& d, const P& potential, double kT, double boxLength) {
    DmdSettings s;
    if (!d.levels.empty()) {
        s.levels = TerraceLevels::explicitLevels(d.levels, d.values);
        s.levels.checkMinimum(potential.minimumEnergy(), "dmd.levels");
    } else if (!d.terraces.isDefault()) {
        if (!(kT > 0.0) || !std::isfinite(kT))
            throw SceneError("state.temperature: kT must be > 0 to design terraces");
        auto design = designTerraces(d, potential, kT);
        s.levels =
            TerraceLevels::explicitLevels(std::move(design->levels), std::move(design->values));
        s.levels.checkMinimum(potential.minimumEnergy(), "dmd.terraces");
    } else {
        if (!(kT > 0.0) || !std::isfinite(kT))
            throw SceneError("state.temperature: kT must be > 0 to set dmd.dV in units of kT");
        if (!(d.dV > 0.0) || !std::isfinite(d.dV))
            throw SceneError("dmd.dV: must be > 0, got " + std::to_string(d.dV));
        const std::string crowded =
            limits::terraceCountProblem(potential.minimumEnergy(), d.dV, kT);
        if (!crowded.empty()) throw SceneError(crowded);
        s.levels = TerraceLevels::uniform(d.dV * kT);
        s.levels.checkMinimum(potential.minimumEnergy(), "dmd.dV");
    }
    const auto named = std::find_if(std::begin(queueKinds), std::end(queueKinds),
                                    [&](const auto& q) { return d.queue == q.first; });
    if (d.queue == "auto")
        s.queue = QueueKind::Tree;
    else if (named != std::end(queueKinds))
        s.queue = named->second;
    else
        throw SceneError("dmd.queue: must be \"auto\", \"heap\", \"bpq\" or \"tree\", got \"" +
                         d.queue + "\"");
    if (d.invalidation == "lazy")
        s.eager = false;
    else if (d.invalidation == "eager")
        s.eager = true;
    else
        throw SceneError("dmd.invalidation: must be \"lazy\" or \"eager\", got \"" +
                         d.invalidation + "\"");
    if (!(d.horizon_fs >= limits::minHorizonFs) || !std::isfinite(d.horizon_fs))
        throw SceneError("dmd.horizon_fs: must be >= " + std::to_string(limits::minHorizonFs) +
                         " fs, got " + std::to_string(d.horizon_fs) +
                         ": a shorter horizon only multiplies virtual events");
    s.horizon = units::fromFs(d.horizon_fs);
    s.holdScreen = d.hold_screen;
    s.sortBodies = d.sort_bodies;
    if (d.resort_cells && (!(*d.resort_cells >= 0.0) || !std::isfinite(*d.resort_cells)))
        throw SceneError("dmd.resort_cells: must be >= 0, got " + std::to_string(*d.resort_cells));
    s.resortCells = d.resort_cells;
    s.rm = interactionRange(s.levels, potential);
    if (!(s.rm > 0.0))
        throw SceneError("dmd.dV: no level bounding terrace 0 is ever reached (r_m = 0)");
    // With L < 2 r_m a pair could interact through two periodic images at once.
    if (boxLength < 2.0 * s.rm)
        throw SceneError("dmd.dV: the box edge " + std::to_string(boxLength) +
                         " Å is shorter than twice the interaction range r_m = " +
                         std::to_string(s.rm) + " Å; use more bodies or a larger dV");
    return s;
}

} // namespace terrace::dmd
