#pragma once
// Data of the paper's Fig. 1 ("Illustration of the potential energy discretization procedure"):
// the continuous rod potential U(r, c) (core/rod_potential.hpp, paper eq. for the "Model System")
// and its terraced form (paper eq. 7)
//     V = V_min + Σ_k Θ(U − U_k) ΔV,   U_k = V_min + (k − ½) ΔV,
// in reduced units with ε = 5/2, σ = 1, ζ = 1, ΔV = 1, V_min = −2 (the figure's parameters).
// With these numbers the levels are the project's uniform levels (n − ½)ΔV (dmd/terrace_levels.hpp)
// and V is the terrace energy nΔV, floored at V_min: the paper's sum starts at k = 1 (U_1 = −3/2),
// so U = −5/2 = −ε, the minimum, is not a level there and all U < −3/2 sit on V_min.
#include <filesystem>

namespace terrace::experiments {

struct PotentialMapSettings {
    double epsilon = 2.5, sigma = 1.0, zeta = 1.0, dV = 1.0, vMin = -2.0;
    double rMin = 0.9, rMax = 2.6;   // range of r shown
    int rPoints = 121, cPoints = 61; // fine enough to show every step of the figure's terraces
};

/// Writes r,c,U,V on a grid (c from −1 to 1), one block per r separated by a blank line, the
/// layout gnuplot's splot/pm3d reads.
void writePotentialMap(const std::filesystem::path& csv, const PotentialMapSettings& s = {});

} // namespace terrace::experiments
