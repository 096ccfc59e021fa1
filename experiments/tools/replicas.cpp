#include "experiments/tools/replicas.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace terrace::experiments {

bool isErrorColumn(const std::string& name) {
    return name == "err" || (name.size() > 4 && name.compare(name.size() - 4, 4, "_err") == 0);
}

analysis::CsvTable replicaMean(const std::vector<analysis::CsvTable>& replicas) {
    if (replicas.size() < 2)
        throw std::invalid_argument("replica mean: need at least two replicas for an error bar");
    const auto& first = replicas.front();
    int rows = first.rows();
    for (const auto& t : replicas) {
        if (t.header != first.header)
            throw std::invalid_argument("replica mean: replicas have different columns");
        rows = std::min(rows, t.rows());
    }
    // A grid mismatch would average different lags or radii: it must be an error, not a blur.
    for (const auto& t : replicas)
        for (int i = 0; i < rows; ++i)
            if (std::abs(t.columns[0][i] - first.columns[0][i]) >
                1e-9 * std::max(1.0, std::abs(first.columns[0][i])))
                throw std::invalid_argument("replica mean: replicas have different x grids");

    const double R = double(replicas.size());
    analysis::CsvTable out;
    out.header = first.header;
    out.columns.assign(first.header.size(), std::vector<double>(rows));
    for (std::size_t c = 0; c < first.header.size(); ++c) {
        if (c > 0 && isErrorColumn(first.header[c])) continue; // filled with its value column
        for (int i = 0; i < rows; ++i) {
            double sum = 0.0;
            for (const auto& t : replicas)
                sum += t.columns[c][i];
            const double mean = sum / R;
            out.columns[c][i] = mean;
            if (c + 1 < first.header.size() && isErrorColumn(first.header[c + 1])) {
                double ss = 0.0;
                for (const auto& t : replicas)
                    ss += (t.columns[c][i] - mean) * (t.columns[c][i] - mean);
                out.columns[c + 1][i] = std::sqrt(ss / (R * (R - 1.0)));
            }
        }
    }
    return out;
}

double interpolate(const analysis::CsvTable& t, int c, double x) {
    const auto& xs = t.columns[0];
    if (xs.empty() || x < xs.front() || x > xs.back())
        return std::numeric_limits<double>::quiet_NaN();
    const auto hi = std::lower_bound(xs.begin(), xs.end(), x);
    const std::size_t j = hi - xs.begin();
    if (*hi == x || j == 0) return t.columns[c][j];
    const double w = (x - xs[j - 1]) / (xs[j] - xs[j - 1]);
    return (1.0 - w) * t.columns[c][j - 1] + w * t.columns[c][j];
}

namespace {
int errorColumnOf(const analysis::CsvTable& t, const std::string& column) {
    const int c = t.find(column);
    if (c < 1) return -1;
    if (t.find(column + "_err") > 0) return t.find(column + "_err");
    if (c + 1 < int(t.header.size()) && t.header[c + 1] == "err") return c + 1;
    return -1;
}
} // namespace

double rmsNoise(const analysis::CsvTable& reference, const analysis::CsvTable& curve,
                const std::string& column, double xMax) {
    const int er = errorColumnOf(reference, column), ec = errorColumnOf(curve, column);
    if (er < 0 || ec < 0)
        throw std::invalid_argument("noise floor: no error column for '" + column + "'");
    double ss = 0.0;
    int n = 0;
    for (int i = 0; i < reference.rows(); ++i) {
        const double x = reference.columns[0][i];
        if (xMax > 0.0 && x > xMax) break;
        const double s = interpolate(curve, ec, x), sRef = reference.columns[er][i];
        if (!std::isfinite(s) || !std::isfinite(sRef)) continue;
        ss += s * s + sRef * sRef;
        ++n;
    }
    if (n == 0) throw std::invalid_argument("noise floor: the curves share no grid point");
    return std::sqrt(ss / n);
}

double rmsDifference(const analysis::CsvTable& reference, const analysis::CsvTable& curve,
                     const std::string& column, double xMax) {
    const int cr = reference.find(column), cc = curve.find(column);
    if (cr < 1 || cc < 1)
        throw std::invalid_argument("error norm: no column '" + column + "' in both curves");
    double ss = 0.0;
    int n = 0;
    for (int i = 0; i < reference.rows(); ++i) {
        const double x = reference.columns[0][i];
        if (xMax > 0.0 && x > xMax) break;
        const double y = interpolate(curve, cc, x), yRef = reference.columns[cr][i];
        if (!std::isfinite(y) || !std::isfinite(yRef)) continue;
        ss += (y - yRef) * (y - yRef);
        ++n;
    }
    if (n == 0) throw std::invalid_argument("error norm: the curves share no grid point");
    return std::sqrt(ss / n);
}

} // namespace terrace::experiments
