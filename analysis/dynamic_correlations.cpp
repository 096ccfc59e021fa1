#include "analysis/dynamic_correlations.hpp"
#include "analysis/block_average.hpp"
#include "analysis/time_correlation.hpp"
#include "core/units.hpp"
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

namespace terrace::analysis {

namespace {

/// Relative spread of sample intervals tolerated as "equally spaced": times come back from text
/// trajectories through a fs → time-unit conversion, which costs a few ulps, never 1e-9.
constexpr double spacingTolerance = 1e-9;

/// Lag grid in ps and empty block tables for B blocks.
SampledCurve emptyCurve(const OriginBlocks& o, double dtPs) {
    SampledCurve c;
    for (int k = 0; k <= o.maxLag; ++k)
        c.tPs.push_back(k * dtPs);
    c.blockValue.assign(o.blocks, std::vector<double>(o.maxLag + 1, 0.0));
    c.blockWeight.assign(o.blocks, std::vector<double>(o.maxLag + 1, 0.0));
    for (int b = 0; b < o.blocks; ++b)
        for (int k = 0; k <= o.maxLag; ++k)
            c.blockWeight[b][k] = o.origins(b, k);
    return c;
}

/// Pools per-block values into value and err, lag by lag.
void poolBlocks(SampledCurve& c) {
    const int blocks = static_cast<int>(c.blockValue.size());
    std::vector<double> v(blocks), w(blocks);
    c.value.assign(c.tPs.size(), 0.0);
    c.err.assign(c.tPs.size(), 0.0);
    for (std::size_t k = 0; k < c.tPs.size(); ++k) {
        double sw = 0.0, swv = 0.0;
        for (int b = 0; b < blocks; ++b) {
            v[b] = c.blockValue[b][k], w[b] = c.blockWeight[b][k];
            sw += w[b], swv += w[b] * v[b];
        }
        c.value[k] = swv / sw;
        c.err[k] = blockError(v, w, c.value[k]);
    }
}

/// Feeds every body's series x_i(t) = component(sample t, body i) into the correlator.
void addSeries(BlockedAutocorrelation& acf, const std::vector<Snapshot>& samples,
               const std::function<double(const Snapshot&, int)>& component, double weight) {
    const int n = samples.front().size(), t = static_cast<int>(samples.size());
    std::vector<double> x(t);
    for (int i = 0; i < n; ++i) {
        for (int s = 0; s < t; ++s)
            x[s] = component(samples[s], i);
        acf.add(x, weight);
    }
}

/// Per-block means over bodies and origins: sums[b][k] / (origins · N).
void setBlockMeans(SampledCurve& c, const std::vector<std::vector<double>>& sums, int n) {
    for (std::size_t b = 0; b < sums.size(); ++b)
        for (std::size_t k = 0; k < sums[b].size(); ++k) {
            const double w = c.blockWeight[b][k];
            c.blockValue[b][k] = w > 0.0 ? sums[b][k] / (w * n) : 0.0;
        }
}

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
    return {t, maxLag, blocks};
}

} // namespace

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
    SampledCurve c = emptyCurve(o, dtPs);
    const int n = samples.front().size();
    setBlockMeans(c, acf.sums(), n);
    // ⟨v²⟩ pooled over all origins, then each block normalised by its own ⟨v²⟩.
    double sw = 0.0, swv = 0.0;
    for (int b = 0; b < o.blocks; ++b)
        sw += c.blockWeight[b][0], swv += c.blockWeight[b][0] * c.blockValue[b][0];
    if (!(swv > 0.0)) throw std::invalid_argument("VACF: all velocities are zero");
    if (meanSquareVelocity) *meanSquareVelocity = swv / sw;
    for (auto& block : c.blockValue) {
        const double v2 = block[0];
        for (double& v : block)
            v /= v2;
    }
    poolBlocks(c);
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
    OrientationalCorrelation out{emptyCurve(o, dtPs), emptyCurve(o, dtPs)};
    setBlockMeans(out.c1, first.sums(), n);
    setBlockMeans(out.c2, second.sums(), n);
    for (auto& block : out.c2.blockValue)
        for (double& v : block)
            v = 1.5 * v - 0.5; // P₂ of ⟨(s(0)·s(t))²⟩, linear per block
    poolBlocks(out.c1);
    poolBlocks(out.c2);
    return out;
}

SampledCurve meanSquaredDisplacement(const std::vector<Snapshot>& samples, int maxLag, int blocks) {
    const double dtPs = sampleIntervalPs(samples);
    const OriginBlocks o = checkedBlocks(samples, maxLag, blocks);
    const int n = samples.front().size(), t = o.samples;
    std::vector<Vec3> centre(n, Vec3::Zero());
    for (const auto& f : samples)
        for (int i = 0; i < n; ++i)
            centre[i] += f.position[i] / t;

    BlockedAutocorrelation acf(t, o.maxLag, o.blocks);
    for (int a = 0; a < 3; ++a)
        addSeries(
            acf, samples,
            [a, &centre](const Snapshot& f, int i) { return f.position[i][a] - centre[i][a]; },
            1.0);
    // prefix[t] = Σ_{t' < t} Σ_i |r_i(t') − r̄_i|²
    std::vector<double> prefix(t + 1, 0.0);
    for (int s = 0; s < t; ++s) {
        double sq = 0.0;
        for (int i = 0; i < n; ++i)
            sq += (samples[s].position[i] - centre[i]).squaredNorm();
        prefix[s + 1] = prefix[s] + sq;
    }
    SampledCurve c = emptyCurve(o, dtPs);
    const auto cross = acf.sums();
    for (int b = 0; b < o.blocks; ++b)
        for (int k = 0; k <= o.maxLag; ++k) {
            const int first = o.begin(b), count = o.origins(b, k);
            if (count == 0) continue;
            const double squares = (prefix[first + count] - prefix[first]) +
                                   (prefix[first + count + k] - prefix[first + k]);
            // Round-off can leave −1e-16 at lag 0; a squared displacement is never negative.
            c.blockValue[b][k] = std::max(0.0, (squares - 2.0 * cross[b][k]) / (count * n));
        }
    poolBlocks(c);
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

Diffusion diffusionFromMsd(const SampledCurve& msd) {
    const int maxLag = static_cast<int>(msd.tPs.size()) - 1;
    const int lo = maxLag / 4, hi = (3 * maxLag) / 4;
    Diffusion d;
    if (hi - lo < 1) {
        d.coefficient = d.err = std::numeric_limits<double>::quiet_NaN();
        return d;
    }
    d.fromPs = msd.tPs[lo];
    d.toPs = msd.tPs[hi];
    d.coefficient = slope(msd.tPs, msd.value, lo, hi) / 6.0;
    std::vector<double> blockD, weight;
    for (std::size_t b = 0; b < msd.blockValue.size(); ++b) {
        const bool whole = msd.blockWeight[b][hi] > 0.0; // every lag of the window reached
        blockD.push_back(whole ? slope(msd.tPs, msd.blockValue[b], lo, hi) / 6.0 : 0.0);
        double w = 0.0;
        for (int k = lo; k <= hi && whole; ++k)
            w += msd.blockWeight[b][k];
        weight.push_back(w);
    }
    d.err = blockError(blockD, weight, d.coefficient);
    return d;
}

} // namespace terrace::analysis
