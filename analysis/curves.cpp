#include "analysis/curves.hpp"
#include "analysis/block_average.hpp"
#include "core/units.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace terrace::analysis {

namespace {

/// Weighted means of the fine values of each coarse block at lag k (membership given), with
/// the coarse blocks' weights.
void coarseValues(const SampledCurve& c, int k, const std::vector<int>& group,
                  std::vector<double>& value, std::vector<double>& weight) {
    value.assign(c.blocks, 0.0);
    weight.assign(c.blocks, 0.0);
    for (std::size_t f = 0; f < group.size(); ++f) {
        if (group[f] < 0) continue;
        const double w = c.fineWeight[f][k];
        value[group[f]] += w * c.fineValue[f][k], weight[group[f]] += w;
    }
    for (int b = 0; b < c.blocks; ++b)
        if (weight[b] > 0.0) value[b] /= weight[b];
}

/// Least-squares slope of y against x over indices [lo, hi].
double slope(const std::vector<double>& x, const std::vector<double>& y, int lo, int hi) {
    double mx = 0.0, my = 0.0;
    const int m = hi - lo + 1;
    for (int k = lo; k <= hi; ++k)
        mx += x[k] / m, my += y[k] / m;
    double sxy = 0.0, sxx = 0.0;
    for (int k = lo; k <= hi; ++k)
        sxy += (x[k] - mx) * (y[k] - my), sxx += (x[k] - mx) * (x[k] - mx);
    return sxy / sxx;
}

/// Index of the last lag at or before time t on a grid of increasing lags (0 if none).
int lastLagAtOrBefore(const std::vector<double>& tPs, double t) {
    const double tolerance = 1e-9 * tPs.back();
    int k = 0;
    while (k + 1 < static_cast<int>(tPs.size()) && tPs[k + 1] <= t + tolerance)
        ++k;
    return k;
}

} // namespace

int fineBlockCount(long samples, int blocks) {
    return static_cast<int>(std::min<long>(samples, long(fineBlocksPerBlock) * blocks));
}

int fineBlockOfSample(long t, long planned, int fine) {
    if (t >= planned) return fine - 1;
    long f = (t * fine) / planned; // a first guess, then corrected exactly
    while (f > 0 && blockBegin(f, planned, fine) > t)
        --f;
    while (f + 1 < fine && blockBegin(f + 1, planned, fine) <= t)
        ++f;
    return static_cast<int>(f);
}

std::vector<int> coarseBlocks(const std::vector<double>& fineWeights, int blocks) {
    double total = 0.0;
    for (double w : fineWeights)
        total += w;
    std::vector<int> group(fineWeights.size(), -1);
    double before = 0.0;
    for (std::size_t f = 0; f < fineWeights.size(); ++f) {
        if (fineWeights[f] <= 0.0) continue;
        const double middle = (before + 0.5 * fineWeights[f]) / total;
        group[f] = std::min(blocks - 1, static_cast<int>(middle * blocks));
        before += fineWeights[f];
    }
    return group;
}

void finishOrientational(OrientationalCorrelation& c) {
    for (auto& block : c.c2.fineValue)
        for (double& v : block)
            v = 1.5 * v - 0.5;
    poolFineBlocks(c.c1);
    poolFineBlocks(c.c2);
}

void poolFineBlocks(SampledCurve& c) {
    std::vector<double> v, w, lagWeights(c.fineWeight.size());
    c.value.assign(c.tPs.size(), 0.0);
    c.err.assign(c.tPs.size(), 0.0);
    for (std::size_t k = 0; k < c.tPs.size(); ++k) {
        for (std::size_t f = 0; f < lagWeights.size(); ++f)
            lagWeights[f] = c.fineWeight[f][k];
        coarseValues(c, static_cast<int>(k), coarseBlocks(lagWeights, c.blocks), v, w);
        double sw = 0.0, swv = 0.0;
        for (int b = 0; b < c.blocks; ++b)
            sw += w[b], swv += w[b] * v[b];
        c.value[k] = swv / sw;
        c.err[k] = blockError(v, w, c.value[k]);
    }
}

int largestLag(long samples, int blocks) {
    // Block 1 starts at ⌊T/B⌋; its first origin needs a partner at t0 + k ≤ T − 1.
    return static_cast<int>(std::min<long>(samples - 1 - blockBegin(1, samples, blocks), 1L << 30));
}

