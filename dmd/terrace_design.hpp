#pragma once
// Terrace designs: where the levels U_k lie and what energy V_s each terrace carries, as pure
// functions of (potential, kT, parameters). The paper uses uniform levels U_k = (k − ½)ΔV with
// midpoint energies and expects "some other distribution of energy levels" to do better;
// Thomson, Lue & Bannerman (J. Chem. Phys. 140, 034105 (2014)) compared, for LJ spheres, steps
// placed by equal energy, equal distance or equal shell volume, with step energies at the
// midpoint, volume average or matched to the second virial coefficient. Here the same choices
// are made for any pair potential, orientational ones included, plus one of our own.
//
// Level placement (`dmd.terraces.levels`), with n levels in the well (U < 0; by default as many
// as uniform levels of height dV put there, and at least 2):
//   energy    U_k = (k − ½)ΔV, ΔV = |U_min|/n (or the scene's dV when n is not given), k ≠ 0.
//   distance  radii uniform along the profile u(r) = U at the alignment s_i·s_j = 1/√2 (for the
//             rods r_e = r there, so this is uniform in the effective distance): in the well
//             r_k = r_min + (k − ½)h, h = (r_out − r_min)/n; on the wall r_σ − (k − ½)h while
//             u < U_cap; U_k = u(r_k).
//   volume    the same with r³ in place of r: shells of equal volume.
//   optimal   see below.
// Above U_cap = 50 kT (every start lies below it, core/initial_state.hpp) one more level closes
// the set, and the terrace beyond it carries U_cap: a wall no thermal pair crosses.
//
// Terrace energies (`dmd.terraces.values`) over the configurations whose U lies on the terrace,
// with the pair density of states Ω(U) (dmd/pair_energy_density.hpp):
//   midpoint   (U_{k−1} + U_k)/2 (the paper; the outermost terraces repeat the next step);
//   volume     ⟨U⟩ under Ω;
//   boltzmann  ⟨U⟩ under Ω e^{−βU};
//   virial     −kT ln⟨e^{−βU}⟩ under Ω: each terrace then contributes to the second virial
//              coefficient B₂ = −½∫(e^{−βU} − 1) exactly what the continuous potential does
//              over the same configurations, so the terraced B₂ equals the continuous one to
//              the quadrature (terrace 0 and the wall aside).
// The terrace holding U = 0 always carries exactly 0 (every far pair sits on it).
//
// Our design, `optimal`: the levels and energies that minimise the Boltzmann-weighted squared
// error of the terraced energy for a given number of levels,
//
//     E² = ∫ Ω(U) e^{−βU} (U − V(U))² dU,   V(U) = V_s for U on terrace s,
//
// over the pair configurations within the model's range, with V_0 = 0 held. It is the Lloyd–Max
// quantiser of U under the weight Ω e^{−βU} (S. P. Lloyd, IEEE Trans. Inf. Theory 28, 129 (1982);
// J. Max, IRE Trans. Inf. Theory 6, 7 (1960)): at the optimum each level is the midpoint of the
// energies on its two sides, U_k = (V_k + V_{k+1})/2, and each energy is the Boltzmann mean of U
// over its terrace; alternating the two conditions lowers E² at every step. Levels gather where
// pairs spend their time (the well, the foot of the wall) and thin out where they rarely go, so
// that for the same number of crossings the energy the run samples is closer to the continuous
// one. n levels go below 0 and, by default, as many above it as uniform levels of the same
// step fit below 5 kT (the wall a thermal pair climbs: e^{−5} ≈ 0.7 %).
//
// Units: kJ/mol, Å.
#include "core/initial_state.hpp"
#include "core/pair_potential.hpp"
#include "core/scene.hpp"
#include "dmd/pair_energy_density.hpp"
#include "dmd/section.hpp"
#include <algorithm>
#include <cmath>
#include <concepts>
#include <deque>
#include <functional>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

