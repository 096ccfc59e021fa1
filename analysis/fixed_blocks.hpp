#pragma once
// A series' mean and its block error (analysis/block_average.hpp) taken sample by sample over
// blocks laid out in advance. For a planned length n and B blocks, block b holds samples
// ⌊bn/B⌋ … ⌊(b+1)n/B⌋ − 1, as blockMean lays them over a whole series: a run knows how many
// samples it will take before it starts, so the state is B sums and B counts whatever the run's
// length (a restart file keeps it, analysis/state_bytes.hpp), and a series that reaches its
// planned length gives blockMean's numbers bit for bit (the same sums, added in the same order).
//
// A series stopped short of its plan (a run interrupted for good) has its last blocks part-filled
// or empty: they count with their weights (blockRatio), where blockMean would have laid B blocks
// over the shorter series. Both are one standard error of the same mean; only the grouping
// differs.
#include "analysis/block_average.hpp"
#include "analysis/state_bytes.hpp"
#include <stdexcept>
#include <string>
#include <vector>

namespace terrace::analysis {

class FixedBlocks {
public:
    FixedBlocks() : FixedBlocks(0, 1) {}
    /// `planned` samples (≥ 0) in `blocks` blocks (≥ 1; with fewer samples, some stay empty).
    FixedBlocks(long planned, int blocks)
        : planned_(planned), sums_(std::size_t(blocks > 0 ? blocks : 0), 0.0),
          weights_(sums_.size(), 0.0) {
        if (planned < 0 || blocks < 1)
            throw std::invalid_argument("FixedBlocks: need a planned length ≥ 0 and a block");
    }

    /// The next sample; std::out_of_range beyond the planned length.
    void add(double x) {
        const long b = long(sums_.size());
        while (block_ < b && count_ >= (block_ + 1) * planned_ / b)
            ++block_;
        if (block_ == b)
            throw std::out_of_range("FixedBlocks: more than the " + std::to_string(planned_) +
                                    " samples planned");
        sums_[std::size_t(block_)] += x;
        weights_[std::size_t(block_)] += 1.0;
        ++count_;
    }

    long count() const { return count_; }
    long planned() const { return planned_; }
    int blocks() const { return int(sums_.size()); }
    /// Each block's sum and number of samples, in the order of the samples.
    const std::vector<double>& sums() const { return sums_; }
    const std::vector<double>& weights() const { return weights_; }

    /// The pooled mean and its error (NaN with fewer than two non-empty blocks); `samples` is the
    /// number of non-empty blocks. std::invalid_argument before the first sample.
    Estimate estimate() const { return blockRatio(sums_, weights_); }

    void write(StateWriter& out) const {
        out.value(planned_), out.value(count_), out.value(block_);
        out.doubles(sums_), out.doubles(weights_);
    }
    /// Into blocks of the same plan; std::invalid_argument (naming `what`) for another's state.
    void read(StateReader& in, const char* what) {
        if (in.value<long>(what) != planned_)
            throw std::invalid_argument(std::string("analysis state: ") + what +
                                        " was planned for another number of samples");
        count_ = in.value<long>(what), block_ = in.value<long>(what);
        in.doubles(sums_, what), in.doubles(weights_, what);
        if (count_ < 0 || count_ > planned_ || block_ < 0 || block_ > long(sums_.size()))
            throw std::invalid_argument(std::string("analysis state: ") + what +
                                        " counts more samples than planned (damaged)");
    }

private:
    long planned_ = 0, count_ = 0;
    long block_ = 0; // the block the last sample went to
    std::vector<double> sums_, weights_;
};

} // namespace terrace::analysis
