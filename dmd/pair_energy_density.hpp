#pragma once
// The energies an isolated pair takes, weighted by the configuration volume that carries them:
// the density of states Ω(U) of one pair, over centre distances r in [r_in, r_out] and random
// relative orientations,
//
//     Ω(U) dU = ∫ 4πr² dr ⟨ δ(U(r, s_i, s_j) − U) ⟩_{s_i, s_j} dU   (Å³ per kJ/mol).
//
// In a dilute gas the pair density is ρ² e^{−βU} Ω(U) (the second-virial level of theory), so
// Ω with a Boltzmann factor is the weight a terrace design (dmd/terrace_design.hpp) gives to
// the error it makes at U. Built by quadrature: midpoint radii, and a fixed set of random axis
// pairs for an orientational potential (the separation along x; any potential is invariant
// under a common rotation), so the same potential always gives the same density.
//
// Terrace sums are prefix sums over the samples sorted by U: Σw, Σw e^{−βU}, Σw U e^{−βU},
// Σw U and Σw U² e^{−βU} over any interval of U in O(log n).
#include "core/body_orientation.hpp"
#include "core/huge_pages.hpp"
#include "core/initial_state.hpp"
#include "core/pair_potential.hpp"
#include "dmd/orientation_samples.hpp"
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace terrace::dmd {

class PairEnergyDensity {
public:
    /// Sums over the samples with U in [lo, hi): volume (Å³), Boltzmann-weighted volume, and the
    /// first moments of U under each (kJ/mol Å³).
    struct Sums {
        double volume = 0.0, boltzmann = 0.0, energyBoltzmann = 0.0, energyVolume = 0.0;
        double squareBoltzmann = 0.0; // Σw e^{−βU} U², kJ²/mol² Å³
    };

    /// radii × orientations samples over r in [rIn, rOut] (Å); energies above uCap (or not
    /// finite) are left out: no design places a terrace there.
    template <PairPotential P>
    static PairEnergyDensity build(const P& p, double kT, double rIn, double rOut, double uCap,
                                   int radii = 4000, int orientations = 512) {
        PairEnergyDensity d;
        d.kT_ = kT;
        const int nOrient = isOrientational<P> ? orientations : 1;
        std::mt19937_64 rng(0x7e44ace5); // fixed: a design is a pure function of its inputs
        using Orientation = typename P::Orientation;
        std::vector<std::pair<Orientation, Orientation>> axes(
            nOrient, {unusedOrientation<P>(), unusedOrientation<P>()});
        if constexpr (isOrientational<P>)
            for (int k = 0; k < nOrient; ++k)
                axes[k] = sampledOrientations(p, k, rng);
        const double dr = (rOut - rIn) / radii;
        struct Sample {
            double U, w;
        };
        BodyArray<Sample> s;
        s.reserve(static_cast<std::size_t>(radii) * nOrient);
        for (int k = 0; k < radii; ++k) {
            const double r = rIn + (k + 0.5) * dr;
            const double w = 4.0 * std::numbers::pi * r * r * dr / nOrient;
            for (const auto& [si, sj] : axes) {
                const double U = p.energy(Vec3(r, 0.0, 0.0), si, sj);
                if (std::isfinite(U) && U <= uCap) s.push_back({U, w});
            }
        }
        std::sort(s.begin(), s.end(), [](const Sample& a, const Sample& b) { return a.U < b.U; });
        // Two million samples for an orientational potential, 130 MB with their sums: reserved
        // whole and in huge pages (core/huge_pages.hpp), since grown by doubling in small pages
        // their first touches cost more than the quadrature itself.
        d.energy_.reserve(s.size());
        d.prefix_.reserve(s.size() + 1);
        d.prefix_.assign(1, Sums{});
        for (const auto& x : s) {
            Sums next = d.prefix_.back();
            const double b = x.w * std::exp(-x.U / kT);
            next.volume += x.w;
            next.boltzmann += b;
            next.energyBoltzmann += b * x.U;
            next.energyVolume += x.w * x.U;
            next.squareBoltzmann += b * x.U * x.U;
            d.energy_.push_back(x.U);
            d.prefix_.push_back(next);
        }
        return d;
    }

    double kT() const { return kT_; }
    double lowestEnergy() const { return energy_.empty() ? 0.0 : energy_.front(); }

    /// Sums over U in [lo, hi) (infinite bounds allowed).
    Sums over(double lo, double hi) const { return between(indexOf(lo), indexOf(hi)); }

    /// Samples in all.
    std::size_t size() const { return energy_.size(); }

    /// The first sample with U >= u, searched in [from, to) only: the caller knows it lies there
    /// (an iteration whose levels move within known bounds), which keeps the search short.
    std::size_t indexOf(double u, std::size_t from = 0,
                        std::size_t to = std::numeric_limits<std::size_t>::max()) const {
        to = std::min(to, energy_.size());
        return static_cast<std::size_t>(
            std::lower_bound(energy_.begin() + static_cast<std::ptrdiff_t>(from),
                             energy_.begin() + static_cast<std::ptrdiff_t>(to), u) -
            energy_.begin());
    }

    /// Sums over samples a … b − 1 of the sorted list.
    Sums between(std::size_t a, std::size_t b) const {
        const Sums &x = prefix_[b], &y = prefix_[a];
        return {x.volume - y.volume, x.boltzmann - y.boltzmann,
                x.energyBoltzmann - y.energyBoltzmann, x.energyVolume - y.energyVolume,
                x.squareBoltzmann - y.squareBoltzmann};
    }

private:
    double kT_ = 1.0;
    BodyArray<double> energy_; // sorted
    BodyArray<Sums> prefix_;   // prefix_[k]: sums over the first k samples
};

} // namespace terrace::dmd
