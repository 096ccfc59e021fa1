#pragma once
// Statistics for choosing a setting (time step, terrace spacing, …) by what it costs in accuracy.
// A candidate's systematic bias on an observable is the mean over its independent replicas minus
// the reference mean. A setting is acceptable when |bias| ≤ tolerance, and the decision is only
// taken once the error bar keeps |bias| clear of the tolerance; more replicas are run until it
// does or a budget is spent. Along a ladder of settings the bias is fitted to a power law, which
// gives the setting where the bias reaches the tolerance; costs are compared as paired ratios.
//
// Few replicas. Replicas are expensive, so a decision may rest on 3–10 of them, and then the
// standard error is itself a poor estimate (with 3 replicas it is below half its true value one
// time in five). A deviation in units of such an error follows Student's t with the error's
// degrees of freedom (Estimate::dof), so every multiplier here is the t quantile with the same
// tail probability as the requested normal deviate z. Without it a two-replica estimate would
// pass a one-sided "2σ" test 15 % of the time instead of 2.3 %.
#include "analysis/block_average.hpp"
#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace terrace::analysis {

/// Mean over independent replicas with se = sd/√n (sd with n − 1), dof n − 1. One value: err NaN;
/// none: mean NaN.
Estimate replicaMean(std::span<const double> values);

/// One estimate from per-replica estimates (each a time average with its own block error), as
/// the plain mean. Replicas of one setting are runs of equal length, so their true variances are
/// equal and equal weights are already the minimum-variance combination; inverse-variance weights
/// from estimated errors (7 dof each from 8 blocks) would only add noise, and for observables
/// whose block error grows with the value they would bias the mean towards small values.
/// The error is the larger of the replica scatter sd/√n (dof n − 1), honest even when block errors
/// miss correlations longer than a block, and the propagated √(Σ err_i²)/n (dof by
/// Welch–Satterthwaite), which guards against a scatter that comes out small by chance when there
/// are few replicas. The larger of two estimates is conservative, not unbiased.
Estimate combineReplicaEstimates(std::span<const Estimate> perReplica);

/// The mean of replicas that each carry a block error, with the error the blocks give
/// (√(Σ err_i²)/n, Welch–Satterthwaite dof: about n(B − 1) for B blocks each) unless the replicas'
/// scatter contradicts it: when scatter²/propagated² exceeds the `level` quantile of
/// F(n − 1, dof) (the blocks miss a correlation longer than a block, or the runs differ more than
/// their blocks say), the scatter's sd/√n with n − 1 dof. Few replicas then still decide what
/// their blocks resolve (two runs of 8 blocks: ~14 dof instead of 1), and the blocks are trusted
/// only as far as the replicas bear them out.
Estimate pooledReplicaEstimate(std::span<const Estimate> perReplica, double level = 0.95);

/// a − b with errors in quadrature. The degrees of freedom are the smaller of the two, the
/// conservative answer to the Behrens–Fisher problem: the tail of (a − b)/err never exceeds that
/// of Student's t with min(ν_a, ν_b) degrees of freedom (M. R. Mickey and M. B. Brown, Ann. Math.
/// Stat. 37, 639 (1966)). Welch–Satterthwaite's (σ_a² + σ_b²)²/(σ_a⁴/ν_a + σ_b⁴/ν_b), evaluated
/// with the estimated σ, fails exactly in the case that matters here: a candidate from 2 replicas
/// whose scatter came out small by chance against a 100-replica reference gets a large ν and a
/// normal multiplier; in a Monte-Carlo of a bias on the tolerance at z = 2.67 (one-sided 0.38 %)
/// it was declared Within 3.3 % and Outside 3.7 % of the time. samples is a's: in a bias, the
/// candidate's replica count.
Estimate difference(Estimate a, Estimate b);

struct Tolerance {
    double value = 0.0;
    bool relative = false; // value is a fraction of |reference|
};

/// The tolerance in the observable's units: a relative one is a fraction of max(|reference|,
/// floor), the floor standing in where the observable's scale is not its value (a pressure that
/// crosses zero). The reference's own error makes a relative tolerance uncertain by
/// value·err(reference), which is left out: it is the fraction value (≪ 1) of an error that
/// already enters the bias in full.
double absoluteTolerance(Tolerance tolerance, double reference, double floor = 0.0);

/// The multiplier of a standard error with dof degrees of freedom that has the one-sided tail
/// probability of the normal deviate z: T_ν⁻¹(Φ(z)); z itself for ν = ∞, NaN for ν ≤ 0 or NaN.
double studentMultiplier(double z, double dof);

enum class Decision { Within, Outside, Unresolved };

struct BiasDecision {
    Estimate bias;
    double tolerance = NAN;
    double z = NAN;          // requested normal deviate
    double multiplier = NAN; // studentMultiplier(z, bias.dof), the one applied
    Decision decision = Decision::Unresolved;
};

/// With k = studentMultiplier(z, bias.dof): Within when |b| + k·se ≤ tol, Outside when
/// |b| − k·se ≥ tol, else Unresolved (also for a NaN bias or error). Within is the two one-sided
/// tests of equivalence testing (D. J. Schuirmann, J. Pharmacokinet. Biopharm. 15, 657 (1987)):
/// when the true |bias| ≥ tol it is declared with probability ≤ Φ(−z); likewise Outside when the
/// true |bias| ≤ tol. Each wrong decision thus has probability ≤ α/2 for z = Φ⁻¹(1 − α/2), and a
/// bias exactly at the tolerance is resolved either way with probability ≤ α.
BiasDecision decideBias(Estimate bias, double tolerance, double z);

