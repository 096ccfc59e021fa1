#pragma once
// Data of the paper's Fig. 2 ("Example of the adaptive root search with cubic interpolation",
// sec. 3): the project's own search (dmd/root_search.hpp, findTerraceExit) run on a real pair of
// the dense-rod scene's starting configuration, observed through the pair evaluation it calls.
//
// findTerraceExit has no trace hook; every sample it takes goes through the evaluation callback,
// so wrapping that callback records all of them. A sample later than every earlier one is a grid
// point (extremum searches and root refinement only look inside an already bracketed interval);
// the others are extremum checks and root refinement. The cubic Hermite interpolants between
// consecutive grid points and their extrema use the search's own detail::HermiteCubic (paper
// eq. 14), so the figure shows exactly what the search saw.
//
// Files written to dir (times in fs, energies in kJ/mol):
//   fig2_exact.csv    (t_fs, U) the pair's continuous U along free motion, finely sampled
//   fig2_grid.csv     (t_fs, U, dUdt) grid points in order, dUdt in kJ/mol per fs
//   fig2_cubic.csv    (t_fs, U_cubic) each interpolant, blocks separated by blank lines
//   fig2_extrema.csv  (t_fs, U_cubic) extrema of the interpolants, where grazing is looked for
//   fig2_inner.csv    (t_fs, U) samples inside bracketed intervals: extremum probes, root
//   fig2_root.csv     (t_fs, U, level) the event time the search returned, the level crossed
//   fig2_info.json    the pair, its terrace, the levels, the settings and the counts above
#include <filesystem>

namespace terrace::experiments {

/// Picks the pair of the default dense-rod start (ΔV = dVInKT kT) whose search shows the most
/// steps of the algorithm and writes the files above. Throws if no pair's search finds a root.
void writeSearchTrace(const std::filesystem::path& dir, double dVInKT = 0.5);

} // namespace terrace::experiments
