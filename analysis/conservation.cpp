#include "analysis/conservation.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace terrace::analysis {

void EnergyAccumulator::add(double t, double e, double u) {
    if (n_ > 0 && !(t > lastT_)) throw std::invalid_argument("energyStats: times must increase");
    if (n_ == 0) initial_ = e, firstT_ = t, firstU_ = u;
    final_ = e, lastT_ = t;
    maxDev_ = std::max(maxDev_, std::abs(e - initial_));
    sumE_ += e, sumU_ += u;
    ++n_;
    const double n = double(n_);
    // Centred on the first record, the values are the small fluctuations themselves (exact for
    // those within a factor 2 of it, Sterbenz): the running means and sums then keep the digits
    // of the fluctuations, not those of the energy's size.
    const double x = t - firstT_, y = e - initial_, z = u - firstU_;
    // Each centred sum grows by (x − old mean)(y − new mean).
    const double dx = x - meanT_, dy = y - meanE_, dz = z - meanU_;
    meanT_ += dx / n, meanE_ += dy / n, meanU_ += dz / n;
    m2T_ += dx * (x - meanT_);
    m2E_ += dy * (y - meanE_);
    m2U_ += dz * (z - meanU_);
    coTE_ += dx * (y - meanE_);
}

EnergyStats EnergyAccumulator::stats() const {
    if (n_ == 0) throw std::invalid_argument("energyStats: no energy records");
    const double n = double(n_);
    EnergyStats s{};
    s.initial = initial_;
    s.final = final_;
    s.mean = sumE_ / n;
    s.std = std::sqrt(std::max(0.0, m2E_) / n);
    s.maxAbsDev = maxDev_;
    s.potentialMean = sumU_ / n;
    s.potentialStd = std::sqrt(std::max(0.0, m2U_) / n);
    const double u = std::abs(s.potentialMean);
    if (u > 0.0)
        s.relFluct = s.std / u;
    else
        s.relFluct = s.std > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
    s.driftPerPs = m2T_ > 0.0 ? coTE_ / m2T_ : 0.0;
    return s;
}

void EnergyAccumulator::write(StateWriter& out) const {
    out.value(n_);
    for (const double x : {initial_, firstT_, firstU_, final_, lastT_, maxDev_, sumE_, sumU_,
                           meanT_, meanE_, meanU_, m2U_, m2T_, m2E_, coTE_})
        out.value(x);
}

void EnergyAccumulator::read(StateReader& in) {
    const char* what = "energy statistics";
    n_ = in.value<long>(what);
    if (n_ < 0) throw std::invalid_argument("analysis state: energy statistics: a negative count");
    for (double* x : {&initial_, &firstT_, &firstU_, &final_, &lastT_, &maxDev_, &sumE_, &sumU_,
                      &meanT_, &meanE_, &meanU_, &m2U_, &m2T_, &m2E_, &coTE_})
        *x = in.value<double>(what);
}

EnergyStats energyStats(const std::vector<double>& tPs, const std::vector<double>& total,
                        const std::vector<double>& potential) {
    if (tPs.size() != total.size() || potential.size() != total.size())
        throw std::invalid_argument("energyStats: times, total and potential differ in length");
    EnergyAccumulator a;
    for (std::size_t k = 0; k < total.size(); ++k)
        a.add(tPs[k], total[k], potential[k]);
    return a.stats();
}

} // namespace terrace::analysis
