#pragma once
// `terrace analyse DIR`: the correlation CSVs of a finished (or killed) run recomputed from its
// trajectory, DIR/trajectory.xyz, read frame by frame into the same accumulators a run feeds as it
// goes (analysis/run_analysis.hpp), with the run's analysis settings from DIR/scene.json (without
// it the defaults, g(r) out to L/2). Never holds the trajectory: one pass counts its whole frames
// (the blocks of the analysis are laid out over them), a second streams them in. A last frame cut
// short by a killed run is left out, with a warning.
#include <filesystem>

namespace terrace::cli {

/// Writes rdf.csv, vacf.csv, oacf.csv and msd.csv into dir and prints the analysis' summary;
/// returns the exit status. Throws on a trajectory too short or unreadable.
int analyseRun(const std::filesystem::path& dir);

} // namespace terrace::cli
