#pragma once
// Centre-of-mass radial distribution function, normalised by the ideal-gas shell count:
//
//     g(r) = h(r) / [ F · N(N−1)/2 · V_shell(r) / V ],   V_shell = 4π/3 (r_hi³ − r_lo³),
//
// h(r) = number of distinct pairs (minimum image) with separation in the bin [r_lo, r_hi), summed
// over F frames. N(N−1)/2 rather than N²/2 makes uniformly random points give g = 1 exactly in
// expectation at any N (no 1 − 1/N bias). Bins run up to L/2, where a sphere round a body still
// lies inside the minimum-image cell, so every shell is counted completely. Lengths in Å.
// The pairs are counted as a run goes by rdf_accumulator.hpp (cell list out to r_max), in tests
// also by reference/all_pairs_rdf.hpp (every pair).
// (Allen and Tildesley, Computer Simulation of Liquids, 2nd ed., sec. 8.2.)
//
// Error bars: the frames are cut into B contiguous blocks of time; each block gives its own g(r),
// and the error is the standard error of the block values (block_average.hpp).
#include <vector>

namespace terrace::analysis {

struct RadialDistribution {
    double binWidth = 0.0;      // Å
    std::vector<double> r;      // bin centres, Å
    std::vector<double> g, err; // g(r) and one standard error
};

/// g(r) from per-block pair histograms (h[b][k] over framesInBlock[b] frames of N bodies in a box
/// of edge length Å): the normalisation and block errors above, shared by rdf_accumulator.hpp.
RadialDistribution distributionFromHistograms(const std::vector<std::vector<double>>& histogram,
                                              const std::vector<double>& framesInBlock, int bodies,
                                              double length, double binWidth);
/// The same for histograms of `pairs` pairs a frame (a partial g(r): rdf_accumulator.hpp); NaN
/// throughout when pairs is 0.
RadialDistribution distributionOfPairs(const std::vector<std::vector<double>>& histogram,
                                       const std::vector<double>& framesInBlock, double pairs,
                                       double length, double binWidth);

} // namespace terrace::analysis
