#include "analysis/tradeoff_stats.hpp"
#include <algorithm>
#include <boost/math/distributions/binomial.hpp>
#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <boost/math/tools/minima.hpp>
#include <limits>
#include <stdexcept>
#include <vector>

namespace terrace::analysis {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();

/// The degrees of freedom of a sum of two errors (difference, above); NaN if either is.
double smallerDof(double a, double b) {
    return std::isnan(a) || std::isnan(b) ? nan : std::min(a, b);
}

} // namespace

Estimate replicaMean(std::span<const double> values) {
    const int n = static_cast<int>(values.size());
    Estimate e{nan, nan, 0.0, n};
    if (n == 0) return e;
    double sum = 0.0;
    for (double v : values)
        sum += v;
    e.mean = sum / n;
    if (n < 2) return e;
    double ss = 0.0;
    for (double v : values)
        ss += (v - e.mean) * (v - e.mean);
    e.err = std::sqrt(ss / (n - 1) / n);
    e.dof = n - 1;
    return e;
}

Estimate combineReplicaEstimates(std::span<const Estimate> perReplica) {
    const int n = static_cast<int>(perReplica.size());
    std::vector<double> values;
    values.reserve(perReplica.size());
    double sumVar = 0.0, sumVarSquaredPerDof = 0.0;
    bool errorsKnown = n > 0;
    for (const Estimate& r : perReplica) {
        values.push_back(r.mean);
        if (!(std::isfinite(r.err) && r.err >= 0.0)) errorsKnown = false;
        const double var = r.err * r.err;
        sumVar += var;
        if (!std::isinf(r.dof)) sumVarSquaredPerDof += var * var / r.dof;
    }
    const Estimate scatter = replicaMean(values);
    if (!errorsKnown) return scatter;
    const double propagated = std::sqrt(sumVar) / n;
    if (propagated > scatter.err || std::isnan(scatter.err)) {
        const double dof = sumVarSquaredPerDof > 0.0 ? sumVar * sumVar / sumVarSquaredPerDof : inf;
        return {scatter.mean, propagated, dof, n};
    }
    return scatter;
}

Estimate pooledReplicaEstimate(std::span<const Estimate> perReplica, double level) {
    const int n = static_cast<int>(perReplica.size());
    std::vector<double> values;
    double sumVar = 0.0, sumVarSquaredPerDof = 0.0;
    for (const Estimate& r : perReplica) {
        values.push_back(r.mean);
        if (!(std::isfinite(r.err) && r.err > 0.0 && r.dof > 0.0)) return replicaMean(values);
        const double var = r.err * r.err;
        sumVar += var;
        if (!std::isinf(r.dof)) sumVarSquaredPerDof += var * var / r.dof;
    }
    const Estimate scatter = replicaMean(values);
    if (n == 0) return scatter;
    const double propagated = std::sqrt(sumVar) / n;
    const double dof = sumVarSquaredPerDof > 0.0 ? sumVar * sumVar / sumVarSquaredPerDof : inf;
    const Estimate blocks{scatter.mean, propagated, dof, n};
    if (n < 2) return blocks;
    const double ratio = scatter.err * scatter.err / (propagated * propagated);
    const boost::math::fisher_f_distribution<double> f(n - 1, std::min(dof, 1e6));
    return ratio > boost::math::quantile(f, level) ? scatter : blocks;
}

Estimate difference(Estimate a, Estimate b) {
    return {a.mean - b.mean, std::hypot(a.err, b.err), smallerDof(a.dof, b.dof), a.samples};
}

double absoluteTolerance(Tolerance tolerance, double reference, double floor) {
    return tolerance.relative ? tolerance.value * std::max(std::abs(reference), floor)
                              : tolerance.value;
}

double studentMultiplier(double z, double dof) {
    if (std::isnan(z) || std::isnan(dof) || dof <= 0.0) return nan;
    if (std::isinf(dof)) return z;
    const double tail = 0.5 * std::erfc(z / std::sqrt(2.0)); // Φ(−z)
    if (tail <= 0.0) return inf;
    if (tail >= 1.0) return -inf;
    const boost::math::students_t_distribution<double> t(dof);
    return boost::math::quantile(boost::math::complement(t, tail));
}

BiasDecision decideBias(Estimate bias, double tolerance, double z) {
    BiasDecision d{bias, tolerance, z, studentMultiplier(z, bias.dof), Decision::Unresolved};
    const double size = std::abs(bias.mean), margin = d.multiplier * bias.err;
    if (size + margin <= tolerance)
        d.decision = Decision::Within;
    else if (size - margin >= tolerance)
        d.decision = Decision::Outside;
    return d;
}

double sequentialZ(double alpha, int looks) {
    if (!(alpha > 0.0 && alpha < 1.0) || looks < 1)
        throw std::invalid_argument("sequentialZ: need 0 < alpha < 1 and at least one look");
    const boost::math::normal_distribution<double> normal;
    return boost::math::quantile(boost::math::complement(normal, alpha / (2.0 * looks)));
}

