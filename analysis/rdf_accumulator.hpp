#pragma once
// g(r) accumulated frame by frame as a run goes, in memory independent of the run's length and
// time O(N) per frame: pairs are found through a cell list of cells at least r_max wide (each
// body meets the bodies of its own and the 26 neighbouring cells; the 13 forward neighbours and
// the cell itself give every pair once). Boxes fewer than three cells wide are counted over all
// pairs. Normalisation and block errors are those of rdf.hpp: the frames are cut into B
// contiguous blocks of a planned number of frames, g per block, the spread of the blocks gives
// the error. With r_max = L/2, one frame every sample and the planned number of frames all seen,
// the histogram is that of every pair (reference/all_pairs_rdf.hpp), count for count.
//
// A mixture (species given) also counts one histogram per unordered pair of species (AA, AB, BB,
// …) in the same frames and blocks, from the same pairs: the pair's species look up which one it
// adds to, so a frame still costs O(N). Partial g_ab is normalised by the pairs of its own kind,
// N_a(N_a − 1)/2 like and N_a N_b unlike, so that g_ab → 1 far from a body in an ideal mixture;
// the partial histograms add up to the total, hence g = Σ_{a≤b} (P_ab / P) g_ab with
// P = N(N − 1)/2, to round-off. Memory: S(S+1)/2 times the total's
// histograms, and 8 B a body for its species (given and sorted by cell).
#include "analysis/rdf.hpp"
#include "analysis/species_labels.hpp"
#include "analysis/state_bytes.hpp"
#include "core/snapshot.hpp"
#include <cstddef>
#include <functional>
#include <vector>

namespace terrace::analysis {

/// Body b's position (Å), for b = 0 … N − 1: a frame read body by body where it lives (an engine's
/// own arrays), so that a large system's positions are not copied beside it for a g(r) frame
/// (24 B a body at the run's peak). An empty function: no frame.
using PositionOf = std::function<Vec3(int)>;

class RdfAccumulator {
public:
    /// bins of width binWidth (Å) up to rMax (Å, ≤ L/2); `plannedFrames` frames cut into
    /// `blocks` contiguous blocks (frames beyond the plan join the last block).
    /// With species (SpeciesLabels::check), the partial histograms too.
    RdfAccumulator(int bodies, double boxLength, double binWidth, double rMax, long plannedFrames,
                   int blocks, const SpeciesLabels& species = {});

    void add(const Snapshot& frame);
    /// The frame of `bodies` bodies in a box of boxLength whose positions positionOf gives (each
    /// asked for twice): the same counts as add() of a snapshot of those positions.
    void add(const PositionOf& positionOf, int bodies, double boxLength);
    long frames() const { return frames_; }
    /// g(r) of the frames added so far; blocks that received no frame do not count.
    RadialDistribution result() const;
    /// Species given at construction (0: none, no partials).
    int species() const { return species_; }
    /// Partial g_ab(r) of species a and b (either order) of the frames added so far, with its
    /// block errors; NaN throughout when the pair has no pairs (a species of one body).
    RadialDistribution partial(int a, int b) const;
    /// P_ab: the pairs of species a and b in one frame, N_a(N_a − 1)/2 or N_a N_b.
    double pairs(int a, int b) const;
    double rMax() const { return binWidth_ * bins_; }
    /// Heap memory held, bytes.
    std::size_t bytes() const;
    /// The histograms and frame counts (state_bytes.hpp), then for a mixture the partial
    /// histograms (a plain scene's state is what it was before mixtures); restore() takes them
    /// into an accumulator built with the same settings and species.
    void save(StateWriter& out) const;
    void restore(StateReader& in);

private:
    // Mixed: also the partial histograms, [pair of species][bin] flat in `partial`.
    template <bool Mixed> void countAllPairs(std::vector<double>& histogram, double* partial);
    template <bool Mixed> void countByCells(std::vector<double>& histogram, double* partial);

    int bodies_, bins_, blocks_, block_ = 0;
    int species_ = 0; // S; 0: no partials
    double length_, binWidth_;
    long plannedFrames_, frames_ = 0;
    int cellsPerSide_;                           // < 3: all pairs
    std::vector<std::vector<double>> histogram_; // [block][bin]
    std::vector<double> framesInBlock_;
    std::vector<std::vector<double>> partial_; // [block][pair · bins + bin], mixtures only
    std::vector<std::int32_t> speciesOf_;      // body i's species (scene order)
    std::vector<long> perSpecies_;             // N_a
    std::vector<int> pairOf_;                  // [a · S + b]: speciesPairIndex(a, b, S)
    // Scratch, reused frame after frame: wrapped coordinates sorted by cell, cell starts.
    std::vector<double> x_, y_, z_;
    std::vector<std::int32_t> kind_; // the sorted bodies' species (mixtures only)
    std::vector<int> cellOf_, cellStart_, fill_;
};

} // namespace terrace::analysis
