#include "analysis/dynamic_correlations.hpp"
#include "analysis/block_average.hpp"
#include "analysis/cancellation.hpp"
#include "analysis/time_correlation.hpp"
#include "core/units.hpp"
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace terrace::analysis {

namespace {

/// Relative spread of sample intervals tolerated as "equally spaced": times come back from text
/// trajectories through a fs → time-unit conversion, which costs a few ulps, never 1e-9.
constexpr double spacingTolerance = 1e-9;

/// Lag grid in ps and empty fine-block tables (o: the fine blocks) for B coarse blocks.
SampledCurve emptyCurve(const OriginBlocks& o, double dtPs, int blocks) {
    SampledCurve c;
    c.blocks = blocks;
    for (int k = 0; k <= o.maxLag; ++k)
        c.tPs.push_back(k * dtPs);
    c.fineValue.assign(o.blocks, std::vector<double>(o.maxLag + 1, 0.0));
    c.fineWeight.assign(o.blocks, std::vector<double>(o.maxLag + 1, 0.0));
    for (int f = 0; f < o.blocks; ++f)
        for (int k = 0; k <= o.maxLag; ++k)
            c.fineWeight[f][k] = o.origins(f, k);
    return c;
}

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

} // namespace

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

namespace {

/// Feeds every body's series x_i(t) = component(sample t, body i) into the correlator.
void addSeries(BlockedAutocorrelation& acf, const std::vector<Snapshot>& samples,
               const std::function<double(const Snapshot&, int)>& component, double weight) {
    const int n = samples.front().size(), t = static_cast<int>(samples.size());
    std::vector<double> x(t);
    for (int i = 0; i < n; ++i) {
        if (i % 256 == 0) throwIfCancelled();
        for (int s = 0; s < t; ++s)
            x[s] = component(samples[s], i);
        acf.add(x, weight);
    }
}

/// Per-block means over bodies and origins: sums[b][k] / (origins · N).
void setBlockMeans(SampledCurve& c, const std::vector<std::vector<double>>& sums, int n) {
    for (std::size_t f = 0; f < sums.size(); ++f)
        for (std::size_t k = 0; k < sums[f].size(); ++k) {
            const double w = c.fineWeight[f][k];
            c.fineValue[f][k] = w > 0.0 ? sums[f][k] / (w * n) : 0.0;
        }
}

/// The fine origin blocks for B coarse blocks, after checking B and the lag.
OriginBlocks checkedBlocks(const std::vector<Snapshot>& samples, int maxLag, int blocks) {
    const int t = static_cast<int>(samples.size());
    if (blocks < 2 || blocks > t / 2)
        throw std::invalid_argument("time correlations need 2 ≤ blocks ≤ samples/2 (" +
                                    std::to_string(t) + " samples, " + std::to_string(blocks) +
                                    " blocks)");
    if (maxLag < 0 || maxLag > largestLag(t, blocks))
        throw std::invalid_argument("time correlations: lag " + std::to_string(maxLag) +
                                    " beyond the largest allowed, " +
                                    std::to_string(largestLag(t, blocks)));
    return {t, maxLag, fineBlockCount(t, blocks)};
}

} // namespace

int fineBlockCount(int samples, int blocks) {
    return std::min(samples, fineBlocksPerBlock * blocks);
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

double sampleIntervalPs(const std::vector<Snapshot>& samples) {
    if (samples.size() < 2) throw std::invalid_argument("time correlations need ≥ 2 samples");
    const int n = samples.front().size();
    const double dt = samples[1].time - samples[0].time;
    if (!(dt > 0.0)) throw std::invalid_argument("samples must be increasing in time");
    for (std::size_t s = 0; s < samples.size(); ++s) {
        const auto& f = samples[s];
        if (f.size() != n || static_cast<int>(f.velocity.size()) != n)
            throw std::invalid_argument("sample " + std::to_string(s) +
                                        ": number of bodies or velocities differs");
        const double expected = samples[0].time + static_cast<double>(s) * dt;
        if (std::abs(f.time - expected) > spacingTolerance * std::max(1.0, std::abs(expected)))
            throw std::invalid_argument("samples are not equally spaced in time (sample " +
                                        std::to_string(s) + ")");
    }
    return units::toPs(dt);
}

bool axesRotate(const std::vector<Snapshot>& samples) {
    const auto& first = samples.front();
    for (const auto& f : samples) {
        if (f.axis.size() != first.axis.size()) return true;
        for (std::size_t i = 0; i < f.axis.size(); ++i)
            if (f.axis[i] != first.axis[i]) return true;
    }
    return false;
}

int largestLag(int samples, int blocks) {
    // Block 1 starts at ⌊T/B⌋; its first origin needs a partner at t0 + k ≤ T − 1.
    return samples - 1 - OriginBlocks{samples, 0, blocks}.begin(1);
}

int lagFor(double requestPs, double dtPs, int samples, int blocks) {
    const int wanted =
        requestPs > 0.0 ? static_cast<int>(std::lround(requestPs / dtPs)) : (samples - 1) / 2;
    return std::clamp(wanted, 0, largestLag(samples, blocks));
}

SampledCurve velocityAutocorrelation(const std::vector<Snapshot>& samples, int maxLag, int blocks,
                                     double* meanSquareVelocity) {
    const double dtPs = sampleIntervalPs(samples);
    const OriginBlocks o = checkedBlocks(samples, maxLag, blocks);
    BlockedAutocorrelation acf(o.samples, o.maxLag, o.blocks);
    for (int a = 0; a < 3; ++a)
        addSeries(
            acf, samples, [a](const Snapshot& f, int i) { return f.velocity[i][a]; }, 1.0);
    SampledCurve c = emptyCurve(o, dtPs, blocks);
    const int n = samples.front().size();
    setBlockMeans(c, acf.sums(), n);
    // ⟨v²⟩ pooled over all origins, then each fine block normalised by its own ⟨v²⟩.
    double sw = 0.0, swv = 0.0;
    for (int f = 0; f < o.blocks; ++f)
        sw += c.fineWeight[f][0], swv += c.fineWeight[f][0] * c.fineValue[f][0];
    if (!(swv > 0.0)) throw std::invalid_argument("VACF: all velocities are zero");
    if (meanSquareVelocity) *meanSquareVelocity = swv / sw;
    for (auto& fine : c.fineValue) {
        const double v2 = fine[0];
        if (!(v2 > 0.0))
            throw std::invalid_argument("VACF: all velocities zero over a block of samples");
        for (double& v : fine)
            v /= v2;
    }
    poolFineBlocks(c);
    return c;
}

OrientationalCorrelation orientationalAutocorrelation(const std::vector<Snapshot>& samples,
                                                      int maxLag, int blocks) {
    const double dtPs = sampleIntervalPs(samples);
    const OriginBlocks o = checkedBlocks(samples, maxLag, blocks);
    const int n = samples.front().size();
    for (const auto& f : samples)
        if (static_cast<int>(f.axis.size()) != n)
            throw std::invalid_argument("OACF: every sample needs one axis per body");
    BlockedAutocorrelation first(o.samples, o.maxLag, o.blocks),
        second(o.samples, o.maxLag, o.blocks);
    for (int a = 0; a < 3; ++a) {
        addSeries(
            first, samples, [a](const Snapshot& f, int i) { return f.axis[i][a]; }, 1.0);
        for (int b = a; b < 3; ++b) // Q_ab = s_a s_b; off-diagonal pairs appear twice in Σ_ab
            addSeries(
                second, samples,
                [a, b](const Snapshot& f, int i) { return f.axis[i][a] * f.axis[i][b]; },
                a == b ? 1.0 : 2.0);
    }
    OrientationalCorrelation out{emptyCurve(o, dtPs, blocks), emptyCurve(o, dtPs, blocks)};
    setBlockMeans(out.c1, first.sums(), n);
    setBlockMeans(out.c2, second.sums(), n);
    for (auto& block : out.c2.fineValue)
        for (double& v : block)
            v = 1.5 * v - 0.5; // P₂ of ⟨(s(0)·s(t))²⟩, linear per block
    poolFineBlocks(out.c1);
    poolFineBlocks(out.c2);
    return out;
}

SampledCurve meanSquaredDisplacement(const std::vector<Snapshot>& samples, int maxLag, int blocks) {
    const double dtPs = sampleIntervalPs(samples);
    const int n = samples.front().size(), t = static_cast<int>(samples.size());
    if (blocks < 1 || blocks > n)
        throw std::invalid_argument("MSD: need 1 ≤ blocks ≤ bodies (" + std::to_string(n) +
                                    " bodies, " + std::to_string(blocks) + " blocks)");
    if (maxLag < 0 || maxLag >= t)
        throw std::invalid_argument("MSD: lag " + std::to_string(maxLag) + " beyond the samples");
    std::vector<Vec3> centre(n, Vec3::Zero());
    for (const auto& f : samples)
        for (int i = 0; i < n; ++i)
            centre[i] += f.position[i] / t;

    // Blocks of bodies (contiguous groups), each with every time origin; see the header.
    SampledCurve c;
    c.blocks = blocks;
    for (int k = 0; k <= maxLag; ++k)
        c.tPs.push_back(k * dtPs);
    std::vector<double> series(t), prefix(t + 1);
    for (int g = 0; g < blocks; ++g) {
        const int first = (g * n) / blocks, last = ((g + 1) * n) / blocks, members = last - first;
        BlockedAutocorrelation acf(t, maxLag, 1);
        std::fill(prefix.begin(), prefix.end(), 0.0); // Σ_{t' < t} Σ_i |r_i(t') − r̄_i|²
        for (int i = first; i < last; ++i)
            for (int a = 0; a < 3; ++a) {
                if (i % 256 == 0 && a == 0) throwIfCancelled();
                for (int s = 0; s < t; ++s) {
                    series[s] = samples[s].position[i][a] - centre[i][a];
                    prefix[s + 1] += series[s] * series[s];
                }
                acf.add(series);
            }
        std::partial_sum(prefix.begin(), prefix.end(), prefix.begin());
        const auto cross = acf.sums().front();
        std::vector<double> value(maxLag + 1, 0.0), weight(maxLag + 1);
        for (int k = 0; k <= maxLag; ++k) {
            const double origins = t - k;
            const double squares = prefix[t - k] + (prefix[t] - prefix[k]);
            weight[k] = origins * members;
            // Round-off of the FFT sums leaves ±1e-15 where the displacement is exactly zero
            // (lag 0); a squared displacement is never negative.
            if (k > 0) value[k] = std::max(0.0, (squares - 2.0 * cross[k]) / weight[k]);
        }
        c.fineValue.push_back(std::move(value));
        c.fineWeight.push_back(std::move(weight));
    }
    poolFineBlocks(c);
    return c;
}

namespace {

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

} // namespace

namespace {

/// Index of the last lag at or before time t on a grid of increasing lags (0 if none).
int lastLagAtOrBefore(const std::vector<double>& tPs, double t) {
    const double tolerance = 1e-9 * tPs.back();
    int k = 0;
    while (k + 1 < static_cast<int>(tPs.size()) && tPs[k + 1] <= t + tolerance)
        ++k;
    return k;
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
    // Coarse blocks by the fine blocks' origins at the window's last lag, fixed over the window.
    std::vector<double> lastWeights;
    for (const auto& w : msd.fineWeight)
        lastWeights.push_back(w[hi]);
    const std::vector<int> group = coarseBlocks(lastWeights, msd.blocks);
    std::vector<std::vector<double>> curve(msd.blocks, std::vector<double>(hi + 1, 0.0));
    std::vector<double> weight(msd.blocks, 0.0), v, w;
    for (int k = lo; k <= hi; ++k) {
        coarseValues(msd, k, group, v, w);
        for (int b = 0; b < msd.blocks; ++b)
            curve[b][k] = v[b], weight[b] += w[b];
    }
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
    // Blocks as for the MSD fit: coarse blocks fixed by the fine blocks' origins at the last lag,
    // each block's curve integrated whole; the spread of the block integrals is the error.
    const int last = static_cast<int>(vacf.tPs.size()) - 1;
    std::vector<double> lastWeights;
    for (const auto& w : vacf.fineWeight)
        lastWeights.push_back(w[last]);
    const std::vector<int> group = coarseBlocks(lastWeights, vacf.blocks);
    std::vector<std::vector<double>> curve(vacf.blocks, std::vector<double>(last + 1, 0.0));
    std::vector<double> weight(vacf.blocks, 0.0), v, w;
    for (int k = 0; k <= last; ++k) {
        coarseValues(vacf, k, group, v, w);
        for (int b = 0; b < vacf.blocks; ++b)
            curve[b][k] = v[b], weight[b] += w[b];
    }
    std::vector<double> blockD(vacf.blocks, 0.0);
    for (int b = 0; b < vacf.blocks; ++b)
        if (weight[b] > 0.0) blockD[b] = v2 * integral(curve[b]) / 3.0;
    d.err = blockError(blockD, weight, d.coefficient);
    return d;
}

} // namespace terrace::analysis
