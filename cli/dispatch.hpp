#pragma once
// Runtime scene choices -> compile-time (body kind, potential) pairs. This is the only place
// where the body kind and the potential are chosen at run time; everything below is a template.
#include "core/asymmetric_top.hpp"
#include "core/initial_state.hpp"
#include "core/linear_rotor.hpp"
#include "core/sphere.hpp"
#include "core/symmetric_top.hpp"

namespace terrace::cli {

/// Calls fn.template operator()<Kind>(potential) for the scene's body kind and potential.
template <class Fn> auto withBodyAndPotential(const Scene& scene, Fn&& fn) {
    if (scene.potential.kind == "lj") return fn.template operator()<Sphere>(ljPotential(scene));
    const RodPotential rod = rodPotential(scene);
    if (scene.body.kind == "symmetric") return fn.template operator()<SymmetricTop>(rod);
    if (scene.body.kind == "asymmetric") return fn.template operator()<AsymmetricTop>(rod);
    return fn.template operator()<LinearRotor>(rod);
}

} // namespace terrace::cli
