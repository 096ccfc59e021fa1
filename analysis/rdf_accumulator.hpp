#pragma once
// g(r) accumulated frame by frame as a run goes, in memory independent of the run's length and
// time O(N) per frame: pairs are found through a cell list of cells at least r_max wide (each
// body meets the bodies of its own and the 26 neighbouring cells; the 13 forward neighbours and
// the cell itself give every pair once). Boxes fewer than three cells wide are counted over all
// pairs. Normalisation and block errors are those of rdf.hpp: the frames are cut into B
// contiguous blocks of a planned number of frames, g per block, the spread of the blocks gives
// the error. With r_max = L/2, one frame every sample and the planned number of frames all seen,
// the histogram is that of every pair (reference/all_pairs_rdf.hpp), count for count.
#include "analysis/rdf.hpp"
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
    RdfAccumulator(int bodies, double boxLength, double binWidth, double rMax, long plannedFrames,
                   int blocks);

    void add(const Snapshot& frame);
    /// The frame of `bodies` bodies in a box of boxLength whose positions positionOf gives (each
    /// asked for twice): the same counts as add() of a snapshot of those positions.
    void add(const PositionOf& positionOf, int bodies, double boxLength);
    long frames() const { return frames_; }
    /// g(r) of the frames added so far; blocks that received no frame do not count.
    RadialDistribution result() const;
    double rMax() const { return binWidth_ * bins_; }
    /// Heap memory held, bytes.
    std::size_t bytes() const;
    /// The histograms and frame counts (state_bytes.hpp); restore() takes them into an
    /// accumulator built with the same settings.
    void save(StateWriter& out) const;
    void restore(StateReader& in);

private:
    void countAllPairs(std::vector<double>& histogram);
    void countByCells(std::vector<double>& histogram);

    int bodies_, bins_, blocks_, block_ = 0;
    double length_, binWidth_;
    long plannedFrames_, frames_ = 0;
    int cellsPerSide_;                           // < 3: all pairs
    std::vector<std::vector<double>> histogram_; // [block][bin]
    std::vector<double> framesInBlock_;
    // Scratch, reused frame after frame: wrapped coordinates sorted by cell, cell starts.
    std::vector<double> x_, y_, z_;
    std::vector<int> cellOf_, cellStart_, fill_;
};

} // namespace terrace::analysis