namespace terrace::dmd {

/// Levels and the energies of the terraces between them (levels.size() + 1), kJ/mol.
struct TerraceDesign {
    std::vector<double> levels, values;
};

/// Highest designed level, in kT: every start configuration lies below it.
inline constexpr double designCapInKT = terrace::detail::maxStartEnergyInKT;
/// The wall the optimal design resolves by default, in kT.
inline constexpr double optimalWallInKT = 5.0;
/// Levels (well, wall and cap) an optimal design may have. Lloyd–Max moves each level by a
/// fraction of its neighbours' shift per sweep, so the sweeps needed grow with the level count:
/// on the dense rods (8 levels per level in the well) 2401 levels converge in 9500 of the 10⁴
/// sweeps allowed, 2.2 s in all, while 8001 had not converged after 10⁴ (6.7 s); the density of
/// states behind it holds ~2·10⁶ samples, ~1000 per terrace at this count.
inline constexpr long maxOptimalLevels = 2500;

/// The potential along one fixed alignment, s_i·s_j = 1/√2 with the separation along x (a frame
/// potential: body j turned by 45° about x from body i; a mixture: its first species' pair, at
/// that alignment where it has rods).
template <PairPotential P> double profileEnergy(const P& p, double r) {
    if constexpr (P::attitude == AttitudeUse::Frame) {
        const Mat3 qi = Mat3::Identity();
        const Mat3 qj = rotationMatrix(Vec3::UnitX(), -0.25 * std::numbers::pi);
        return p.energy(Vec3(r, 0.0, 0.0), qi, qj);
    } else if constexpr (P::attitude == AttitudeUse::Species) {
        return p.energy(Vec3(r, 0.0, 0.0), 0, 0); // a mixture's first like pair
    } else if constexpr (P::attitude == AttitudeUse::SpeciesAxis) {
        const Vec3 sj = (Vec3::UnitZ() + Vec3::UnitY()).normalized();
        return p.energy(Vec3(r, 0.0, 0.0), SpeciesAxis{Vec3::UnitZ(), 0}, SpeciesAxis{sj, 0});
    } else {
        const Vec3 si = Vec3::UnitZ();
        const Vec3 sj = (Vec3::UnitZ() + Vec3::UnitY()).normalized();
        return p.energy(Vec3(r, 0.0, 0.0), si, sj);
    }
}

/// Landmarks of the profile: its minimum r_min, its inner zero r_σ, searched in [rIn, rOut].
struct ProfileShape {
    double rMin = 0.0, rZero = 0.0, uMin = 0.0;
};

template <PairPotential P> ProfileShape profileShape(const P& p, double rIn, double rOut) {
    ProfileShape s;
    constexpr int scan = 4000;
    s.uMin = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= scan; ++k) {
        const double r = rIn + (rOut - rIn) * k / scan;
        const double u = profileEnergy(p, r);
        if (u < s.uMin) s.uMin = u, s.rMin = r;
    }
    // Golden-section refinement of the minimum within one scan step either side.
    double a = std::max(rIn, s.rMin - (rOut - rIn) / scan);
    double b = std::min(rOut, s.rMin + (rOut - rIn) / scan);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int it = 0; it < 100; ++it) {
        const double c = b - g * (b - a), d = a + g * (b - a);
        if (profileEnergy(p, c) < profileEnergy(p, d))
            b = d;
        else
            a = c;
    }
    s.rMin = 0.5 * (a + b);
    s.uMin = profileEnergy(p, s.rMin);
    double lo = rIn, hi = s.rMin; // u(lo) > 0 > u(hi)
    for (int it = 0; it < 200 && hi - lo > 1e-14 * hi; ++it) {
        const double mid = 0.5 * (lo + hi);
        (profileEnergy(p, mid) > 0.0 ? lo : hi) = mid;
    }
    s.rZero = 0.5 * (lo + hi);
    return s;
}