std::vector<int> lookSchedule(int first, int maxReplicas) {
    if (first < 1 || maxReplicas < first)
        throw std::invalid_argument("lookSchedule: need 1 <= first <= maxReplicas");
    std::vector<int> counts;
    for (long n = first; n < maxReplicas; n *= 2)
        counts.push_back(static_cast<int>(n));
    counts.push_back(maxReplicas);
    return counts;
}

int nextLook(std::span<const int> schedule, int current, int projected) {
    if (schedule.empty()) throw std::invalid_argument("nextLook: empty schedule");
    for (int n : schedule)
        if (n > current && n >= projected) return n;
    return schedule.back();
}

int replicasToResolve(Estimate candidate, Estimate reference, double tolerance, double z,
                      int maxReplicas) {
    const int current = candidate.samples;
    if (current < 2 || !std::isfinite(candidate.err))
        return std::max(current, std::min(2, maxReplicas));
    const Estimate bias = difference(candidate, reference);
    if (decideBias(bias, tolerance, z).decision != Decision::Unresolved) return current;
    if (current >= maxReplicas) return current;
    const double perReplicaVar = candidate.err * candidate.err * current;
    const double refVar = reference.err * reference.err;
    const double gap = std::abs(std::abs(bias.mean) - tolerance);
    // Resolved at n when k(ν_n)·se_n ≤ gap. se_n falls with n, and so does k as its ν_n =
    // min(n − 1, ν_ref) does not: the smallest such n is found by bisection.
    const auto resolves = [&](int n) {
        const double var = perReplicaVar / n;
        const double k = studentMultiplier(z, smallerDof(n - 1.0, reference.dof));
        return k * std::sqrt(var + refVar) <= gap;
    };
    if (!resolves(maxReplicas)) return maxReplicas;
    int lo = current, hi = maxReplicas; // lo does not resolve, hi does
    while (hi - lo > 1) {
        const int mid = lo + (hi - lo) / 2;
        (resolves(mid) ? hi : lo) = mid;
    }
    return hi;
}

PowerLaw fitPowerLaw(std::span<const double> x, std::span<const Estimate> bias,
                     std::optional<double> fixedP, double pMin, double pMax) {
    if (x.size() != bias.size())
        throw std::invalid_argument("fitPowerLaw: one bias estimate per setting");
    if (!fixedP && !(pMin < pMax)) throw std::invalid_argument("fitPowerLaw: need pMin < pMax");
    PowerLaw law;
    std::vector<double> lnX, y, w;
    for (std::size_t i = 0; i < x.size(); ++i)
        if (x[i] > 0.0 && std::isfinite(x[i]) && std::isfinite(bias[i].mean) &&
            std::isfinite(bias[i].err) && bias[i].err > 0.0) {
            lnX.push_back(std::log(x[i]));
            y.push_back(bias[i].mean);
            w.push_back(1.0 / (bias[i].err * bias[i].err));
        }
    const int n = static_cast<int>(y.size());
    law.points = n;
    const int needed = fixedP ? 2 : 3;
    if (n < needed) {
        law.why = "needs " + std::to_string(needed) + " points with x > 0 and an error, has " +
                  std::to_string(n);
        return law;
    }
    // Work about the pivot x0 so that u = x/x0 is of order one whatever the units of x.
    double lnX0 = 0.0;
    for (double l : lnX)
        lnX0 += l;
    lnX0 /= n;
    std::vector<double> L(lnX.size());
    for (int i = 0; i < n; ++i)
        L[i] = lnX[i] - lnX0;
    law.pivot = std::exp(lnX0);

    const auto amplitude = [&](double p) { // closed-form least squares for a at fixed p
        double syf = 0.0, sff = 0.0;
        for (int i = 0; i < n; ++i) {
            const double f = std::exp(p * L[i]);
            syf += w[i] * y[i] * f, sff += w[i] * f * f;
        }
        return syf / sff;
    };
    // χ² summed directly, not as Σwy² − (Σwyf)²/Σwf², which cancels to round-off near a good fit
    // and would hide the minimum from the search.
    const auto chi2 = [&](double p) {
        const double a = amplitude(p);
        double s = 0.0;
        for (int i = 0; i < n; ++i) {
            const double r = y[i] - a * std::exp(p * L[i]);
            s += w[i] * r * r;
        }
        return s;
    };

    double p;
    bool atEdge = false;
    if (fixedP) {
        p = *fixedP;
    } else {
        constexpr int scan = 256;
        const double h = (pMax - pMin) / (scan - 1);
        int best = 0;
        double bestChi2 = inf;
        for (int j = 0; j < scan; ++j)
            if (const double c2 = chi2(pMin + j * h); c2 < bestChi2) bestChi2 = c2, best = j;
        if (best == 0 || best == scan - 1) {
            p = pMin + best * h;
            atEdge = true;
            law.why = "chi2 is smallest at an end of the exponent range [" + std::to_string(pMin) +
                      ", " + std::to_string(pMax) + "]";
        } else {
            const auto found = boost::math::tools::brent_find_minima(
                chi2, pMin + (best - 1) * h, pMin + (best + 1) * h,
                std::numeric_limits<double>::digits / 2);
            p = found.first;
        }
        const double target = chi2(p) + 1.0;
        // Walk out from the minimum a scan step at a time, so that the first crossing of
        // χ²_min + 1 is found, then bisect it.
        const auto crossing = [&](double dir, double edge, bool& reached) {
            double inside = p;
            while ((edge - inside) * dir > 0.0) {
                const double out =
                    dir > 0 ? std::min(inside + h, edge) : std::max(inside - h, edge);
                if (chi2(out) >= target) {
                    double a = inside, b = out;
                    for (int it = 0; it < 60; ++it) {
                        const double m = 0.5 * (a + b);
                        (chi2(m) >= target ? b : a) = m;
                    }
                    return 0.5 * (a + b);
                }
                inside = out;
            }
            reached = true;
            return edge;
        };
        bool cut = false;
        const double hi = crossing(+1.0, pMax, cut), lo = crossing(-1.0, pMin, cut);
        law.pErr = 0.5 * (hi - lo);
        if (cut && law.why.empty())
            law.why = "the exponent's chi2 + 1 interval reaches an end of the exponent range";
    }
    const double a = amplitude(p);
    law.p = p;
    law.c = a * std::exp(-p * lnX0);
    law.chi2 = chi2(p);

    // Linearised covariance of (ln|a|, p): the inverse of the Fisher matrix Σ w ∇f ∇fᵀ with
    // ∂f/∂ln|a| = f and ∂f/∂p = f·ln u.
    double f11 = 0.0, f12 = 0.0, f22 = 0.0;
    for (int i = 0; i < n; ++i) {
        const double f = a * std::exp(p * L[i]), wf2 = w[i] * f * f;
        f11 += wf2, f12 += wf2 * L[i], f22 += wf2 * L[i] * L[i];
    }
    if (fixedP) {
        law.pErr = 0.0;
        law.pFisherErr = 0.0;
        law.lnAmplitudeErr = 1.0 / std::sqrt(f11);
        law.correlation = 0.0;
    } else {
        const double det = f11 * f22 - f12 * f12;
        law.lnAmplitudeErr = std::sqrt(f22 / det);
        law.pFisherErr = std::sqrt(f11 / det);
        law.correlation = -f12 / std::sqrt(f11 * f22);
    }
    law.ok = !atEdge;
    return law;
}