int lagFor(double requestPs, double dtPs, long samples, int blocks) {
    const long wanted = requestPs > 0.0 ? std::lround(requestPs / dtPs) : (samples - 1) / 2;
    return static_cast<int>(std::clamp<long>(wanted, 0, largestLag(samples, blocks)));
}

namespace {

/// Each coarse block's curve over lags lo … hi (zero below lo) and its weight summed over them:
/// coarse blocks grouped by the fine blocks' origins at lag hi, fixed over the whole window.
struct BlockCurves {
    std::vector<std::vector<double>> curve;
    std::vector<double> weight;
};
BlockCurves blockCurves(const SampledCurve& c, int lo, int hi) {
    std::vector<double> lastWeights;
    for (const auto& w : c.fineWeight)
        lastWeights.push_back(w[hi]);
    const std::vector<int> group = coarseBlocks(lastWeights, c.blocks);
    BlockCurves out{std::vector<std::vector<double>>(c.blocks, std::vector<double>(hi + 1, 0.0)),
                    std::vector<double>(c.blocks, 0.0)};
    std::vector<double> v, w;
    for (int k = lo; k <= hi; ++k) {
        coarseValues(c, k, group, v, w);
        for (int b = 0; b < c.blocks; ++b)
            out.curve[b][k] = v[b], out.weight[b] += w[b];
    }
    return out;
}

} // namespace

Diffusion diffusionFromMsd(const SampledCurve& msd) {
    // The window [t_max/4, 3 t_max/4] by time, so that uniform and multiple-tau grids fit the same
    // span (on a uniform grid, lags ⌊K/4⌋ … ⌊3K/4⌋).
    const double tMax = msd.tPs.empty() ? 0.0 : msd.tPs.back();
    const int lo = msd.tPs.empty() ? 0 : lastLagAtOrBefore(msd.tPs, 0.25 * tMax);
    const int hi = msd.tPs.empty() ? 0 : lastLagAtOrBefore(msd.tPs, 0.75 * tMax);
    Diffusion d;
    if (hi - lo < 1) {
        d.coefficient = d.err = std::numeric_limits<double>::quiet_NaN();
        return d;
    }
    d.fromPs = msd.tPs[lo];
    d.toPs = msd.tPs[hi];
    d.coefficient = slope(msd.tPs, msd.value, lo, hi) / 6.0;
    const auto [curve, weight] = blockCurves(msd, lo, hi);
    std::vector<double> blockD(msd.blocks, 0.0);
    for (int b = 0; b < msd.blocks; ++b)
        if (weight[b] > 0.0) blockD[b] = slope(msd.tPs, curve[b], lo, hi) / 6.0;
    d.err = blockError(blockD, weight, d.coefficient);
    return d;
}

Diffusion greenKuboDiffusion(const SampledCurve& vacf, double meanSquareVelocity) {
    // D = ⟨v²⟩/3 ∫ c dt (trapezoid rule over the lag grid, truncated at the last lag), Å²/ps.
    const double v2 = meanSquareVelocity / (units::psPerTimeUnit * units::psPerTimeUnit);
    auto integral = [&vacf](const std::vector<double>& c) {
        double sum = 0.0;
        for (std::size_t k = 1; k < vacf.tPs.size(); ++k)
            sum += 0.5 * (c[k] + c[k - 1]) * (vacf.tPs[k] - vacf.tPs[k - 1]);
        return sum;
    };
    Diffusion d;
    d.coefficient = v2 * integral(vacf.value) / 3.0;
    d.toPs = vacf.tPs.empty() ? 0.0 : vacf.tPs.back();
    if (vacf.tPs.size() < 2 || vacf.fineValue.empty()) {
        d.err = std::numeric_limits<double>::quiet_NaN();
        return d;
    }
    // Blocks as for the MSD fit, each block's curve integrated whole; the spread of the block
    // integrals is the error.
    const auto [curve, weight] = blockCurves(vacf, 0, static_cast<int>(vacf.tPs.size()) - 1);
    std::vector<double> blockD(vacf.blocks, 0.0);
    for (int b = 0; b < vacf.blocks; ++b)
        if (weight[b] > 0.0) blockD[b] = v2 * integral(curve[b]) / 3.0;
    d.err = blockError(blockD, weight, d.coefficient);
    return d;
}

} // namespace terrace::analysis
