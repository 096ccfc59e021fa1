#pragma once
// Symmetric splittings of the rigid-body Liouvillian into kicks (p += F c dt, L += τ c dt: the
// potential part) and drifts (exact free motion over d dt: straight lines and the body kind's
// exact rotation, core/free_orbit.hpp), scene key smd.scheme. A step is
//     K(c_0) D(d_0) K(c_1) D(d_1) … D(d_{m-1}) K(c_m),      Σ c = Σ d = 1, c_k = c_{m-k},
// with a force evaluation after every drift; the last kick of a step and the first of the next
// use the same forces, so a step costs m force evaluations. Every scheme is symmetric (hence
// time-reversible) and symplectic, as each of its parts is.
//   verlet    m = 1: c = ½, ½; d = 1. Second order; the splitting of van Zon & Schofield (the
//             paper's SMD; Dullweber, Leimkuhler & McLachlan, J. Chem. Phys. 107, 5840 (1997)).
//   omelyan   m = 2: c = λ, 1 − 2λ, λ; d = ½, ½ with λ = 0.1931833275037836. Second order, the
//             velocity form (force, free motion, force, …) whose λ minimises the norm of the
//             third-order error terms: Omelyan, Mryglod & Folk, Phys. Rev. E 65, 056706 (2002),
//             the optimised second-order velocity-Verlet-like integrator; two force evaluations
//             a step.
//   yoshida4  m = 3: verlet composed at steps w₁ dt, w₀ dt, w₁ dt with w₁ = 1/(2 − 2^{1/3}),
//             w₀ = 1 − 2 w₁ (Yoshida, Phys. Lett. A 150, 262 (1990), the fourth-order symmetric
//             composition of a second-order one): c = w₁/2,
//             (w₁ + w₀)/2, (w₀ + w₁)/2, w₁/2; d = w₁, w₀, w₁. Fourth order; w₀ < 0 drifts
//             backwards, the price of a fourth-order symmetric composition.
#include "core/scene.hpp"
#include <cmath>
#include <string>
#include <vector>

namespace terrace::smd {

struct Splitting {
    std::vector<double> kick;  // c_0 … c_m
    std::vector<double> drift; // d_0 … d_{m-1}
    int order = 2;             // of the energy error in dt
    int forceEvaluations() const { return int(drift.size()); }
};

inline Splitting splitting(const std::string& scheme) {
    if (scheme == "verlet") return {{0.5, 0.5}, {1.0}, 2};
    if (scheme == "omelyan") {
        constexpr double lambda = 0.1931833275037836; // Omelyan, Mryglod & Folk (2002)
        return {{lambda, 1.0 - 2.0 * lambda, lambda}, {0.5, 0.5}, 2};
    }
    if (scheme == "yoshida4") {
        const double w1 = 1.0 / (2.0 - std::cbrt(2.0)), w0 = 1.0 - 2.0 * w1;
        return {{0.5 * w1, 0.5 * (w1 + w0), 0.5 * (w0 + w1), 0.5 * w1}, {w1, w0, w1}, 4};
    }
    throw SceneError("smd.scheme: must be verlet, omelyan or yoshida4, got '" + scheme + "'");
}

} // namespace terrace::smd