Interval settingAtTolerance(const PowerLaw& law, double tolerance) {
    Interval r;
    if (!law.ok || !(law.p > 0.0) || !(law.c != 0.0) || !(tolerance > 0.0)) return r;
    const double lnA = std::log(std::abs(law.c)) + law.p * std::log(law.pivot);
    const double D = std::log(tolerance) - lnA;
    const double lnX = std::log(law.pivot) + D / law.p;
    const double gA = -1.0 / law.p, gP = -D / (law.p * law.p);
    const double sA = law.lnAmplitudeErr, sP = law.pFisherErr;
    const double var =
        gA * gA * sA * sA + gP * gP * sP * sP + 2.0 * gA * gP * law.correlation * sA * sP;
    const double s = std::sqrt(std::max(var, 0.0));
    r.value = std::exp(lnX);
    r.lo = std::exp(lnX - s);
    r.hi = std::exp(lnX + s);
    return r;
}

RatioInterval pairedRatio(std::span<const double> a, std::span<const double> b, double level) {
    if (a.size() != b.size()) throw std::invalid_argument("pairedRatio: one b timing per a timing");
    if (!(level > 0.0 && level < 1.0))
        throw std::invalid_argument("pairedRatio: the level must lie between 0 and 1");
    std::vector<double> r;
    r.reserve(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (!(a[i] > 0.0 && b[i] > 0.0 && std::isfinite(a[i]) && std::isfinite(b[i])))
            throw std::invalid_argument("pairedRatio: timings must be positive and finite");
        r.push_back(a[i] / b[i]);
    }
    RatioInterval out;
    const int n = static_cast<int>(r.size());
    out.pairs = n;
    if (n == 0) return out;
    std::sort(r.begin(), r.end());
    out.median = n % 2 ? r[n / 2] : 0.5 * (r[n / 2 - 1] + r[n / 2]);
    const boost::math::binomial_distribution<double> sign(n, 0.5);
    // Coverage of [r_(k), r_(n+1−k)]: the true median lies outside it only when fewer than k of
    // the n ratios fall on one side of it, each side with probability P(Binomial(n, ½) ≤ k − 1).
    const auto coverage = [&](int k) { return 1.0 - 2.0 * boost::math::cdf(sign, k - 1); };
    int k = 1;
    while (k + 1 <= n / 2 && coverage(k + 1) >= level)
        ++k;
    out.lo = r[k - 1];
    out.hi = r[n - k];
    out.level = coverage(k);
    return out;
}

} // namespace terrace::analysis
