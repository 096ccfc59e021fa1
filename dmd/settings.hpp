#pragma once
// The DMD engine's settings, from the scene's dmd section (dmd/section.hpp, which reads and checks
// its keys) and the model: the levels, the interaction range r_m and the box it must fit in,
// checked before any work (DESIGN.md "Interfaces", "Bad input"): every problem is a SceneError
// naming its key. The measurement switches (core/measure.hpp) come from the environment.
#include "core/heat_bath.hpp"
#include "core/measure.hpp"
#include "core/scene.hpp"
#include "core/step_potential.hpp"
#include "core/units.hpp"
#include "dmd/section.hpp"
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

/// The calendars by their `dmd.queue` names.
inline constexpr std::pair<const char*, QueueKind> queueKinds[] = {
    {"heap", QueueKind::Heap}, {"bpq", QueueKind::BoundedPriority}, {"tree", QueueKind::Tree}};
inline std::string queueName(QueueKind kind) {
    for (const auto& [name, k] : queueKinds)
        if (k == kind) return name;
    throw std::logic_error("dmd: a queue kind without a name");
}

struct DmdSettings {
    TerraceLevels levels;
    double rm = 0.0; // interaction range, Å
    QueueKind queue = QueueKind::Tree;
    bool eager = false;     // eager invalidation: erase a body's queued events at its event
    double horizon = 0.04;  // time units
    bool holdScreen = true; // off: TERRACE_MEASURE=no-hold-screen
    // Bodies numbered in the Morton order of their cells inside the engine (off:
    // TERRACE_MEASURE=no-sort-dmd), and renumbered after an RMS displacement of this many cells
    // (0: never; unset: auto)
    bool sortBodies = true;
    std::optional<double> resortCells;
    HeatBath bath; // run.heat_bath (core/heat_bath.hpp): none unless the caller sets it
};

template <PairPotential P>
DmdSettings readDmdSettings(const DmdSection& d, const P& potential, double kT, double boxLength) {
    DmdSettings s;
    if constexpr (isSteppedModel<P>) {
        // A step table brings its own levels, one per radius (core/step_potential.hpp).
        if (!d.levels.empty())
            throw SceneError("dmd.levels: potential.kind steps sets its own levels, one per "
                             "step of its table: leave dmd.levels out");
        if (!d.terraces.isDefault())
            throw SceneError("dmd.terraces: potential.kind steps sets its own levels, one per "
                             "step of its table: leave dmd.terraces out");
        const StepPotential& steps = *stepPotentialOf(potential);
        s.levels = TerraceLevels::stepped(steps.levels(), steps.values(), "potential.steps");
    } else if (!d.levels.empty()) {
        s.levels = TerraceLevels::explicitLevels(d.levels, d.values);
        s.levels.checkMinimum(potential.minimumEnergy(), "dmd.levels");
    } else if (!d.terraces.isDefault()) {
        if (!(kT > 0.0) || !std::isfinite(kT))
            throw SceneError("state.temperature: kT must be > 0 to design terraces");
        auto design = rememberedDesign(d, potential, kT);
        s.levels =
            TerraceLevels::explicitLevels(std::move(design->levels), std::move(design->values));
        s.levels.checkMinimum(potential.minimumEnergy(), "dmd.terraces");
    } else {
        if (!(kT > 0.0) || !std::isfinite(kT))
            throw SceneError("state.temperature: kT must be > 0 to set dmd.dV in units of kT");
        const std::string crowded = terraceCountProblem(potential.minimumEnergy(), d.dV, kT);
        if (!crowded.empty()) throw SceneError(crowded);
        s.levels = TerraceLevels::uniform(d.dV * kT);
        s.levels.checkMinimum(potential.minimumEnergy(), "dmd.dV", kT);
    }
    for (const auto& [name, kind] : queueKinds)
        if (d.queue == name) s.queue = kind;
    s.eager = d.invalidation == "eager";
    s.horizon = units::fromFs(d.horizon_fs);
    const MeasureSwitches measure = measureSwitches();
    s.holdScreen = measure.holdScreen;
    s.sortBodies = measure.sortDmd;
    s.resortCells = d.resort_cells;
    s.rm = interactionRange(s.levels, potential);
    if (!(s.rm > 0.0))
        throw SceneError("dmd.dV: no level bounding terrace 0 is ever reached (r_m = 0)");
    // With L < 2 r_m a pair could interact through two periodic images at once.
    if (boxLength < 2.0 * s.rm)
        throw SceneError(
            "dmd.dV: the box edge " + showNumber(boxLength) +
            " Å is shorter than twice the interaction range r_m = " + showNumber(s.rm) +
            " Å; use at least " + showNumber(std::pow(2.0 * s.rm / boxLength, 3)) +
            " times as many bodies at this density (state.n), or a larger dV");
    return s;
}

/// The settings from the scene's dmd section as it stands (read and checked anew).
template <PairPotential P>
DmdSettings readDmdSettings(const nlohmann::json& section, const P& potential, double kT,
                            double boxLength) {
    return readDmdSettings(readDmdSection(section), potential, kT, boxLength);
}

} // namespace terrace::dmd
