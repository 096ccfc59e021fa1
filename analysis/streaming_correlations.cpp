#include "analysis/streaming_correlations.hpp"
#include "analysis/block_average.hpp"
#include "analysis/windowed_correlation.hpp"
#include "core/units.hpp"
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace terrace::analysis {

namespace {

constexpr int rows = 9; // v, s, r: three components each

/// Relative spread of sample intervals tolerated as "equally spaced": times come back from text
/// trajectories through a fs → time-unit conversion, which costs a few ulps, never 1e-9.
constexpr double spacingTolerance = 1e-9;

} // namespace

std::vector<int> followedPerSpecies(const std::vector<std::int32_t>& speciesOf, int species,
                                    int followBodies) {
    const long n = static_cast<long>(speciesOf.size());
    const long wanted = followBodies > 0 ? std::min<long>(followBodies, n) : n;
    std::vector<std::vector<int>> members(static_cast<std::size_t>(species));
    for (long i = 0; i < n; ++i)
        members.at(static_cast<std::size_t>(speciesOf[i])).push_back(static_cast<int>(i));
    std::vector<int> follow;
    for (const auto& bodies : members) {
        const long na = static_cast<long>(bodies.size());
        if (na == 0) continue;
        // The species' share of the followed bodies, rounded down, but never none.
        const long ma = std::clamp((wanted * na) / n, 1L, na);
        for (long k = 0; k < ma; ++k)
            follow.push_back(bodies[static_cast<std::size_t>((k * na) / ma)]);
    }
    std::sort(follow.begin(), follow.end());
    return follow;
}

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
    fine_ = fineBlockCount(planned_, blocks_);

    if (!plan.follow.empty()) {
        follow_ = plan.follow;
        for (std::size_t k = 0; k < follow_.size(); ++k)
            if (follow_[k] < 0 || follow_[k] >= bodies || (k > 0 && follow_[k] <= follow_[k - 1]))
                throw std::invalid_argument("time correlations: the followed bodies must be "
                                            "ascending, distinct and among the bodies");
    } else {
        const int all = plan.followBodies > 0 ? std::min(plan.followBodies, bodies) : bodies;
        for (int k = 0; k < all; ++k)
            follow_.push_back(static_cast<int>((long(k) * bodies) / all));
    }
    const int m = static_cast<int>(follow_.size());
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

    // Level 0 (lags 0 … p − 1, every origin) is summed by FFT over windows of W = p samples:
    // exactly the lags that every origin reaches on this grid, so the FFT changes no lag and no
    // set of origins, and the curves are those of the direct sums within round-off, while the
    // coarser levels go on as before. A wider window would move lags of the coarser levels onto
    // every origin (other values, not round-off), for memory 2W · 9 doubles a followed body,
    // and cost more per sample than the decimated levels it would replace.
    windowed_ =
        std::make_unique<WindowedCorrelation>(m, p_, firstLagOfLevel_[1], planned_, fine_, groups_);
    ring_.assign(levels_, std::vector<double>());
    for (int l = 1; l < levels_; ++l)
        ring_[l].assign(std::size_t(p_) * rows * m, 0.0);
    slotFine_.assign(levels_, std::vector<int>(p_, 0));
    const std::size_t g = lag_.size();
    tau_.vv.assign(fine_, std::vector<double>(g, 0.0));
    tau_.ss = tau_.s2 = tau_.origins = tau_.vv;
    tau_.msd.assign(groups_, std::vector<double>(g, 0.0));
    tau_.msdOrigins.assign(g, 0.0);
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
    const int fine = fineBlockOfSample(t, planned_, fine_);
    windowed_->add(frame, index);
    for (int l = 1; l < levels_; ++l) {
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
    tau_.vv[f][g] += vv, tau_.ss[f][g] += ss, tau_.s2[f][g] += s2, tau_.origins[f][g] += 1.0;
    for (int b = 0; b < groups_; ++b) {
        const int first = (b * m) / groups_, last = ((b + 1) * m) / groups_;
        double d2 = 0.0;
        for (int k = first; k < last; ++k) {
            const double dx = now[6 * m + k] - then[6 * m + k],
                         dy = now[7 * m + k] - then[7 * m + k],
                         dz = now[8 * m + k] - then[8 * m + k];
            d2 += dx * dx + dy * dy + dz * dz;
        }
        tau_.msd[b][g] += d2;
    }
    tau_.msdOrigins[g] += 1.0;
}

LagSums StreamingCorrelations::sums() const {
    LagSums all = tau_;
    const LagSums linear = windowed_->sums();
    const std::size_t lags = linear.msdOrigins.size(); // the grid's first lags, 0 … p − 1
    for (std::size_t f = 0; f < all.vv.size(); ++f)
        for (std::size_t g = 0; g < lags; ++g) {
            all.vv[f][g] = linear.vv[f][g], all.ss[f][g] = linear.ss[f][g];
            all.s2[f][g] = linear.s2[f][g], all.origins[f][g] = linear.origins[f][g];
        }
    for (std::size_t b = 0; b < all.msd.size(); ++b)
        for (std::size_t g = 0; g < lags; ++g)
            all.msd[b][g] = linear.msd[b][g];
    for (std::size_t g = 0; g < lags; ++g)
        all.msdOrigins[g] = linear.msdOrigins[g];
    return all;
}

SampledCurve StreamingCorrelations::emptyCurve(const LagSums& sums) const {
    SampledCurve c;
    c.blocks = blocks_;
    for (std::size_t g = 0; g < lag_.size() && sums.msdOrigins[g] > 0.0; ++g)
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
    const LagSums sums = this->sums();
    SampledCurve c = emptyCurve(sums);
    setFine(c, sums.vv, sums.origins, followed());
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
    const LagSums sums = this->sums();
    OrientationalCorrelation out{emptyCurve(sums), emptyCurve(sums)};
    setFine(out.c1, sums.ss, sums.origins, followed());
    setFine(out.c2, sums.s2, sums.origins, followed());
    finishOrientational(out);
    return out;
}

SampledCurve StreamingCorrelations::displacement() const {
    if (seen_ < 2) throw std::invalid_argument("time correlations need ≥ 2 samples");
    const LagSums sums = this->sums();
    SampledCurve c = emptyCurve(sums);
    c.blocks = groups_;
    const int m = followed();
    for (int b = 0; b < groups_; ++b) {
        const double members = ((b + 1) * m) / groups_ - (b * m) / groups_;
        std::vector<double> value(c.tPs.size(), 0.0), weight(c.tPs.size(), 0.0);
        for (std::size_t g = 0; g < c.tPs.size(); ++g) {
            weight[g] = sums.msdOrigins[g] * members;
            // A squared displacement is never negative; FFT round-off may leave −1e-16 where
            // bodies stand still.
            value[g] = weight[g] > 0.0 ? std::max(0.0, sums.msd[b][g] / weight[g]) : 0.0;
        }
        c.fineValue.push_back(std::move(value));
        c.fineWeight.push_back(std::move(weight));
    }
    poolFineBlocks(c);
    return c;
}

std::size_t StreamingCorrelations::bytes() const {
    std::size_t b = windowed_->bytes();
    for (const auto& r : ring_)
        b += r.size() * sizeof(double);
    b += (4 * std::size_t(fine_) + groups_ + 1) * lag_.size() * sizeof(double);
    return b + follow_.size() * (sizeof(int) + sizeof(Vec3));
}

void StreamingCorrelations::save(StateWriter& out) const {
    out.value(std::int64_t(seen_)), out.value(std::uint8_t(rotating_)), out.value(firstTime_);
    // The first sample's axes, zeros before it: the state's size does not change with it.
    std::vector<double> axes(3 * std::size_t(followed()), 0.0);
    for (std::size_t k = 0; k < firstAxis_.size(); ++k)
        for (int a = 0; a < 3; ++a)
            axes[3 * k + a] = firstAxis_[k][a];
    out.doubles(axes);
    for (int l = 1; l < levels_; ++l)
        out.doubles(ring_[l]), out.raw(slotFine_[l]);
    for (const auto* sums : {&tau_.vv, &tau_.ss, &tau_.s2, &tau_.origins, &tau_.msd})
        out.nested(*sums);
    out.doubles(tau_.msdOrigins);
    windowed_->save(out);
}

void StreamingCorrelations::restore(StateReader& in) {
    const auto seen = in.value<std::int64_t>("time correlations' samples");
    const auto rotating = in.value<std::uint8_t>("time correlations' rotation flag");
    firstTime_ = in.value<double>("time correlations' first time");
    if (seen < 0 || rotating > 1)
        throw std::invalid_argument("analysis state: the time correlations' samples or rotation "
                                    "flag out of range");
    seen_ = long(seen), rotating_ = rotating == 1;
    std::vector<double> first(3 * std::size_t(followed()));
    in.doubles(first, "time correlations' first axes");
    firstAxis_.clear();
    if (seen_ > 0) // else the first sample sets them
        for (int k = 0; k < followed(); ++k)
            firstAxis_.emplace_back(first[3 * k], first[3 * k + 1], first[3 * k + 2]);
    for (int l = 1; l < levels_; ++l) {
        in.doubles(ring_[l], "multiple-tau ring");
        in.raw(slotFine_[l], "multiple-tau ring's blocks");
        for (const int f : slotFine_[l])
            if (f < 0 || f >= fine_)
                throw std::invalid_argument("analysis state: a ring slot's block out of range");
    }
    in.nested(tau_.vv, "multiple-tau VACF sums");
    in.nested(tau_.ss, "multiple-tau OACF sums");
    in.nested(tau_.s2, "multiple-tau P2 sums");
    in.nested(tau_.origins, "multiple-tau origin counts");
    in.nested(tau_.msd, "multiple-tau MSD sums");
    in.doubles(tau_.msdOrigins, "multiple-tau MSD origin counts");
    windowed_->restore(in);
    if (windowed_->samples() != seen_)
        throw std::invalid_argument("analysis state: the FFT correlation's samples are not the "
                                    "time correlations'");
}

} // namespace terrace::analysis
