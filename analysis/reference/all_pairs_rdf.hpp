#pragma once
// REFERENCE, for tests and benchmarks only (not linked by the product): centre-of-mass g(r) of a
// whole run held in memory, every pair of every frame by minimum image, bins up to L/2, frames
// cut into B contiguous blocks; normalised as rdf.hpp. The oracle that the product's cell-list
// accumulator (rdf_accumulator.hpp) is tested against, count for count.
#include "analysis/rdf.hpp"
#include "core/snapshot.hpp"
#include <vector>

namespace terrace::analysis::reference {

/// g(r) over all frames (equal N and box length in all), B time blocks.
RadialDistribution radialDistribution(const std::vector<Snapshot>& frames, double binWidth,
                                      int blocks);

} // namespace terrace::analysis::reference
