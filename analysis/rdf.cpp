#include "analysis/rdf.hpp"
#include "analysis/block_average.hpp"
#include <limits>
#include <numbers>

namespace terrace::analysis {

namespace {

double shellVolume(double lo, double hi) {
    return 4.0 / 3.0 * std::numbers::pi * (hi * hi * hi - lo * lo * lo);
}

} // namespace

RadialDistribution distributionFromHistograms(const std::vector<std::vector<double>>& histogram,
                                              const std::vector<double>& framesInBlock, int bodies,
                                              double length, double binWidth) {
    return distributionOfPairs(histogram, framesInBlock, 0.5 * bodies * (bodies - 1.0), length,
                               binWidth);
}

RadialDistribution distributionOfPairs(const std::vector<std::vector<double>>& histogram,
                                       const std::vector<double>& framesInBlock, double pairs,
                                       double length, double binWidth) {
    const double volume = length * length * length;
    const std::size_t blocks = histogram.size(), bins = histogram.front().size();
    RadialDistribution rdf;
    rdf.binWidth = binWidth;
    std::vector<double> sums(blocks);
    for (std::size_t k = 0; k < bins; ++k) {
        const double ideal = pairs * shellVolume(k * binWidth, (k + 1) * binWidth) / volume;
        if (!(pairs > 0.0)) { // no pair of this kind: nothing to normalise by
            const double nan = std::numeric_limits<double>::quiet_NaN();
            rdf.r.push_back((k + 0.5) * binWidth), rdf.g.push_back(nan), rdf.err.push_back(nan);
            continue;
        }
        for (std::size_t b = 0; b < blocks; ++b)
            sums[b] = histogram[b][k] / ideal;
        const Estimate e = blockRatio(sums, framesInBlock);
        rdf.r.push_back((k + 0.5) * binWidth);
        rdf.g.push_back(e.mean);
        rdf.err.push_back(e.err);
    }
    return rdf;
}

} // namespace terrace::analysis
