#include "analysis/reference/direct_correlations.hpp"
#include "core/units.hpp"
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace terrace::analysis::reference {

namespace {

/// Relative spread of sample intervals tolerated as "equally spaced": times come back from text
/// trajectories through a fs → time-unit conversion, which costs a few ulps, never 1e-9.
constexpr double spacingTolerance = 1e-9;

/// Origins of fine block f (of F over T samples) that have a partner k samples later.
double origins(int f, int k, int samples, int fine) {
    const long last = std::min<long>(blockBegin(f + 1, samples, fine), samples - k);
    return double(std::max<long>(0, last - blockBegin(f, samples, fine)));
}

/// Lag grid and fine-block tables (sums[f][k] to fill) for T samples, B coarse blocks.
SampledCurve emptyCurve(int samples, int maxLag, int blocks, double dtPs) {
    const int fine = fineBlockCount(samples, blocks);
    SampledCurve c;
    c.blocks = blocks;
    for (int k = 0; k <= maxLag; ++k)
        c.tPs.push_back(k * dtPs);
    c.fineValue.assign(fine, std::vector<double>(maxLag + 1, 0.0));
    c.fineWeight.assign(fine, std::vector<double>(maxLag + 1, 0.0));
    for (int f = 0; f < fine; ++f)
        for (int k = 0; k <= maxLag; ++k)
            c.fineWeight[f][k] = origins(f, k, samples, fine);
    return c;
}

/// Adds Σ_{t0 ∈ f} Σ_i term(i, t0, t0 + k) into c.fineValue[f][k], then divides by origins · N.
template <class Term>
void directSums(SampledCurve& c, const std::vector<Snapshot>& samples, Term term) {
    const int t = static_cast<int>(samples.size()), n = samples.front().size();
    const int fine = static_cast<int>(c.fineValue.size()), maxLag = int(c.tPs.size()) - 1;
    for (int f = 0; f < fine; ++f)
        for (long t0 = blockBegin(f, t, fine); t0 < blockBegin(f + 1, t, fine); ++t0)
            for (int k = 0; k <= maxLag && t0 + k < t; ++k) {
                double sum = 0.0;
                for (int i = 0; i < n; ++i)
                    sum += term(samples[t0], samples[t0 + k], i);
                c.fineValue[f][k] += sum;
            }
    for (int f = 0; f < fine; ++f)
        for (int k = 0; k <= maxLag; ++k) {
            const double w = c.fineWeight[f][k];
            c.fineValue[f][k] = w > 0.0 ? c.fineValue[f][k] / (w * n) : 0.0;
        }
}

void checkLag(const std::vector<Snapshot>& samples, int maxLag, int blocks) {
    const int t = static_cast<int>(samples.size());
    if (blocks < 2 || blocks > t / 2)
        throw std::invalid_argument("time correlations need 2 ≤ blocks ≤ samples/2");
    if (maxLag < 0 || maxLag > largestLag(t, blocks))
        throw std::invalid_argument("time correlations: lag " + std::to_string(maxLag) +
                                    " beyond the largest allowed");
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

SampledCurve velocityAutocorrelation(const std::vector<Snapshot>& samples, int maxLag, int blocks,
                                     double* meanSquareVelocity) {
    const double dtPs = sampleIntervalPs(samples);
    checkLag(samples, maxLag, blocks);
    SampledCurve c = emptyCurve(static_cast<int>(samples.size()), maxLag, blocks, dtPs);
    directSums(c, samples, [](const Snapshot& a, const Snapshot& b, int i) {
        return a.velocity[i].dot(b.velocity[i]);
    });
    // ⟨v²⟩ pooled over all origins, then each fine block normalised by its own ⟨v²⟩.
    double sw = 0.0, swv = 0.0;
    for (std::size_t f = 0; f < c.fineValue.size(); ++f)
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
    checkLag(samples, maxLag, blocks);
    const int t = static_cast<int>(samples.size()), n = samples.front().size();
    for (const auto& f : samples)
        if (static_cast<int>(f.axis.size()) != n)
            throw std::invalid_argument("OACF: every sample needs one axis per body");
    OrientationalCorrelation out{emptyCurve(t, maxLag, blocks, dtPs),
                                 emptyCurve(t, maxLag, blocks, dtPs)};
    directSums(out.c1, samples, [](const Snapshot& a, const Snapshot& b, int i) {
        return a.axis[i].dot(b.axis[i]);
    });
    directSums(out.c2, samples, [](const Snapshot& a, const Snapshot& b, int i) {
        const double c = a.axis[i].dot(b.axis[i]);
        return c * c;
    });
    finishOrientational(out);
    return out;
}

SampledCurve meanSquaredDisplacement(const std::vector<Snapshot>& samples, int maxLag, int blocks) {
    const double dtPs = sampleIntervalPs(samples);
    const int n = samples.front().size(), t = static_cast<int>(samples.size());
    if (blocks < 1 || blocks > n) throw std::invalid_argument("MSD: need 1 ≤ blocks ≤ bodies");
    if (maxLag < 0 || maxLag >= t) throw std::invalid_argument("MSD: lag beyond the samples");
    // Blocks of bodies (contiguous groups), each with every time origin (curves.hpp).
    SampledCurve c;
    c.blocks = blocks;
    for (int k = 0; k <= maxLag; ++k)
        c.tPs.push_back(k * dtPs);
    for (int g = 0; g < blocks; ++g) {
        const int first = (g * n) / blocks, last = ((g + 1) * n) / blocks;
        std::vector<double> value(maxLag + 1, 0.0), weight(maxLag + 1, 0.0);
        for (int k = 0; k <= maxLag; ++k) {
            for (int t0 = 0; t0 + k < t; ++t0)
                for (int i = first; i < last; ++i)
                    value[k] +=
                        (samples[t0 + k].position[i] - samples[t0].position[i]).squaredNorm();
            weight[k] = double(t - k) * (last - first);
            value[k] /= weight[k];
        }
        c.fineValue.push_back(std::move(value));
        c.fineWeight.push_back(std::move(weight));
    }
    poolFineBlocks(c);
    return c;
}

} // namespace terrace::analysis::reference
