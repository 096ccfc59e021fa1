#pragma once
// Regression check of two correlation curves, A (the reference grid) and B, read from CSV.
//
// Columns: x is the first column of each file (same name in both). The value column is `column`,
// or A's first column after x. Its error column is "<column>_err", or "err" when it directly
// follows the first value column (rdf.csv, vacf.csv, msd.csv). A file without an error column
// counts as exact (σ = 0), e.g. an analytic curve; if neither file has one, there is no scale to
// judge agreement on and compareCsv throws.
//
// Grids: B (values and errors) is interpolated linearly onto A's points inside B's x range; A's
// points outside it are left out. Points where a value or an error is NaN are left out.
//
// Per point: z_i = (a_i − b_i)/σ_i with σ_i² = σ_a,i² + σ_b,i². A point with σ_i = 0 must agree to
// round-off (it then takes no part in χ²), otherwise |z_i| = ∞.
//
// Verdict. tolSigma sets a false-alarm probability p = erfc(tolSigma/√2), that of one normal
// deviate beyond ±tolSigma (3 → 0.27 %). The curves disagree when either
//   (a) some |z_i| exceeds the Bonferroni limit z_n = √2 erfc⁻¹(p/n) over the n points with σ > 0
//       (never below tolSigma): one point far off, allowing for many points being looked at; or
//   (b) χ²/dof = Σ z_i²/n exceeds the (1 − p) quantile of χ²_ν/ν with ν = min(n, 10): a
//       systematic shift that no single point shows. ν is capped because neighbouring lags of a
//       correlation function are strongly correlated and block error bars rest on ~8 blocks, so
//       Σ z_i² fluctuates like a sum of about ten independent squares, not of n.
#include <filesystem>
#include <string>

namespace terrace::analysis {

struct Comparison {
    bool agree;
    double chi2PerDof;
    double maxDeviationSigma;
    double atX;          // x of the largest deviation
    int points;          // points compared (common grid, finite values)
    std::string verdict; // one line
};

Comparison compareCsv(const std::filesystem::path& a, const std::filesystem::path& b,
                      double tolSigma, const std::string& column = "");

/// Limits of the verdict above, for n points with σ > 0.
double pointLimitSigma(double tolSigma, int n);
double chi2PerDofLimit(double tolSigma, int n);

/// Effective number of independent points a correlation curve's χ² behaves like (see above).
inline constexpr int effectiveIndependentPoints = 10;

} // namespace terrace::analysis
