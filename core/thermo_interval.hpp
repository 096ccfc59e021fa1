#pragma once
// output.thermo_every_fs when a scene does not give it: thermo.csv is written by default, as
// LAMMPS prints thermo output unasked, at about defaultThermoRows rows over production so that a
// run's course shows at a glance whatever its length, and a file of a hundred short lines costs
// nothing beside the run. Rows come at samples (cli/sample_sink.hpp), so the interval is a whole
// number of run.sample_fs, at least one: a run of fewer than 150 samples gets a row at each.
// An explicit 0 turns the file off.
#include "core/whole_intervals.hpp"
#include <algorithm>
#include <cmath>

namespace terrace {

inline constexpr long defaultThermoRows = 100;

/// round(samples / 100) samples, at least one, in fs; samples = whole run.sample_fs in
/// run.time_ps, as the run takes them.
inline double defaultThermoEveryFs(double timePs, double sampleFs) {
    const long samples = wholeIntervals(timePs * 1000.0 / sampleFs);
    const long every = std::max(1L, std::lround(double(samples) / double(defaultThermoRows)));
    return double(every) * sampleFs;
}

} // namespace terrace
