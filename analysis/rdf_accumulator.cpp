#include "analysis/rdf_accumulator.hpp"
#include "analysis/cancellation.hpp"
#include "core/box.hpp"
#include "core/format_text.hpp"
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace terrace::analysis {

namespace {

/// The most bins a g(r) may have.
constexpr int maxBins = 1000000;

/// First frame of block b of B over F planned frames: rdf.hpp's contiguous blocks.
long blockBegin(long b, long planned, int blocks) {
    return (b * planned) / blocks;
}

} // namespace

RdfAccumulator::RdfAccumulator(int bodies, double boxLength, double binWidth, double rMax,
                               long plannedFrames, int blocks, const SpeciesLabels& species)
    : bodies_(bodies), blocks_(blocks), length_(boxLength), binWidth_(binWidth),
      plannedFrames_(plannedFrames) {
    if (bodies < 2 || !(boxLength > 0.0))
        throw std::invalid_argument("g(r): need two bodies and a box");
    if (!(binWidth > 0.0)) throw std::invalid_argument("g(r): the bin width must be > 0");
    if (!(rMax > 0.0) || rMax > 0.5 * boxLength * (1.0 + 1e-12))
        throw std::invalid_argument("g(r): r_max must lie in (0, L/2]");
    if (plannedFrames < 1 || blocks < 1 || blocks > plannedFrames)
        throw std::invalid_argument("g(r): need 1 ≤ blocks ≤ planned frames");
    // Counted in double first: a box read from a damaged trajectory can ask for more bins than
    // an int holds, and far more than any g(r) needs (8 blocks of 10⁶ bins are 64 MB).
    const double binCount = std::floor(std::min(rMax, 0.5 * boxLength) / binWidth);
    if (!(binCount <= maxBins)) {
        throw std::invalid_argument(formatText(
            "g(r): r_max / bin width asks for %.3g bins, more than %d", binCount, maxBins));
    }
    bins_ = static_cast<int>(binCount);
    if (bins_ < 1) throw std::invalid_argument("g(r): the bin is wider than r_max");
    histogram_.assign(blocks, std::vector<double>(bins_, 0.0));
    framesInBlock_.assign(blocks, 0.0);
    // Cells beyond ~N per side would be mostly empty: no gain, only memory. (The cap is taken
    // before the cast: the box may be many r_max wide.)
    cellsPerSide_ = static_cast<int>(std::min(std::floor(boxLength / (binWidth_ * bins_)),
                                              std::max(1.0, std::floor(std::cbrt(bodies)))));
    x_.resize(bodies), y_.resize(bodies), z_.resize(bodies);
    species.check(bodies);
    if (!species.empty()) {
        species_ = species.count();
        speciesOf_ = species.ofBody;
        perSpecies_ = species.bodiesPerSpecies();
        kind_.resize(bodies);
        pairOf_.resize(std::size_t(species_) * species_);
        for (int a = 0; a < species_; ++a)
            for (int b = 0; b < species_; ++b)
                pairOf_[std::size_t(a) * species_ + b] = speciesPairIndex(a, b, species_);
        const std::size_t pairs = std::size_t(species_) * (species_ + 1) / 2;
        partial_.assign(blocks, std::vector<double>(pairs * bins_, 0.0));
    }
    if (cellsPerSide_ >= 3) {
        cellOf_.resize(bodies);
        cellStart_.resize(std::size_t(cellsPerSide_) * cellsPerSide_ * cellsPerSide_ + 1);
    }
}

void RdfAccumulator::add(const Snapshot& frame) {
    add([&frame](int b) { return frame.position[b]; }, frame.size(), frame.boxLength);
}

void RdfAccumulator::add(const PositionOf& positionOf, int bodies, double boxLength) {
    if (bodies != bodies_ || boxLength != length_)
        throw std::invalid_argument("g(r): N and box length must not change");
    while (block_ + 1 < blocks_ && frames_ >= blockBegin(block_ + 1, plannedFrames_, blocks_))
        ++block_;
    const PeriodicBox box{length_};
    const bool mixed = species_ > 0;
    double* partial = mixed ? partial_[block_].data() : nullptr;
    if (cellsPerSide_ < 3) {
        for (int i = 0; i < bodies_; ++i) {
            const Vec3 r = box.wrap(positionOf(i));
            x_[i] = r.x(), y_[i] = r.y(), z_[i] = r.z();
        }
        if (mixed) {
            std::copy(speciesOf_.begin(), speciesOf_.end(), kind_.begin());
            countAllPairs<true>(histogram_[block_], partial);
        } else {
            countAllPairs<false>(histogram_[block_], nullptr);
        }
    } else {
        // Counting sort of the wrapped positions by cell: each cell's bodies contiguous.
        const int m = cellsPerSide_;
        const double perCell = m / length_;
        std::fill(cellStart_.begin(), cellStart_.end(), 0);
        auto index = [m, perCell](double c) { return std::min(m - 1, int(c * perCell)); };
        // The wrap is done twice rather than kept (24 B a body at the run's peak).
        for (int i = 0; i < bodies_; ++i) {
            const Vec3 r = box.wrap(positionOf(i));
            cellOf_[i] = (index(r.x()) * m + index(r.y())) * m + index(r.z());
            ++cellStart_[cellOf_[i] + 1];
        }
        for (std::size_t c = 1; c < cellStart_.size(); ++c)
            cellStart_[c] += cellStart_[c - 1];
        fill_.assign(cellStart_.begin(), cellStart_.end() - 1);
        for (int i = 0; i < bodies_; ++i) {
            const Vec3 r = box.wrap(positionOf(i));
            const int k = fill_[cellOf_[i]]++;
            x_[k] = r.x(), y_[k] = r.y(), z_[k] = r.z();
            if (mixed) kind_[k] = speciesOf_[i];
        }
        if (mixed)
            countByCells<true>(histogram_[block_], partial);
        else
            countByCells<false>(histogram_[block_], nullptr);
    }
    framesInBlock_[block_] += 1.0;
    ++frames_;
}

template <bool Mixed>
void RdfAccumulator::countAllPairs(std::vector<double>& histogram, double* partial) {
    const int bins = bins_;
    [[maybe_unused]] const int species = species_;
    const double length = length_, half = 0.5 * length;
    const double rMax2 = rMax() * rMax(), inverseWidth = 1.0 / binWidth_;
    const auto image = [length, half](double d) { // branch-free: random signs mispredict
        return d - length * static_cast<double>((d > half) - (d < -half));
    };
    for (int i = 0; i < bodies_; ++i) {
        if (i % 1024 == 0) throwIfCancelled();
        for (int j = i + 1; j < bodies_; ++j) {
            const double dx = image(x_[i] - x_[j]), dy = image(y_[i] - y_[j]),
                         dz = image(z_[i] - z_[j]);
            const double r2 = dx * dx + dy * dy + dz * dz;
            if (r2 >= rMax2) continue;
            const int bin = static_cast<int>(std::sqrt(r2) * inverseWidth);
            if (bin >= bins) continue; // sqrt may round r just onto the last edge
            ++histogram[bin];
            if constexpr (Mixed) ++partial[pairOf_[kind_[i] * species + kind_[j]] * bins + bin];
        }
    }
}

template <bool Mixed>
void RdfAccumulator::countByCells(std::vector<double>& histogram, double* partial) {
    const int m = cellsPerSide_, bins = bins_;
    [[maybe_unused]] const int species = species_;
    const double length = length_, half = 0.5 * length;
    const double rMax2 = rMax() * rMax(), inverseWidth = 1.0 / binWidth_;
    const auto image = [length, half](double d) {
        return d - length * static_cast<double>((d > half) - (d < -half));
    };
    auto pairs = [&](int i, int jBegin, int jEnd) {
        const double xi = x_[i], yi = y_[i], zi = z_[i];
        // Species i's row of the pair table: one look-up a pair for its partial histogram.
        const int* row = Mixed ? pairOf_.data() + std::size_t(kind_[i]) * species : nullptr;
        for (int j = jBegin; j < jEnd; ++j) {
            const double dx = image(xi - x_[j]), dy = image(yi - y_[j]), dz = image(zi - z_[j]);
            const double r2 = dx * dx + dy * dy + dz * dz;
            if (r2 >= rMax2) continue;
            const int bin = static_cast<int>(std::sqrt(r2) * inverseWidth);
            if (bin >= bins) continue;
            ++histogram[bin];
            if constexpr (Mixed) ++partial[row[kind_[j]] * bins + bin];
        }
    };
    auto wrap = [m](int c) { return c < 0 ? c + m : (c >= m ? c - m : c); };
    for (int cx = 0; cx < m; ++cx) {
        throwIfCancelled();
        for (int cy = 0; cy < m; ++cy)
            for (int cz = 0; cz < m; ++cz) {
                const int c = (cx * m + cy) * m + cz;
                const int begin = cellStart_[c], end = cellStart_[c + 1];
                for (int i = begin; i < end; ++i)
                    pairs(i, i + 1, end);
                // The 13 neighbours lexicographically after (0, 0, 0): each pair of cells once.
                for (int dx = 0; dx <= 1; ++dx)
                    for (int dy = (dx == 0 ? 0 : -1); dy <= 1; ++dy)
                        for (int dz = (dx == 0 && dy == 0 ? 1 : -1); dz <= 1; ++dz) {
                            const int d = (wrap(cx + dx) * m + wrap(cy + dy)) * m + wrap(cz + dz);
                            for (int i = begin; i < end; ++i)
                                pairs(i, cellStart_[d], cellStart_[d + 1]);
                        }
            }
    }
}

RadialDistribution RdfAccumulator::result() const {
    if (frames_ < 1) throw std::invalid_argument("g(r): no frames");
    return distributionFromHistograms(histogram_, framesInBlock_, bodies_, length_, binWidth_);
}

double RdfAccumulator::pairs(int a, int b) const {
    if (a < 0 || b < 0 || a >= species_ || b >= species_)
        throw std::invalid_argument("g(r): no species " + std::to_string(std::max(a, b)));
    const double na = double(perSpecies_[a]), nb = double(perSpecies_[b]);
    return a == b ? 0.5 * na * (na - 1.0) : na * nb;
}

RadialDistribution RdfAccumulator::partial(int a, int b) const {
    if (frames_ < 1) throw std::invalid_argument("g(r): no frames");
    const double count = pairs(a, b); // and the species checked
    const std::size_t first = std::size_t(speciesPairIndex(a, b, species_)) * bins_;
    std::vector<std::vector<double>> histogram(blocks_);
    for (int k = 0; k < blocks_; ++k)
        histogram[k].assign(partial_[k].begin() + first, partial_[k].begin() + first + bins_);
    return distributionOfPairs(histogram, framesInBlock_, count, length_, binWidth_);
}

std::size_t RdfAccumulator::bytes() const {
    std::size_t partials = 0;
    for (const auto& h : partial_)
        partials += h.size();
    return sizeof(double) * (std::size_t(blocks_) * bins_ + partials + 3 * x_.size()) +
           sizeof(int) * (cellOf_.size() + cellStart_.size() + fill_.capacity() + pairOf_.size()) +
           sizeof(std::int32_t) * (speciesOf_.size() + kind_.size()) +
           sizeof(long) * perSpecies_.size();
}

void RdfAccumulator::save(StateWriter& out) const {
    out.value(std::int64_t(frames_)), out.value(std::int32_t(block_));
    out.nested(histogram_), out.doubles(framesInBlock_);
    if (species_ > 0) out.nested(partial_);
}

void RdfAccumulator::restore(StateReader& in) {
    const auto frames = in.value<std::int64_t>("g(r) frames");
    const auto block = in.value<std::int32_t>("g(r) block");
    if (frames < 0 || block < 0 || block >= blocks_)
        throw std::invalid_argument("analysis state: g(r) frames or block out of range");
    frames_ = long(frames), block_ = block;
    in.nested(histogram_, "g(r) histograms");
    in.doubles(framesInBlock_, "g(r) frames per block");
    if (species_ > 0) in.nested(partial_, "partial g(r) histograms");
}

} // namespace terrace::analysis
