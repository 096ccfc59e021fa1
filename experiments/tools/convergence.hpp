#pragma once
// The order of convergence of DMD to SMD as the terrace height ΔV → 0 (experiments/convergence.sh).
//
// For one quantity and system, each DMD setting k gives an error e_k > 0 against the reference
// (SMD at dt = 0.2 fs) with a statistical uncertainty s_k. A power law e = A ΔV^p is a straight
// line in y = ln e, x = ln ΔV, fitted by weighted least squares with σ_y = s/e (first-order
// propagation through the logarithm), following W. H. Press et al., Numerical Recipes, 3rd ed.
// (2007), sec. 15.2, eqs. 15.2.4–15.2.9: with weights w = 1/σ_y²,
//     S = Σw, S_x = Σwx, S_y = Σwy, S_xx = Σwx², S_xy = Σwxy, Δ = S S_xx − S_x²,
//     p = (S S_xy − S_x S_y)/Δ,  ln A = (S_xx S_y − S_x S_xy)/Δ,  σ_p² = S/Δ,
//     χ² = Σ w (y − ln A − p x)².
// When χ²/(n − 2) > 1 the points scatter more than their errors allow (e.g. a coarse ΔV outside
// the asymptotic regime): σ_p is then scaled by sqrt(χ²/(n − 2)) (the Birge ratio, the Particle
// Data Group's scale factor: Review of Particle Physics, Introduction), so that a poor power law
// shows as a wide error rather than a confident slope.
// A point whose error is not resolved from zero — e < resolvedSigmas · s — tells nothing about
// the slope (its logarithm is dominated by noise) and is left out of the fit, and marked.
// The shared reference makes the e_k of one system correlated; the fit treats them as independent
// (the reference is run longer than each DMD set so that its share of s_k is the smaller one).
#include "analysis/csv.hpp"
#include <string>
#include <vector>

namespace terrace::experiments {

/// A point is within the statistical floor unless its error exceeds this many uncertainties
/// (two: a 5 % chance that pure noise passes for a resolved error).
inline constexpr double resolvedSigmas = 2.0;

struct MeanAndError {
    double mean = 0.0;
    double error = 0.0; // standard error of the mean, sqrt(Σ(x − x̄)²/(R(R − 1))); NaN for R = 1
};

/// Replica mean and standard error of independent values (NaN values are refused).
MeanAndError replicaStatistics(const std::vector<double>& values);

struct ConvergencePoint {
    double dV = 0.0;    // terrace height (kT)
    double error = 0.0; // e, the distance from the reference
    double sigma = 0.0; // s, its statistical uncertainty
};

/// Whether a point's error is resolved from zero (see above); NaN never is.
bool isResolved(const ConvergencePoint& p);

struct OrderFit {
    double order = 0.0, orderError = 0.0; // p and σ_p (scaled by the Birge ratio when > 1)
    double logPrefactor = 0.0;            // ln A
    double chi2PerDof = 0.0;              // χ²/(n − 2); NaN for n = 2
    int points = 0;                       // n, resolved points used
};

/// The weighted least-squares fit above over the resolved points with ΔV > 0; NaN order and error
/// when fewer than two remain.
OrderFit fitOrder(const std::vector<ConvergencePoint>& points);

/// The local order between ΔV and ΔV/2, p = log₂(e(ΔV)/e(ΔV/2)), the factor by which the error
/// shrinks when ΔV is halved written as a power of 2, with σ_p = sqrt((s/e)² + (s'/e')²)/ln 2 (the
/// two errors taken as independent); NaN unless both points are resolved.
MeanAndError localOrder(const ConvergencePoint& coarse, const ConvergencePoint& fine);

/// Reads a convergence table (columns dV_kT, then per quantity q: err_q, sigma_q; rows with
/// dV_kT ≤ 0 are the reference's and take no part), writes it to `out` with three columns after
/// each sigma_q: fit_q (1: in the fit, 0: within the statistical floor) and the local order from
/// the row's ΔV to ΔV/2 with its error, order_q and order_q_err (NaN without a resolved row at
/// ΔV/2), and returns one CSV row per quantity: "q,order,order_err,log_prefactor,chi2_per_dof,
/// points".
std::vector<std::string> fitOrders(const analysis::CsvTable& table, const std::string& out);

} // namespace terrace::experiments
