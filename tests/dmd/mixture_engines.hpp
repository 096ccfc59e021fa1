#pragma once
// The Kob–Andersen mixture (tests/mixture_scene.hpp) as the DMD mixture tests run it: the
// engines' types, the scene on an fcc lattice with both engines' sections (each test adds what
// it varies), and its lattice start.
#include "core/initial_state.hpp"
#include "core/lj_mixture.hpp"
#include "core/smoothed_potential.hpp"
#include "core/species_sphere.hpp"
#include "dmd/scene_engine.hpp"
#include "smd/scene_engine.hpp"
#include "tests/mixture_scene.hpp"

namespace terrace::mixture_tests {

using Model = Smoothed<LJMixture>;
using MixtureSystem = System<SpeciesSphere, Model>;
using DmdMixture = dmd::SceneEngine<SpeciesSphere, Model>;
using SmdMixture = smd::SceneEngine<SpeciesSphere, Model>;

/// The scene document at a liquid state point well above the glass transition: fcc start, DMD on
/// the smoothed model at ΔV = dVInKT kT, SMD at 0.2 fs.
inline nlohmann::json mixtureDocument(int n, double density, double temperature, double dVInKT) {
    nlohmann::json j = kobAndersen(n, density, temperature);
    j["state"]["lattice"] = "fcc";
    j["dmd"] = {{"model", "smoothed"}, {"dV", dVInKT}};
    j["smd"] = {{"dt_fs", 0.2}};
    return j;
}

inline MixtureSystem mixtureSystem(const Scene& s) {
    return buildInitialState<SpeciesSphere>(s, Model{ljMixture(s), sceneCutoff(s)});
}

} // namespace terrace::mixture_tests