/// Uniform levels (k − ½) step above uMin and below uCap.
inline std::vector<double> energyLevels(double uMin, double step, double uCap) {
    std::vector<double> L;
    for (int k = static_cast<int>(std::ceil(uMin / step + 0.5)); (k - 0.5) * step < uCap; ++k)
        if ((k - 0.5) * step > uMin) L.push_back((k - 0.5) * step);
    return L;
}

/// Levels at radii uniform in the coordinate x(r) (r for distance, r³ for volume): n in the
/// well between r_min and rOut, and down the wall from r_σ with the same spacing in x while the
/// profile stays below uCap.
template <PairPotential P>
std::vector<double> radialLevels(const P& p, const ProfileShape& shape, double rIn, double rOut,
                                 int n, double uCap, const std::function<double(double)>& x,
                                 const std::function<double(double)>& xInverse) {
    const double h = (x(rOut) - x(shape.rMin)) / n;
    std::vector<double> wall, well;
    for (int k = 1;; ++k) {
        const double xk = x(shape.rZero) - (k - 0.5) * h;
        if (xk <= x(rIn)) break;
        const double u = profileEnergy(p, xInverse(xk));
        if (!(u < uCap)) break;
        wall.push_back(u);
    }
    for (int k = 1; k <= n; ++k)
        well.push_back(profileEnergy(p, xInverse(x(shape.rMin) + (k - 0.5) * h)));
    std::vector<double> L(well.begin(), well.end());
    L.insert(L.end(), wall.begin(), wall.end()); // the wall's levels rise as r falls
    return L;
}

/// Terrace energies for levels L, whose last is the cap, by a rule (midpoint | volume |
/// boltzmann | virial): the terrace holding U = 0 gets 0, the one beyond the cap the cap's
/// energy, an empty terrace (no configuration in the density) its midpoint; the lowest terrace
/// spans [U_min, L_0].
inline std::vector<double> terraceValues(const std::vector<double>& L, const std::string& rule,
                                         const PairEnergyDensity& density, double uMin) {
    if (rule != "midpoint" && rule != "volume" && rule != "boltzmann" && rule != "virial")
        throw SceneError("dmd.terraces.values: must be midpoint, volume, boltzmann or virial, "
                         "got \"" +
                         rule + "\"");
    const std::size_t K = L.size();
    std::vector<double> V(K + 1);
    for (std::size_t s = 0; s <= K; ++s) {
        if (s == K) {
            V[s] = L[K - 1];
            continue;
        }
        const double lo = s == 0 ? -std::numeric_limits<double>::infinity() : L[s - 1];
        const double hi = L[s];
        const double mid = 0.5 * ((s == 0 ? uMin : lo) + hi);
        const auto sum = density.over(lo, hi);
        if (lo < 0.0 && hi > 0.0)
            V[s] = 0.0;
        else if (rule == "midpoint" || !(sum.volume > 0.0) || !(sum.boltzmann > 0.0))
            V[s] = mid;
        else if (rule == "volume")
            V[s] = sum.energyVolume / sum.volume;
        else if (rule == "boltzmann")
            V[s] = sum.energyBoltzmann / sum.boltzmann;
        else // virial
            V[s] = -density.kT() * std::log(sum.boltzmann / sum.volume);
    }
    return V;
}

/// The Boltzmann-weighted squared terracing error E² = Σ_s Σ w e^{−βU} (U − V_s)² over the
/// density's configurations (kJ²/mol² Å³).
inline double designError(const TerraceDesign& d, const PairEnergyDensity& density) {
    const double inf = std::numeric_limits<double>::infinity();
    double e2 = 0.0;
    for (std::size_t s = 0; s < d.values.size(); ++s) {
        const auto sum =
            density.over(s == 0 ? -inf : d.levels[s - 1], s == d.levels.size() ? inf : d.levels[s]);
        const double V = d.values[s];
        e2 += sum.squareBoltzmann - 2.0 * V * sum.energyBoltzmann + V * V * sum.boltzmann;
    }
    return e2;
}

