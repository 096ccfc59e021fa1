#pragma once
// Regression check of two correlation curves, A (the reference grid) and B, read from CSV.
//
// Columns: x is the first column of each file (same name in both). The value column is `column`,
// or A's first column after x. Its error column is "<column>_err", or "err" when it directly
// follows the first value column (rdf.csv, vacf.csv, msd.csv). A file without an error column
// counts as exact (σ = 0), e.g. an analytic curve; if neither file has one, there is no scale to
// judge agreement on and compareCsv throws.
//
// Grids: B is interpolated onto A's points inside B's x range, values by a four-point cubic
// (linear interpolation of a curve bent on the scale of the grid adds a bias of several error
// bars at short times), error bars linearly; on a common grid B's values are used as they are. The
// two must cover the same x range to within one step of the coarser grid, or compareCsv throws
// naming both files' point counts and ranges (a curve cut short would pass on its remaining part).
// Points where a value or an error is NaN are left out.
//
// Per point: z_i = (a_i − b_i)/σ_i with σ_i² = σ_a,i² + σ_b,i². The error bars are themselves
// estimates from B = 8 blocks (analysis::Options), so z_i follows Student's t, not a normal law:
// with ν = B − 1 = 7 per file and Welch–Satterthwaite's ν_i = σ_i⁴ / (σ_a,i⁴/ν + σ_b,i⁴/ν) for
// the pair, z_i is converted to the normal deviate with the same two-sided tail probability,
// ẑ_i. (Without this, 7-dof error bars make 5σ points common among a thousand lags and χ²/dof
// average 1.4 for identical physics.) All limits below apply to ẑ_i. A point with σ_i = 0 (or below
// 1e-12 of the value: round-off) must agree to 1e-9 relative (it then takes no part in χ²),
// otherwise ẑ_i = ∞.
//
// Verdict. tolSigma sets a false-alarm probability p = erfc(tolSigma/√2), that of one normal
// deviate beyond ±tolSigma (3 → 0.27 %). The curves disagree when either
//   (a) some |ẑ_i| exceeds the Bonferroni limit z_n = √2 erfc⁻¹(p/n) over the n points with σ > 0
//       (never below tolSigma): one point far off, allowing for many points being looked at; or
//   (b) χ²/dof = Σ ẑ_i²/n exceeds the (1 − p) quantile of χ²_ν/ν, ν = n_eff: a systematic shift
//       that no single point shows. Neighbouring points of a correlation function have strongly
//       correlated errors (an MSD's almost perfectly), so Σ ẑ_i² fluctuates like a sum of n_eff
//       independent squares, not of n. n_eff = n / (1 + 2 Σ_{j≥1} ρ_j), ρ_j the autocorrelation
//       along x of the deviations ẑ_i − mean(ẑ), summed while positive (the effective sample size
//       of C. J. Geyer, Stat. Sci. 7, 473 (1992)); subtracting the mean keeps a genuine shift
//       from being mistaken for correlated noise.
#include <filesystem>
#include <string>
#include <vector>

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

/// Limits of the verdict above: for n points with σ > 0, and for n_eff independent points.
double pointLimitSigma(double tolSigma, int n);
double chi2PerDofLimit(double tolSigma, double effectivePoints);

/// n_eff of the signed deviations z along x (see above), between 1 and z.size().
double effectivePoints(const std::vector<double>& z);

/// Degrees of freedom of one file's error bars: B − 1 for the default B = 8 blocks.
inline constexpr int errorDegreesOfFreedom = 7;

/// The normal deviate with the two-sided tail probability of Student's t = z at ν degrees of
/// freedom (ν = ∞: z itself).
double normalEquivalent(double z, double nu);

} // namespace terrace::analysis
