#include "analysis/conservation.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace terrace::analysis {

namespace {

double mean(const std::vector<double>& x) {
    double m = 0.0;
    for (double v : x)
        m += v;
    return m / static_cast<double>(x.size());
}

} // namespace

EnergyStats energyStats(const std::vector<double>& tPs, const std::vector<double>& total,
                        const std::vector<double>& potential) {
    const std::size_t n = total.size();
    if (n == 0) throw std::invalid_argument("energyStats: no energy records");
    if (tPs.size() != n || potential.size() != n)
        throw std::invalid_argument("energyStats: times, total and potential differ in length");
    for (std::size_t k = 1; k < n; ++k)
        if (!(tPs[k] > tPs[k - 1])) throw std::invalid_argument("energyStats: times must increase");

    EnergyStats s{};
    s.initial = total.front();
    s.final = total.back();
    s.mean = mean(total);
    double var = 0.0, maxDev = 0.0;
    for (double e : total) {
        var += (e - s.mean) * (e - s.mean);
        maxDev = std::max(maxDev, std::abs(e - s.initial));
    }
    s.std = std::sqrt(var / static_cast<double>(n));
    s.maxAbsDev = maxDev;

    const double u = std::abs(mean(potential));
    if (u > 0.0)
        s.relFluct = s.std / u;
    else
        s.relFluct = s.std > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;

    // Centred sums keep the slope accurate when E is large and its drift tiny.
    const double tm = mean(tPs);
    double stt = 0.0, ste = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        stt += (tPs[k] - tm) * (tPs[k] - tm);
        ste += (tPs[k] - tm) * (total[k] - s.mean);
    }
    s.driftPerPs = stt > 0.0 ? ste / stt : 0.0;
    return s;
}

} // namespace terrace::analysis