/// Lloyd–Max: nBelow levels under 0 and nAbove over it, then the cap; from a uniform start of
/// the given step, iterated until no level moves by more than 1e-12 of the step (or 10⁴ sweeps).
///
/// Each sweep works on the density's sorted samples by index: a terrace's sums are two prefix
/// lookups, and a level's new place, the midpoint of its terraces' energies, lies between its
/// neighbours' old places, so its index is searched there only. The sums and levels are those
/// terraceValues and density.over would give; only the searches are shorter.
inline TerraceDesign optimalDesign(const PairEnergyDensity& density, int nBelow, int nAbove,
                                   double step, double uCap, double uMin) {
    TerraceDesign d;
    for (int k = -nBelow; k <= nAbove; ++k)
        if (k != 0) d.levels.push_back((k > 0 ? k - 0.5 : k + 0.5) * step);
    d.levels.push_back(uCap);
    const std::size_t K = d.levels.size(), free = K - 1; // the cap stays
    std::vector<std::size_t> index(K), next(K);
    for (std::size_t k = 0; k < K; ++k)
        index[k] = density.indexOf(d.levels[k]);
    d.values.assign(K + 1, 0.0);
    auto boltzmannValues = [&] { // terraceValues(d.levels, "boltzmann", density, uMin)
        for (std::size_t s = 0; s <= K; ++s) {
            if (s == K) {
                d.values[s] = d.levels[K - 1];
                continue;
            }
            const double lo = s == 0 ? -std::numeric_limits<double>::infinity() : d.levels[s - 1];
            const double hi = d.levels[s];
            const auto sum = density.between(s == 0 ? 0 : index[s - 1], index[s]);
            if (lo < 0.0 && hi > 0.0)
                d.values[s] = 0.0;
            else if (!(sum.volume > 0.0) || !(sum.boltzmann > 0.0))
                d.values[s] = 0.5 * ((s == 0 ? uMin : lo) + hi);
            else
                d.values[s] = sum.energyBoltzmann / sum.boltzmann;
        }
    };
    for (int sweep = 0; sweep < 10000; ++sweep) {
        boltzmannValues();
        double moved = 0.0;
        for (std::size_t k = 0; k < free; ++k) {
            const double level = 0.5 * (d.values[k] + d.values[k + 1]);
            moved = std::max(moved, std::abs(level - d.levels[k]));
            d.levels[k] = level;
            next[k] = density.indexOf(level, k == 0 ? 0 : index[k - 1], index[k + 1] + 1);
        }
        std::copy(next.begin(), next.begin() + static_cast<std::ptrdiff_t>(free), index.begin());
        if (moved < 1e-12 * step) break;
    }
    boltzmannValues();
    return d;
}

