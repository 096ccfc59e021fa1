#include "analysis/compare.hpp"
#include "analysis/csv.hpp"
#include "core/format_text.hpp"
#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <limits>
#include <vector>

namespace terrace::analysis {

namespace {

/// Points with zero combined error must agree to this relative round-off (e.g. VACF(0) = 1).
constexpr double exactRelativeTolerance = 1e-9;
/// Error bars this small relative to the value are round-off of an exact point (OACF(0) = 1
/// comes out with err ~1e-17): such points are judged as exact, not in units of their "error".
constexpr double roundOffSigma = 1e-12;
/// A's x lies "inside" B's range up to this fraction of B's span (grids written from the same
/// sample interval differ in the last digits only).
constexpr double gridTolerance = 1e-9;

struct Column {
    std::vector<double> x, y, err; // err empty: exact
};

Column pick(const CsvTable& t, const std::string& name, const std::filesystem::path& path) {
    if (t.header.size() < 2 || t.rows() < 1)
        throw CsvError(path.string() + ": needs an x column, a value column and data rows");
    const int c = t.find(name);
    if (c < 1) throw CsvError(path.string() + ": no value column '" + name + "'");
    int e = t.find(name + "_err");
    if (e < 0 && c == 1 && t.header.size() > 2 && t.header[2] == "err") e = 2;
    Column col{t.columns[0], t.columns[c], {}};
    if (e >= 0) col.err = t.columns[e];
    return col;
}

/// Linear interpolation of ys at x on the increasing grid xs (x inside [xs.front(), xs.back()]).
double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
    if (x <= xs.front()) return ys.front();
    if (x >= xs.back()) return ys.back();
    const auto hi = std::upper_bound(xs.begin(), xs.end(), x) - xs.begin();
    const double f = (x - xs[hi - 1]) / (xs[hi] - xs[hi - 1]);
    return ys[hi - 1] + f * (ys[hi] - ys[hi - 1]);
}

/// Cubic (four-point Lagrange) interpolation: a correlation function is curved on the scale of
/// the sample interval (VACF ≈ 1 − a t² at short times), and linear interpolation onto another
/// grid would add a bias of several error bars there; the cubic's error is O(h⁴). Falls back to
/// linear with fewer than four points; an x on a grid point returns that point's value exactly.
double interpolateCubic(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
    const long n = static_cast<long>(xs.size());
    if (n < 4) return interpolate(xs, ys, x);
    if (x <= xs.front()) return ys.front();
    if (x >= xs.back()) return ys.back();
    const long hi = std::upper_bound(xs.begin(), xs.end(), x) - xs.begin();
    if (x == xs[hi - 1]) return ys[hi - 1];
    const long first = std::clamp(hi - 2, 0L, n - 4);
    double y = 0.0;
    for (long i = first; i < first + 4; ++i) {
        double basis = 1.0;
        for (long j = first; j < first + 4; ++j)
            if (j != i) basis *= (x - xs[j]) / (xs[i] - xs[j]);
        y += basis * ys[i];
    }
    return y;
}

} // namespace

double normalEquivalent(double z, double nu) {
    z = std::abs(z);
    if (!std::isfinite(nu) || z == 0.0 || !std::isfinite(z)) return z;
    const double p = 2.0 * boost::math::cdf(complement(boost::math::students_t(nu), z));
    if (p <= 0.0) return std::numeric_limits<double>::infinity();
    return std::sqrt(2.0) * boost::math::erfc_inv(std::min(p, 1.0));
}

double pointLimitSigma(double tolSigma, int n) {
    const double p = std::erfc(tolSigma / std::sqrt(2.0));
    return std::max(tolSigma, std::sqrt(2.0) * boost::math::erfc_inv(p / std::max(n, 1)));
}

double chi2PerDofLimit(double tolSigma, double effectivePoints) {
    const double p = std::erfc(tolSigma / std::sqrt(2.0));
    const double nu = std::max(1.0, effectivePoints);
    return boost::math::quantile(boost::math::chi_squared(nu), 1.0 - p) / nu;
}

double effectivePoints(const std::vector<double>& z) {
    const int n = static_cast<int>(z.size());
    if (n < 2) return n;
    double mean = 0.0;
    for (double v : z)
        mean += v;
    mean /= n; // exact for identical deviations, so that they have no spread at all
    double c0 = 0.0;
    for (double v : z)
        c0 += (v - mean) * (v - mean);
    if (!(c0 > 0.0)) return 1.0; // identical deviations: one piece of information
    double rhoSum = 0.0;
    for (int j = 1; j < n; ++j) {
        double cj = 0.0;
        for (int i = 0; i + j < n; ++i)
            cj += (z[i] - mean) * (z[i + j] - mean);
        if (cj <= 0.0) break; // initial positive sequence
        rhoSum += cj / c0;
    }
    return std::clamp(n / (1.0 + 2.0 * rhoSum), 1.0, static_cast<double>(n));
}

