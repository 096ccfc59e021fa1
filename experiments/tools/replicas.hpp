#pragma once
// Replica statistics and error norms of correlation curves (CSV as written by analysis/csv.hpp).
//
// Replica mean: R independent runs (different seeds) give curves y_r(x) on one grid; the mean is
// ȳ = Σ y_r / R and its standard error σ = sqrt(Σ (y_r − ȳ)² / (R (R − 1))). Independent runs
// make this error honest for time correlations, whose lags are strongly correlated within a run
// (DESIGN.md "Analysis": error bars from block averages or independent replicas).
//
// Error norm of a curve y against a reference y_ref: the root-mean-square difference
//     E = sqrt( (1/n) Σ_i (y(x_i) − y_ref(x_i))² )
// over the reference's grid points x_i inside both curves' ranges (and below xMax when given),
// y interpolated linearly onto x_i. Curves are dimensionless (g(r), normalised ACFs), so E is too.
#include "analysis/csv.hpp"
#include <filesystem>
#include <string>
#include <vector>

namespace terrace::experiments {

/// An error column holds the standard error of the value column before it: "err" or "<name>_err".
bool isErrorColumn(const std::string& name);

/// Mean over replicas, column by column; every error column is replaced by the replica standard
/// error of its value column. Replicas must share the header and the x grid (first column) over
/// their common length; longer ones are cut to the shortest. Needs R ≥ 2.
analysis::CsvTable replicaMean(const std::vector<analysis::CsvTable>& replicas);

/// Root-mean-square difference of `column` of `curve` against `reference` (see above); xMax ≤ 0
/// means no upper limit. Throws std::invalid_argument when the curves share no grid point.
double rmsDifference(const analysis::CsvTable& reference, const analysis::CsvTable& curve,
                     const std::string& column, double xMax = 0.0);

/// The statistical floor of that difference: sqrt((1/n) Σ_i (σ_ref,i² + σ_i²)) over the same
/// points, from the error columns of `column` (see isErrorColumn); what rmsDifference would be
/// for two curves that differ by noise alone. Throws when either table has no error column.
double rmsNoise(const analysis::CsvTable& reference, const analysis::CsvTable& curve,
                const std::string& column, double xMax = 0.0);

/// Linear interpolation of column c of t at x (t's first column increasing); NaN outside.
double interpolate(const analysis::CsvTable& t, int c, double x);

} // namespace terrace::experiments
