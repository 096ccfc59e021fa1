#include "analysis/streaming_correlations.hpp"
#include "analysis/block_average.hpp"
#include "core/units.hpp"
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace terrace::analysis {

namespace {

constexpr int rows = 9; // v, s, r: three components each

/// Relative spread of sample intervals tolerated as equally spaced (as dynamic_correlations).
constexpr double spacingTolerance = 1e-9;

} // namespace

StreamingCorrelations::StreamingCorrelations(int bodies, double sampleIntervalPs,
                                             const StreamingCorrelationPlan& plan)
    : bodies_(bodies), p_(plan.lagsPerLevel), blocks_(plan.blocks), planned_(plan.samples),
      dtPs_(sampleIntervalPs) {
    if (bodies < 1) throw std::invalid_argument("time correlations need a body");
    if (p_ < 4 || p_ % 2 != 0)
        throw std::invalid_argument("time correlations: lags per level must be even and ≥ 4");
    if (planned_ < 4 || blocks_ < 2 || blocks_ > planned_ / 2)
        throw std::invalid_argument("time correlations need 2 ≤ blocks ≤ samples/2 (" +
                                    std::to_string(planned_) + " samples, " +
                                    std::to_string(blocks_) + " blocks)");
    if (plan.maxLag < 0 || plan.maxLag >= planned_)
        throw std::invalid_argument("time correlations: the lag must lie within the run");
    if (!(sampleIntervalPs > 0.0)) throw std::invalid_argument("sample interval must be > 0");
    dtUnits_ = units::fromPs(sampleIntervalPs);
    fine_ = fineBlockCount(static_cast<int>(std::min<long>(planned_, 1L << 30)), blocks_);

    const int m = plan.followBodies > 0 ? std::min(plan.followBodies, bodies) : bodies;
    for (int k = 0; k < m; ++k)
        follow_.push_back(static_cast<int>((long(k) * bodies) / m));
    groups_ = std::min(blocks_, m);

    // The grid: level 0 lags 0 … p−1, level l lags j·2^l for j = p/2 … p−1, up to maxLag.
    while (levels_ < 40 && (long(p_ - 1) << (levels_ - 1)) < plan.maxLag)
        ++levels_;
    for (int l = 0; l < levels_; ++l) {
        firstLagOfLevel_.push_back(static_cast<int>(lag_.size()));
        for (int j = l == 0 ? 0 : p_ / 2; j < p_; ++j) {
            const long lag = long(j) << l;
            if (lag > plan.maxLag) break;
            lag_.push_back(static_cast<int>(lag)), lagLevel_.push_back(l), lagJ_.push_back(j);
        }
    }
    firstLagOfLevel_.push_back(static_cast<int>(lag_.size()));

    ring_.assign(levels_, std::vector<double>(std::size_t(p_) * rows * m, 0.0));
    slotFine_.assign(levels_, std::vector<int>(p_, 0));
    const std::size_t g = lag_.size();
    vv_.assign(fine_, std::vector<double>(g, 0.0));
    ss_ = s2_ = origins_ = vv_;
    msd_.assign(groups_, std::vector<double>(g, 0.0));
    msdOrigins_.assign(g, 0.0);
}

int StreamingCorrelations::fineBlockOf(long t) const {
    // Fine block f holds origins [⌊fT/F⌋, ⌊(f+1)T/F⌋) (OriginBlocks); beyond the plan: the last.
    if (t >= planned_) return fine_ - 1;
    long f = (t * fine_) / planned_; // a first guess, then corrected exactly
    while (f > 0 && (f * planned_) / fine_ > t)
        --f;
    while (f + 1 < fine_ && ((f + 1) * planned_) / fine_ <= t)
        ++f;
    return static_cast<int>(f);
}

void StreamingCorrelations::add(const Snapshot& frame) {
    if (frame.size() != bodies_ || static_cast<int>(frame.velocity.size()) != bodies_ ||
        static_cast<int>(frame.axis.size()) != bodies_)
        throw std::invalid_argument("sample " + std::to_string(seen_) +
                                    ": number of bodies, velocities or axes differs");
    record(frame, follow_.data());
}

void StreamingCorrelations::addFollowed(const Snapshot& followed) {
    const int m = this->followed();
    if (followed.size() != m || static_cast<int>(followed.velocity.size()) != m ||
        static_cast<int>(followed.axis.size()) != m)
        throw std::invalid_argument("sample " + std::to_string(seen_) +
                                    ": not the followed bodies' positions, velocities and axes");
    record(followed, nullptr);
}

void StreamingCorrelations::record(const Snapshot& frame, const int* index) {
    const int m = followed();
    auto entry = [index](int k) { return index ? index[k] : k; };
    if (seen_ == 0) {
        firstTime_ = frame.time;
        for (int k = 0; k < m; ++k)
            firstAxis_.push_back(frame.axis[entry(k)]);
    } else {
        const double expected = firstTime_ + double(seen_) * dtUnits_;
        if (std::abs(frame.time - expected) >
            spacingTolerance * std::max({1.0, std::abs(expected), dtUnits_ * double(seen_)}))
            throw std::invalid_argument("samples are not equally spaced in time (sample " +
                                        std::to_string(seen_) + ")");
    }
    if (!rotating_)
        for (int k = 0; k < m && !rotating_; ++k)
            rotating_ = frame.axis[entry(k)] != firstAxis_[k];

    const long t = seen_;
    const int fine = fineBlockOf(t);
    for (int l = 0; l < levels_; ++l) {
        if (t & ((1L << l) - 1)) break; // level l keeps every 2^l-th sample only
        const long index = t >> l;
        const int slot = static_cast<int>(index % p_);
        double* row = ring_[l].data() + std::size_t(slot) * rows * m;
        for (int k = 0; k < m; ++k) {
            const int i = entry(k);
            for (int a = 0; a < 3; ++a) {
                row[(0 + a) * m + k] = frame.velocity[i][a];
                row[(3 + a) * m + k] = frame.axis[i][a];
                row[(6 + a) * m + k] = frame.position[i][a];
            }
        }
        slotFine_[l][slot] = fine;
        for (int g = firstLagOfLevel_[l]; g < firstLagOfLevel_[l + 1]; ++g) {
            const long origin = index - lagJ_[g];
            if (origin < 0) break;
            correlate(l, slot, static_cast<int>(origin % p_), g);
        }
    }
    ++seen_;
}

void StreamingCorrelations::correlate(int level, int slot, int originSlot, int g) {
    const int m = followed();
    const double* now = ring_[level].data() + std::size_t(slot) * rows * m;
    const double* then = ring_[level].data() + std::size_t(originSlot) * rows * m;
    double vv = 0.0, ss = 0.0, s2 = 0.0;
    for (int k = 0; k < m; ++k) {
        vv += then[k] * now[k] + then[m + k] * now[m + k] + then[2 * m + k] * now[2 * m + k];
        const double c = then[3 * m + k] * now[3 * m + k] + then[4 * m + k] * now[4 * m + k] +
                         then[5 * m + k] * now[5 * m + k];
        ss += c, s2 += c * c;
    }
    const int f = slotFine_[level][originSlot];
    vv_[f][g] += vv, ss_[f][g] += ss, s2_[f][g] += s2, origins_[f][g] += 1.0;
    for (int b = 0; b < groups_; ++b) {
        const int first = (b * m) / groups_, last = ((b + 1) * m) / groups_;
        double d2 = 0.0;
        for (int k = first; k < last; ++k) {
            const double dx = now[6 * m + k] - then[6 * m + k],
                         dy = now[7 * m + k] - then[7 * m + k],
                         dz = now[8 * m + k] - then[8 * m + k];
            d2 += dx * dx + dy * dy + dz * dz;
        }
        msd_[b][g] += d2;
    }
    msdOrigins_[g] += 1.0;
}

int StreamingCorrelations::usedLags() const {
    int used = 0;
    for (std::size_t g = 0; g < lag_.size(); ++g)
        if (msdOrigins_[g] > 0.0) used = static_cast<int>(g) + 1;
    return used;
}

SampledCurve StreamingCorrelations::emptyCurve() const {
    SampledCurve c;
    c.blocks = blocks_;
    for (int g = 0; g < usedLags(); ++g)
        c.tPs.push_back(lag_[g] * dtPs_);
    return c;
}

namespace {

/// fineValue = sums / (origins · M) per fine block and lag, weights the origins.
void setFine(SampledCurve& c, const std::vector<std::vector<double>>& sums,
             const std::vector<std::vector<double>>& origins, int followed) {
    const std::size_t lags = c.tPs.size();
    for (std::size_t f = 0; f < sums.size(); ++f) {
        std::vector<double> value(lags, 0.0), weight(lags, 0.0);
        for (std::size_t g = 0; g < lags; ++g) {
            weight[g] = origins[f][g];
            value[g] = weight[g] > 0.0 ? sums[f][g] / (weight[g] * followed) : 0.0;
        }
        c.fineValue.push_back(std::move(value));
        c.fineWeight.push_back(std::move(weight));
    }
}

} // namespace

SampledCurve StreamingCorrelations::velocity(double* meanSquareVelocity) const {
    if (seen_ < 2) throw std::invalid_argument("time correlations need ≥ 2 samples");
    SampledCurve c = emptyCurve();
    setFine(c, vv_, origins_, followed());
    // ⟨v²⟩ pooled over all origins, then each fine block normalised by its own ⟨v²⟩.
    double sw = 0.0, swv = 0.0;
    for (std::size_t f = 0; f < c.fineValue.size(); ++f)
        sw += c.fineWeight[f][0], swv += c.fineWeight[f][0] * c.fineValue[f][0];
    if (!(swv > 0.0)) throw std::invalid_argument("VACF: all velocities are zero");
    if (meanSquareVelocity) *meanSquareVelocity = swv / sw;
    for (std::size_t f = 0; f < c.fineValue.size(); ++f) {
        if (c.fineWeight[f][0] <= 0.0) continue; // a block the run did not reach
        const double v2 = c.fineValue[f][0];
        if (!(v2 > 0.0))
            throw std::invalid_argument("VACF: all velocities zero over a block of samples");
        for (double& v : c.fineValue[f])
            v /= v2;
    }
    poolFineBlocks(c);
    return c;
}

OrientationalCorrelation StreamingCorrelations::orientation() const {
    if (seen_ < 2) throw std::invalid_argument("time correlations need ≥ 2 samples");
    OrientationalCorrelation out{emptyCurve(), emptyCurve()};
    setFine(out.c1, ss_, origins_, followed());
    setFine(out.c2, s2_, origins_, followed());
    for (auto& block : out.c2.fineValue)
        for (double& v : block)
            v = 1.5 * v - 0.5; // P₂ of ⟨(s(0)·s(t))²⟩, linear per block
    poolFineBlocks(out.c1);
    poolFineBlocks(out.c2);
    return out;
}

SampledCurve StreamingCorrelations::displacement() const {
    if (seen_ < 2) throw std::invalid_argument("time correlations need ≥ 2 samples");
    SampledCurve c = emptyCurve();
    c.blocks = groups_;
    const int m = followed();
    for (int b = 0; b < groups_; ++b) {
        const double members = ((b + 1) * m) / groups_ - (b * m) / groups_;
        std::vector<double> value(c.tPs.size(), 0.0), weight(c.tPs.size(), 0.0);
        for (std::size_t g = 0; g < c.tPs.size(); ++g) {
            weight[g] = msdOrigins_[g] * members;
            value[g] = weight[g] > 0.0 ? msd_[b][g] / weight[g] : 0.0;
        }
        c.fineValue.push_back(std::move(value));
        c.fineWeight.push_back(std::move(weight));
    }
    poolFineBlocks(c);
    return c;
}

std::size_t StreamingCorrelations::bytes() const {
    std::size_t b = 0;
    for (const auto& r : ring_)
        b += r.size() * sizeof(double);
    b += (4 * std::size_t(fine_) + groups_ + 1) * lag_.size() * sizeof(double);
    return b + follow_.size() * (sizeof(int) + sizeof(Vec3));
}

} // namespace terrace::analysis