Comparison compareCsv(const std::filesystem::path& a, const std::filesystem::path& b,
                      double tolSigma, const std::string& column) {
    if (!(std::isfinite(tolSigma) && tolSigma > 0.0))
        throw std::invalid_argument("compare: --tol-sigma must be a finite number > 0");
    const CsvTable ta = readCsv(a), tb = readCsv(b);
    if (ta.header.empty() || tb.header.empty() || ta.header[0] != tb.header[0])
        throw CsvError("compare: x columns differ: '" + ta.header.at(0) + "' in " + a.string() +
                       ", '" + tb.header.at(0) + "' in " + b.string());
    const std::string name = column.empty() ? (ta.header.size() > 1 ? ta.header[1] : "") : column;
    const Column ca = pick(ta, name, a), cb = pick(tb, name, b);
    if (ca.err.empty() && cb.err.empty())
        throw CsvError("compare: neither file has an error column for '" + name +
                       "': no scale to judge agreement on");
    for (std::size_t k = 1; k < cb.x.size(); ++k)
        if (!(cb.x[k] > cb.x[k - 1])) throw CsvError(b.string() + ": x must increase");

    const double slack = gridTolerance * std::max(1.0, std::abs(cb.x.back() - cb.x.front()));
    // The curves must cover the same range (to one step of the coarser grid): points of one that
    // lie beyond the other are not compared, and a curve cut short (a run stopped early, half a
    // file) would otherwise pass on the part it still has.
    auto step = [](const std::vector<double>& x) {
        return x.size() > 1 ? (x.back() - x.front()) / static_cast<double>(x.size() - 1) : 0.0;
    };
    const double reach = std::max(step(ca.x), step(cb.x)) + slack;
    if (std::abs(ca.x.front() - cb.x.front()) > reach ||
        std::abs(ca.x.back() - cb.x.back()) > reach)
        throw CsvError("compare: the curves cover different ranges: " + a.string() + " has " +
                       std::to_string(ca.x.size()) + " points over " + ta.header[0] + " " +
                       formatText("%.6g", ca.x.front()) + " to " + formatText("%.6g", ca.x.back()) +
                       ", " + b.string() + " " + std::to_string(cb.x.size()) + " points over " +
                       formatText("%.6g", cb.x.front()) + " to " + formatText("%.6g", cb.x.back()) +
                       ": compare curves of runs of the same length and analysis settings");
    Comparison r{true, 0.0, 0.0, std::numeric_limits<double>::quiet_NaN(), 0, ""};
    double chi2 = 0.0;
    int dof = 0;
    bool exactMismatch = false;
    std::vector<double> signedZ; // ẑ_i with sign, in x order, for n_eff
    double rawMax = 0.0;         // largest |z_i| before the Student-t conversion, for the verdict
    for (std::size_t i = 0; i < ca.x.size(); ++i) {
        const double x = ca.x[i];
        if (x < cb.x.front() - slack || x > cb.x.back() + slack) continue;
        const double ya = ca.y[i], yb = interpolateCubic(cb.x, cb.y, x);
        const double ea = ca.err.empty() ? 0.0 : ca.err[i];
        const double eb = cb.err.empty() ? 0.0 : interpolate(cb.x, cb.err, x);
        if (!std::isfinite(ya) || !std::isfinite(yb) || !std::isfinite(ea) || !std::isfinite(eb))
            continue;
        ++r.points;
        const double sigma = std::hypot(ea, eb), diff = std::abs(ya - yb);
        double z = 0.0;
        const double scale = std::max({1.0, std::abs(ya), std::abs(yb)});
        if (sigma > roundOffSigma * scale) {
            const double nu = sigma * sigma * sigma * sigma /
                              ((ea * ea * ea * ea + eb * eb * eb * eb) / errorDegreesOfFreedom);
            rawMax = std::max(rawMax, diff / sigma);
            z = normalEquivalent(diff / sigma, nu);
            chi2 += z * z, ++dof;
            if (std::isfinite(z)) signedZ.push_back(ya >= yb ? z : -z);
        } else if (diff > exactRelativeTolerance * scale) {
            z = std::numeric_limits<double>::infinity(), exactMismatch = true;
        }
        if (z > r.maxDeviationSigma || std::isnan(r.atX)) r.maxDeviationSigma = z, r.atX = x;
    }
    if (r.points == 0)
        throw CsvError("compare: no common points of " + a.string() + " and " + b.string());

    r.chi2PerDof = dof > 0 ? chi2 / dof : 0.0;
    const double nEff = effectivePoints(signedZ);
    const double zLimit = pointLimitSigma(tolSigma, dof),
                 chiLimit = chi2PerDofLimit(tolSigma, nEff);
    r.agree = !exactMismatch && r.maxDeviationSigma <= zLimit && r.chi2PerDof <= chiLimit;
    r.verdict =
        std::string(r.agree ? "agree" : "DISAGREE") + ": " + name + " over " +
        std::to_string(r.points) + " points, chi2/dof " +
        formatText("%.3g (limit %.3g", r.chi2PerDof, chiLimit) +
        formatText(" for %.3g independent)", nEff) + ", largest deviation " +
        formatText("%.3g sigma (limit %.3g; raw %.3g)", r.maxDeviationSigma, zLimit, rawMax) +
        " at " + ta.header[0] + " = " + formatText("%.6g", r.atX) +
        (exactMismatch ? "; an exact point (zero error) differs" : "");
    return r;
}

} // namespace terrace::analysis
