#include "analysis/reference/all_pairs_rdf.hpp"
#include "core/box.hpp"
#include <cmath>
#include <stdexcept>

namespace terrace::analysis::reference {

namespace {

/// Adds the pair counts of one frame to the histogram (bins of width w up to w·bins).
/// The pair loop runs ~10⁸ times for a dense-rods run, so positions are wrapped into the box
/// once (PeriodicBox::wrap) and the minimum image of a difference of wrapped coordinates, which
/// lies in (−L, L), is one compare-and-shift per component: the same image as
/// PeriodicBox::minimumImage, without a rounding call per component.
void countPairs(const Snapshot& frame, double w, std::vector<double>& histogram) {
    const PeriodicBox box{frame.boxLength};
    const int n = frame.size(), bins = static_cast<int>(histogram.size());
    const double length = box.length, half = 0.5 * length;
    const double rMax2 = (w * bins) * (w * bins), inverseWidth = 1.0 / w;
    std::vector<double> x(n), y(n), z(n);
    for (int i = 0; i < n; ++i) {
        const Vec3 r = box.wrap(frame.position[i]);
        x[i] = r.x(), y[i] = r.y(), z[i] = r.z();
    }
    const auto image = [length, half](double d) { // branch-free: random signs mispredict
        return d - length * static_cast<double>((d > half) - (d < -half));
    };
    for (int i = 0; i < n; ++i) {
        for (int j = i + 1; j < n; ++j) {
            const double dx = image(x[i] - x[j]), dy = image(y[i] - y[j]), dz = image(z[i] - z[j]);
            const double r2 = dx * dx + dy * dy + dz * dz;
            if (r2 >= rMax2) continue;
            const int bin = static_cast<int>(std::sqrt(r2) * inverseWidth);
            if (bin < bins) ++histogram[bin]; // sqrt may round r just onto the last edge
        }
    }
}

} // namespace

RadialDistribution radialDistribution(const std::vector<Snapshot>& frames, double binWidth,
                                      int blocks) {
    if (frames.empty()) throw std::invalid_argument("radialDistribution: no frames");
    if (!(binWidth > 0.0)) throw std::invalid_argument("radialDistribution: bin width must be > 0");
    const int frameCount = static_cast<int>(frames.size());
    if (blocks < 1 || blocks > frameCount)
        throw std::invalid_argument("radialDistribution: need 1 ≤ blocks ≤ frames");
    const int n = frames.front().size();
    const double length = frames.front().boxLength;
    if (n < 2 || !(length > 0.0))
        throw std::invalid_argument("radialDistribution: need two bodies and a box");
    for (const auto& f : frames)
        if (f.size() != n || f.boxLength != length)
            throw std::invalid_argument("radialDistribution: N and box length must not change");

    const int bins = static_cast<int>(std::floor(0.5 * length / binWidth));
    if (bins < 1) throw std::invalid_argument("radialDistribution: bin wider than L/2");
    // Per-block histograms, then g per block and pooled.
    std::vector<std::vector<double>> histogram(blocks, std::vector<double>(bins, 0.0));
    std::vector<double> framesInBlock(blocks, 0.0);
    for (int b = 0; b < blocks; ++b) {
        const int begin = (b * frameCount) / blocks, end = ((b + 1) * frameCount) / blocks;
        for (int f = begin; f < end; ++f) {
            countPairs(frames[f], binWidth, histogram[b]);
        }
        framesInBlock[b] = end - begin;
    }

    return distributionFromHistograms(histogram, framesInBlock, n, length, binWidth);
}

} // namespace terrace::analysis::reference
