#pragma once
// Runtime scene choices -> compile-time (body kind, potential) pairs. This is the only place
// where the body kind and the potential are chosen at run time; everything below is a template.
#include "cli/restart.hpp"
#include "cli/run_driver.hpp"
#include "core/asymmetric_top.hpp"
#include "core/initial_state.hpp"
#include "core/linear_rotor.hpp"
#include "core/smoothed_potential.hpp"
#include "core/species_rotor.hpp"
#include "core/species_sphere.hpp"
#include "core/sphere.hpp"
#include "core/symmetric_top.hpp"
#include "dmd/section.hpp"
#include <memory>
#include <optional>

namespace terrace::cli {

/// Calls fn.template operator()<Kind>(potential) for the scene's body kind and potential.
template <class Fn> auto withBodyAndPotential(const Scene& scene, Fn&& fn) {
    if (scene.potential.kind == "lj" && !scene.species.empty())
        return fn.template operator()<SpeciesSphere>(ljMixture(scene));
    if (scene.potential.kind == "lj") return fn.template operator()<Sphere>(ljPotential(scene));
    if (scene.potential.kind == "steps" && !scene.species.empty())
        return fn.template operator()<SpeciesSphere>(stepMixture(scene));
    if (scene.potential.kind == "steps")
        return fn.template operator()<Sphere>(stepPotential(scene));
    if (scene.potential.kind == "gay-berne")
        return fn.template operator()<LinearRotor>(gayBernePotential(scene));
    if (scene.potential.kind == "sites") {
        // A linear molecule reads its axis only; any other needs its whole frame.
        const std::vector<Site> sites = sceneSites(scene);
        if (scene.body.kind == "linear")
            return fn.template operator()<LinearRotor>(
                SitePotential<AttitudeUse::Axis>::fromSites(sites));
        return fn.template operator()<AsymmetricTop>(
            SitePotential<AttitudeUse::Frame>::fromSites(sites));
    }
    if (!scene.species.empty()) return fn.template operator()<SpeciesRotor>(rodMixture(scene));
    const RodPotential rod = rodPotential(scene);
    if (scene.body.kind == "symmetric") return fn.template operator()<SymmetricTop>(rod);
    if (scene.body.kind == "asymmetric") return fn.template operator()<AsymmetricTop>(rod);
    return fn.template operator()<LinearRotor>(rod);
}

/// The model both engines simulate: the scene's potential with its smoothed cutoff
/// (core/smoothed_potential.hpp); for DMD with dmd.model = bare, the paper's setting, none; for
/// a step table none either: the table ends at its first radius.
template <PairPotential P> Smoothed<P> sceneModel(const Scene& scene, const P& bare, bool dmd) {
    const bool cut = !(dmd && dmd::readDmdSection(scene.dmd).model == "bare") && !isSteppedModel<P>;
    return Smoothed<P>{bare, cut ? sceneCutoff(scene) : SmoothedCutoff::none()};
}

/// The bodies a run starts from: the scene's initial state, or those of the restart file.
template <BodyKind K, PairPotential P>
System<K, P> startingSystem(const Scene& scene, const P& potential, const RunTarget& target) {
    if (!target.resume) return buildInitialState<K, P>(scene, potential);
    System<K, P> sys;
    sys.box.length = scene.boxLength();
    sys.body = bodyParams(scene);
    sys.potential = potential;
    sys.kT = scene.kT();
    sys.bodies = bodiesFromBinary<typename K::State>(target.resume->at("bodies"),
                                                     target.resume->at("n_bodies").get<int>());
    if constexpr (requires { sys.bodies[0].species; })
        checkSpecies(sys.bodies, static_cast<int>(scene.species.size()));
    return sys;
}

/// The engine a run starts with: from the scene's initial state, or, when continuing, from the
/// restart file's bodies and checkpoint. `make(system, checkpoint)` builds an engine (checkpoint
/// null at the start; else it may be spent). These leave `*target.resume` as they are read: kept,
/// they would sit beside the engine for the whole continued run (~130 B a rod), above the peak of
/// the run before it; the DMD engine also frees the checkpoint's pairs once it has read them.
template <class E, BodyKind K, PairPotential P, class Make>
std::unique_ptr<E> startingEngine(const Scene& scene, const P& potential, const RunTarget& target,
                                  const Make& make) {
    if (!target.resume) return make(startingSystem<K, P>(scene, potential, target), nullptr);
    auto start = startingSystem<K, P>(scene, potential, target);
    target.resume->erase("bodies");
    nlohmann::json checkpoint = std::move(target.resume->at("engine"));
    target.resume->erase("engine");
    return make(std::move(start), &checkpoint);
}

/// A restart point's engine, built as a run continued from its file builds it.
template <class Make> auto rebuildWith(const Make& make) {
    return
        [make](auto&& released) { return make(std::move(released.system), &released.checkpoint); };
}

/// Builds the engine with `make` (startingEngine), claims the output directory unless the caller
/// holds it (a continued run claims it before reading the restart file), and drives the run. The
/// directory is claimed only after the engine is built, so that a scene refused by the engine's
/// own checks leaves nothing behind.
template <class E, BodyKind K, PairPotential P, class Make>
RunOutcome buildAndDrive(const Scene& scene, const P& potential, const RunTarget& target,
                         const Make& make) {
    std::unique_ptr<E> engine = startingEngine<E, K, P>(scene, potential, target, make);
    std::optional<OutputDirectory> output;
    if (target.mode != OutputMode::Continue) output.emplace(target.dir, target.mode);
    return drive(engine, rebuildWith(make), scene, target, K::rotationalDof);
}

} // namespace terrace::cli