/// The design a scene asks for (dmd.terraces), or none for the paper's uniform levels with
/// midpoint energies (dmd.dV alone), which the engine keeps in closed form. dV in kT; the model's
/// range bounds the density (for a bare potential, the reach of the level −ΔV/2).
template <PairPotential P>
std::optional<TerraceDesign> designTerraces(const DmdSection& dmd, const P& p, double kT) {
    const auto& t = dmd.terraces;
    if (t.levels == "energy" && t.values == "midpoint" && t.n == 0) return std::nullopt;
    const double uMin = p.minimumEnergy();
    if (!(uMin < 0.0))
        throw SceneError("dmd.terraces: the potential has no well (U_min = " +
                         std::to_string(uMin) + " kJ/mol) to place levels in");
    const double step = t.n > 0 ? -uMin / t.n : dmd.dV * kT;
    const int nWell = t.n > 0 ? t.n : std::max(2, static_cast<int>(std::floor(-uMin / step + 0.5)));
    const double uCap = designCapInKT * kT;
    double rOut = std::numeric_limits<double>::infinity();
    if constexpr (requires { p.range(); }) rOut = p.range();
    if (!std::isfinite(rOut)) rOut = p.reachDistance(-0.5 * step);
    const double rIn = 0.5 * p.reachDistance(uCap);
    const auto density = PairEnergyDensity::build(p, kT, rIn, rOut, uCap);

    TerraceDesign d;
    if (t.levels == "optimal") {
        if (t.values != "boltzmann")
            throw SceneError("dmd.terraces: levels \"optimal\" set their own values (the "
                             "Boltzmann mean of each terrace); give values \"boltzmann\" or none");
        const int nAbove = static_cast<int>(std::floor(optimalWallInKT * kT / step + 0.5));
        const long total = static_cast<long>(nWell) + std::max(1, nAbove) + 1;
        if (total > maxOptimalLevels)
            throw SceneError(
                std::string(t.n > 0 ? "dmd.terraces.n: " : "dmd.dV: its ") + std::to_string(nWell) +
                " levels in the well make " + std::to_string(total) +
                " with those up the wall to " + std::to_string(static_cast<int>(optimalWallInKT)) +
                " kT (U_min = " + std::to_string(uMin) + " kJ/mol, kT = " + std::to_string(kT) +
                " kJ/mol), more than the " + std::to_string(maxOptimalLevels) +
                " an optimal design converges on in seconds: give fewer levels");
        return optimalDesign(density, nWell, std::max(1, nAbove), step, uCap, uMin);
    }
    if (t.levels == "energy") {
        d.levels = energyLevels(uMin, step, uCap);
    } else if (t.levels == "distance" || t.levels == "volume") {
        const ProfileShape shape = profileShape(p, rIn, rOut);
        if (t.levels == "distance")
            d.levels = radialLevels(
                p, shape, rIn, rOut, nWell, uCap, [](double r) { return r; },
                [](double x) { return x; });
        else
            d.levels = radialLevels(
                p, shape, rIn, rOut, nWell, uCap, [](double r) { return r * r * r; },
                [](double x) { return std::cbrt(x); });
    } else {
        throw SceneError(
            "dmd.terraces.levels: must be energy, distance, volume or optimal, got \"" + t.levels +
            "\"");
    }
    d.levels.push_back(uCap); // every placement stops below it
    d.values = terraceValues(d.levels, t.values, density, uMin);
    return d;
}

/// The designs rememberedDesign keeps per potential type: the last few asked for.
inline constexpr std::size_t rememberedDesignsKept = 32;

/// designTerraces, remembered for the process where potentials of type P can be compared: a
/// design is a pure function of the potential, kT, dV and the terrace keys, and one run asks for
/// it three times (its scene's check for swallowed wells, its memory estimate, its engine), each
/// 0.25–0.4 CPU s for the rods (two million pair energies sorted), about as much as a dilute gas's
/// whole production. The same inputs give the same design, bit for bit, as building it
/// again would. `built`, where given, is set to the designs of type P built so far.
template <PairPotential P>
std::optional<TerraceDesign> rememberedDesign(const DmdSection& dmd, const P& p, double kT,
                                              std::size_t* built = nullptr) {
    static std::mutex guard;
    static std::size_t builds = 0;
    struct Kept {
        P potential;
        double kT, dV;
        DmdSection::Terraces terraces;
        std::optional<TerraceDesign> design;
    };
    static std::deque<Kept> designs;
    if constexpr (std::equality_comparable<P>) {
        const std::lock_guard hold(guard);
        for (const Kept& k : designs)
            if (k.kT == kT && k.dV == dmd.dV && k.terraces == dmd.terraces && k.potential == p) {
                if (built) *built = builds;
                return k.design;
            }
    }
    auto design = designTerraces(dmd, p, kT); // a refusal throws, and nothing is kept
    const std::lock_guard hold(guard);
    ++builds;
    if (built) *built = builds;
    if constexpr (std::equality_comparable<P>) {
        designs.push_back({p, kT, dmd.dV, dmd.terraces, design});
        if (designs.size() > rememberedDesignsKept) designs.pop_front();
    }
    return design;
}

} // namespace terrace::dmd
