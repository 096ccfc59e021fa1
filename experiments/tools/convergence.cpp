#include "experiments/tools/convergence.hpp"
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace terrace::experiments {

namespace {
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
} // namespace

MeanAndError replicaStatistics(const std::vector<double>& values) {
    if (values.empty()) throw std::invalid_argument("replica statistics: no values");
    const double R = double(values.size());
    double sum = 0.0;
    for (double v : values) {
        if (!std::isfinite(v))
            throw std::invalid_argument("replica statistics: a value is not finite");
        sum += v;
    }
    const double mean = sum / R;
    double ss = 0.0;
    for (double v : values)
        ss += (v - mean) * (v - mean);
    // One value has no spread to estimate: its error is unknown, never 0.
    return {mean, values.size() > 1 ? std::sqrt(ss / (R * (R - 1.0))) : nan};
}

bool isResolved(const ConvergencePoint& p) {
    return p.error > 0.0 && p.sigma > 0.0 && p.error >= resolvedSigmas * p.sigma;
}

OrderFit fitOrder(const std::vector<ConvergencePoint>& points) {
    double S = 0.0, Sx = 0.0, Sy = 0.0, Sxx = 0.0, Sxy = 0.0;
    int n = 0;
    for (const auto& p : points) {
        if (!(p.dV > 0.0) || !isResolved(p)) continue;
        const double x = std::log(p.dV), y = std::log(p.error), sy = p.sigma / p.error;
        const double w = 1.0 / (sy * sy);
        S += w, Sx += w * x, Sy += w * y, Sxx += w * x * x, Sxy += w * x * y;
        ++n;
    }
    OrderFit f;
    f.points = n;
    const double delta = S * Sxx - Sx * Sx;
    if (n < 2 || !(delta > 0.0)) {
        f.order = f.orderError = f.logPrefactor = f.chi2PerDof = nan;
        return f;
    }
    f.order = (S * Sxy - Sx * Sy) / delta;
    f.logPrefactor = (Sxx * Sy - Sx * Sxy) / delta;
    f.orderError = std::sqrt(S / delta);
    double chi2 = 0.0;
    for (const auto& p : points) {
        if (!(p.dV > 0.0) || !isResolved(p)) continue;
        const double x = std::log(p.dV), y = std::log(p.error), sy = p.sigma / p.error;
        const double r = (y - f.logPrefactor - f.order * x) / sy;
        chi2 += r * r;
    }
    f.chi2PerDof = n > 2 ? chi2 / (n - 2) : nan;
    if (n > 2 && f.chi2PerDof > 1.0) f.orderError *= std::sqrt(f.chi2PerDof);
    return f;
}

MeanAndError localOrder(const ConvergencePoint& coarse, const ConvergencePoint& fine) {
    if (!isResolved(coarse) || !isResolved(fine)) return {nan, nan};
    const double a = coarse.sigma / coarse.error, b = fine.sigma / fine.error;
    return {std::log2(coarse.error / fine.error), std::sqrt(a * a + b * b) / std::log(2.0)};
}

std::vector<std::string> fitOrders(const analysis::CsvTable& table, const std::string& out) {
    const int cdV = table.find("dV_kT");
    if (cdV < 0) throw std::invalid_argument("convergence table: no column dV_kT");
    analysis::CsvTable marked;
    std::vector<std::string> rows;
    for (std::size_t c = 0; c < table.header.size(); ++c) {
        marked.header.push_back(table.header[c]);
        marked.columns.push_back(table.columns[c]);
        const std::string& name = table.header[c];
        if (name.rfind("sigma_", 0) != 0) continue;
        const std::string q = name.substr(6);
        const int ce = table.find("err_" + q);
        if (ce < 0) throw std::invalid_argument("convergence table: " + name + " without err_" + q);
        std::vector<ConvergencePoint> points;
        std::vector<double> used;
        for (int i = 0; i < table.rows(); ++i) {
            const ConvergencePoint p{table.columns[cdV][i], table.columns[ce][i],
                                     table.columns[c][i]};
            points.push_back(p);
            used.push_back(p.dV > 0.0 ? (isResolved(p) ? 1.0 : 0.0) : nan);
        }
        std::vector<double> local(points.size(), nan), localErr(points.size(), nan);
        for (std::size_t i = 0; i < points.size(); ++i)
            for (const auto& fine : points)
                if (points[i].dV > 0.0 &&
                    std::abs(fine.dV - 0.5 * points[i].dV) < 1e-9 * points[i].dV) {
                    const MeanAndError p = localOrder(points[i], fine);
                    local[i] = p.mean, localErr[i] = p.error;
                }
        marked.header.insert(marked.header.end(),
                             {"fit_" + q, "order_" + q, "order_" + q + "_err"});
        marked.columns.insert(marked.columns.end(), {used, local, localErr});
        const OrderFit f = fitOrder(points);
        char row[256];
        std::snprintf(row, sizeof row, "%s,%.4g,%.2g,%.6g,%.3g,%d", q.c_str(), f.order,
                      f.orderError, f.logPrefactor, f.chi2PerDof, f.points);
        rows.emplace_back(row);
    }
    analysis::writeCsv(out, marked);
    return rows;
}

} // namespace terrace::experiments
