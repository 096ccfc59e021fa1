#pragma once
// What either engine's configuration says of the continuous model, whatever the engine moves on.
//
// DMD samples the terraced Boltzmann distribution ∝ e^{−βΣV_ij}, and its own observables — the
// terraced ⟨V⟩, the impulse virial — carry the terracing twice: in the distribution and in the
// observable. Evaluating the continuous model's U and molecular virial W = Σ r_ij·F_ij on the
// same configurations (configurational estimators) removes the second; only the distribution's
// terracing is left. For the pair structure the same idea gives, to first order in the pair's own
// interaction (the potential of mean force of a dilute pair, W(r) = U(r) − kT ln y(r) with the
// cavity function y unchanged by the terracing of one pair),
//
//     g_c(r) ≈ g_d(r) ⟨e^{−β(U_ij − V_ij)}⟩_{pairs at r},
//
// the average over the pairs at distance r of their Boltzmann factor of continuous against
// terraced energy; for spheres this is g_d(r) e^{−β(U(r) − V(r))}, for bodies with an attitude the
// orientation average over the pairs that occur. TerracingProfile accumulates that average per
// bin of r; SMD, whose V is U, adds nothing to it.
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace terrace {

/// The continuous model's U and W = Σ_pairs r_ij·F_ij (kJ/mol) on one configuration.
struct ContinuousSums {
    double potential = 0.0;
    double virial = 0.0;
};

/// Σ e^{−β(U−V)} and the number of pairs, per bin of the centre distance (the bins of g(r)).
class TerracingProfile {
public:
    TerracingProfile() = default;
    /// bins of width binWidth (Å) from r = 0; beta = 1/kT (mol/kJ).
    TerracingProfile(int bins, double binWidth, double beta)
        : binWidth_(binWidth), beta_(beta), weight_(std::size_t(bins), 0.0),
          count_(std::size_t(bins), 0.0) {}

    /// A pair at centre distance r (Å) with continuous minus terraced energy uMinusV (kJ/mol);
    /// beyond the last bin it is not counted.
    void add(double r, double uMinusV) {
        const auto k = static_cast<std::size_t>(r / binWidth_);
        if (k >= weight_.size()) return;
        weight_[k] += std::exp(-beta_ * uMinusV);
        count_[k] += 1.0;
    }
    /// ⟨e^{−β(U−V)}⟩ in bin k: 1 where no interacting pair was seen (there U = V = 0).
    double meanWeight(std::size_t k) const {
        return count_[k] > 0.0 ? weight_[k] / count_[k] : 1.0;
    }
    bool empty() const {
        for (const double c : count_)
            if (c > 0.0) return false;
        return true;
    }
    int bins() const { return static_cast<int>(weight_.size()); }
    double binWidth() const { return binWidth_; }
    double beta() const { return beta_; }
    const std::vector<double>& weights() const { return weight_; }
    const std::vector<double>& counts() const { return count_; }
    /// Restores sums kept in a restart file; std::invalid_argument unless they have its bins.
    void restore(std::vector<double> weight, std::vector<double> count) {
        if (weight.size() != weight_.size() || count.size() != count_.size())
            throw std::invalid_argument("the terracing profile's bins differ from g(r)'s");
        weight_ = std::move(weight), count_ = std::move(count);
    }

private:
    double binWidth_ = 1.0, beta_ = 0.0;
    std::vector<double> weight_, count_;
};

} // namespace terrace