/// z for deciding at up to `looks` replica counts fixed in advance (lookSchedule), with overall
/// two-sided level alpha per decision: Bonferroni over the counts, z = Φ⁻¹(1 − α/(2·looks)).
/// The replicas form one sequence, so "wrong at count n" is one event per count of the schedule
/// whichever counts the data lead the loop to visit, and the union bound over the schedule holds
/// for any stopping or skipping rule. Over the looks actually taken it would not be guaranteed if
/// the counts themselves followed the data (then every count up to the budget is a possible
/// look). Conservative: a group-sequential boundary would be tighter but needs the looks in
/// order. looks = 1, alpha = 0.0455: z = 2.
double sequentialZ(double alpha, int looks);

/// The replica counts a sequential decision may look at: first, doubling, and maxReplicas last
/// (2, 4, 8, 16, 32, 50 for 2 and 50). Doubling keeps the looks, and so z, few.
std::vector<int> lookSchedule(int first, int maxReplicas);

/// Replicas in all (≥ candidate.samples) the candidate needs so that its bias against the
/// reference would be resolved, projected with the per-replica variance held at its current
/// estimate (se² = s²/n) and the bias at its current value, with the Student multiplier at the
/// projected degrees of freedom; capped at maxReplicas. The current count when already resolved;
/// 2 when there are fewer (no error yet); maxReplicas when no count up to it would resolve, which
/// includes a bias on the tolerance and a reference too uncertain for the gap.
int replicasToResolve(Estimate candidate, Estimate reference, double tolerance, double z,
                      int maxReplicas);

/// The count of the next look: the first of the schedule above current and at or above the
/// projection (replicasToResolve); the schedule's last when none is. So the loop is
///     n = schedule[0]; z = sequentialZ(α, schedule.size());
///     while decideBias(…, z) is Unresolved and n < schedule.back():
///         n = nextLook(schedule, n, replicasToResolve(…)), run replicas up to n.
int nextLook(std::span<const int> schedule, int current, int projected);

struct PowerLaw {
    double c = NAN, p = NAN; // bias(x) = c·x^p
    double pErr = NAN;       // half the Δχ² = 1 interval of p (0 when p was fixed)
    double chi2 = NAN; // at the fit, with points − 2 (or − 1 for fixed p) degrees of freedom
    int points = 0;    // points used (x > 0, finite value, err > 0)
    bool ok = false;
    std::string why; // why not ok, or a caveat on an ok fit
    // Linearised covariance about the pivot x0 (the geometric mean of the x used), where the
    // amplitude a = c·x0^p and the exponent are least correlated; settingAtTolerance's band.
    double pivot = NAN;
    double lnAmplitudeErr = NAN; // se of ln|a|
    double pFisherErr = NAN;     // se of p from the curvature (0 when p was fixed)
    double correlation = NAN;    // of ln|a| and p
};

/// bias(x) = c·x^p by weighted least squares (weights 1/err²) over the points with x > 0. For a
/// given p, c is linear and has a closed form; p minimises the profiled χ²(p) over [pMin, pMax],
/// found on a 256-point scan (which finds the global minimum unless a narrower dip lies between
/// two scan points) and refined by Brent's method between the best point's neighbours. pErr is
/// half the profile interval χ²(p) ≤ χ²_min + 1, a 68 % interval also when χ² is not parabolic
/// in p (F. James, Statistical Methods in Experimental Physics, 2nd ed. (World Scientific, 2006));
/// an interval cut by [pMin, pMax] is noted in why. With fixedP (a known order: 2 for a
/// second-order splitting, 4 for a fourth-order one) only c is fitted. Needs 2 points (3 for free
/// p); ok is false, with why, otherwise or when the best p is at an end of [pMin, pMax].
PowerLaw fitPowerLaw(std::span<const double> x, std::span<const Estimate> bias,
                     std::optional<double> fixedP, double pMin = 0.5, double pMax = 8.0);

struct Interval {
    double value = NAN, lo = NAN, hi = NAN;
};

/// x* at which |c|·x*^p = tolerance, with the ±1σ band from linear propagation of the fit's
/// covariance in ln x* = ln x0 + ln(tolerance/|a|)/p. NaN when the fit is not ok, or p ≤ 0,
/// c = 0 or tolerance ≤ 0 (the law cannot reach it). Outside the fitted range of x it is an
/// extrapolation, and the band says only what the power law would imply.
Interval settingAtTolerance(const PowerLaw& law, double tolerance);

struct RatioInterval {
    double median = NAN, lo = NAN, hi = NAN;
    int pairs = 0;
    double level = NAN; // coverage of [lo, hi]
};

/// The ratios a_i/b_i of paired timings (taken alternately, so that drifts of the machine's load
/// cancel in each pair): their median and the distribution-free confidence interval for the
/// median [r_(k), r_(n+1−k)] from the order statistics, whose coverage is
/// 1 − 2·P(Binomial(n, ½) ≤ k − 1) for any continuous distribution (W. J. Conover, Practical
/// Nonparametric Statistics, 3rd ed. (Wiley, 1999), confidence interval for a quantile). k is the
/// largest with coverage ≥ level; when even k = 1 falls short (n ≤ 5 for 0.95) the interval is
/// [min, max] and level is the coverage reached, 1 − 2^(1−n). Timings must be positive and finite;
/// a and b must have equal lengths.
RatioInterval pairedRatio(std::span<const double> a, std::span<const double> b,
                          double level = 0.95);

} // namespace terrace::analysis
