#pragma once
// Terraced potential (paper eq. 7 and "Model System"; DESIGN.md "Terraced potential").
//
//     V_ij = Σ_k Θ(U_ij − U_k) ΔV_k + V_min,    uniform levels U_k = (k − ½) ΔV
//
// A pair sits on an integer terrace n: the open interval between its lower and upper level.
// With uniform levels terrace n spans ((n − ½)ΔV, (n + ½)ΔV) and carries the energy nΔV, i.e. U
// rounded to the nearest multiple of ΔV, so that far-apart pairs (|U| < ΔV/2) carry none.
// An explicit, increasing list of levels L_0 < … < L_{K−1} (kJ/mol) is also accepted. Its K + 1
// terrace energies V_s (the paper's eq. 7 allows any step ΔV_k = V_k − V_{k−1}) are either given
// — a terrace design (dmd/terrace_design.hpp) — or by default the midpoints of neighbouring levels
// (the outermost terraces repeat the neighbouring step), shifted so that the terrace holding
// U = 0 has energy 0. Either way that terrace has index 0 and energy exactly 0: every far pair
// sits on it. For uniform levels the midpoints reproduce nΔV exactly. A crossing from terrace n
// to m exchanges V_m − V_n with the kinetic energy whatever the levels.
//
// Interaction range r_m: the largest centre distance at which U can reach a level bounding
// terrace 0, from P::reachDistance (paper: r_m = ζ/2 + σ/[½(1 − √(1 − ΔV/2ε))]^{1/6}). Beyond
// r_m the pair is on terrace 0 whatever its orientation.
//
// A level on the potential minimum makes a terrace of zero width (paper, "Model System"): it is
// rejected. Units: kJ/mol, Å.
#include "core/pair_potential.hpp"
#include "core/scene.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace terrace::dmd {

/// A level closer than this to the potential minimum (relative to |U_min|, or absolutely when the
/// minimum is 0) is rejected: the terrace between would be narrower than round-off can resolve.
inline constexpr double minimumClearance = 1e-6;

class TerraceLevels {
public:
    /// Uniform levels (n − ½) step, step in kJ/mol.
    static TerraceLevels uniform(double step) {
        if (!(step > 0.0) || !std::isfinite(step))
            throw SceneError("dmd.dV: must be > 0 and finite, got " + std::to_string(step));
        TerraceLevels t;
        t.step_ = step;
        return t;
    }

    /// Explicit increasing levels in kJ/mol; none may be 0 (far-apart pairs would sit on it).
    /// values: the K + 1 terrace energies from below the lowest level to above the highest, in
    /// kJ/mol, the one holding U = 0 exactly 0; empty for the midpoints.
    static TerraceLevels explicitLevels(std::vector<double> levels,
                                        std::vector<double> values = {}) {
        if (levels.size() < 2)
            throw SceneError("dmd.levels: need at least two levels to define a step height");
        for (std::size_t k = 0; k < levels.size(); ++k) {
            if (!std::isfinite(levels[k]))
                throw SceneError("dmd.levels: level " + std::to_string(k) + " is not finite");
            if (k > 0 && !(levels[k] > levels[k - 1]))
                throw SceneError("dmd.levels: levels must be strictly increasing");
            if (levels[k] == 0.0)
                throw SceneError("dmd.levels: a level at U = 0 would put every far pair on it");
        }
        TerraceLevels t;
        t.levels_ = std::move(levels);
        const auto& L = t.levels_;
        const std::size_t K = L.size();
        t.zeroSlot_ = static_cast<int>(std::upper_bound(L.begin(), L.end(), 0.0) - L.begin());
        if (!values.empty()) {
            if (values.size() != K + 1)
                throw SceneError("dmd.values: " + std::to_string(K) + " levels bound " +
                                 std::to_string(K + 1) + " terraces, got " +
                                 std::to_string(values.size()) + " values");
            for (std::size_t s = 0; s <= K; ++s)
                if (!std::isfinite(values[s]))
                    throw SceneError("dmd.values: value " + std::to_string(s) + " is not finite");
            if (values[t.zeroSlot_] != 0.0)
                throw SceneError("dmd.values: the terrace holding U = 0 (value " +
                                 std::to_string(t.zeroSlot_) +
                                 ") must carry exactly 0, the energy of every far pair");
            t.energy_ = std::move(values);
            return t;
        }
        std::vector<double> energy(K + 1);
        for (std::size_t s = 1; s < K; ++s)
            energy[s] = 0.5 * (L[s - 1] + L[s]);
        energy[0] = L[0] - 0.5 * (L[1] - L[0]);
        energy[K] = L[K - 1] + 0.5 * (L[K - 1] - L[K - 2]);
        const double shift = energy[t.zeroSlot_];
        for (double& e : energy)
            e -= shift;
        t.energy_ = std::move(energy);
        return t;
    }

    /// The levels of a step table (core/step_potential.hpp): increasing levels, all > 0, so that
    /// terrace 0 lies below the first and carries 0, and their K + 1 terrace energies, the first
    /// 0. One level is enough (bare hard spheres), and the last energy may be +∞: a hard core,
    /// which every pair reaching it reflects from (dmd/collision_rule.hpp: a climb of +∞ is never
    /// afforded). The key names the table in errors.
    static TerraceLevels stepped(std::vector<double> levels, std::vector<double> values,
                                 const std::string& key) {
        const std::size_t K = levels.size();
        if (K == 0 || values.size() != K + 1)
            throw SceneError(key + ": " + std::to_string(K) + " steps need " +
                             std::to_string(K + 1) + " terrace energies, got " +
                             std::to_string(values.size()));
        for (std::size_t k = 0; k < K; ++k)
            if (!std::isfinite(levels[k]) || !(levels[k] > (k > 0 ? levels[k - 1] : 0.0)))
                throw SceneError(key + ": step " + std::to_string(k) +
                                 " does not lie strictly inside the one before it");
        for (std::size_t s = 0; s < K; ++s)
            if (!std::isfinite(values[s]))
                throw SceneError(key + ": energy " + std::to_string(s) + " is not finite");
        if (values[0] != 0.0 || std::isnan(values[K]) || values[K] == -HUGE_VAL)
            throw SceneError(key + ": beyond the cutoff the energy is 0, and only the hard core "
                                   "may be infinite");
        TerraceLevels t;
        t.levels_ = std::move(levels);
        t.energy_ = std::move(values);
        t.zeroSlot_ = 0;
        return t;
    }

    bool isUniform() const { return step_ > 0.0; }
    /// The explicit levels and terrace energies (empty for uniform levels), kJ/mol.
    const std::vector<double>& explicitLevelList() const { return levels_; }
    const std::vector<double>& explicitValueList() const { return energy_; }
    double step() const { return step_; }
    /// The smallest distance between two levels (the height scale of grazing checks).
    double smallestStep() const {
        if (isUniform()) return step_;
        // A single level (a stepped hard core) has only its height above terrace 0's floor.
        double h =
            levels_.size() == 1 ? std::abs(levels_[0]) : std::numeric_limits<double>::infinity();
        for (std::size_t k = 1; k < levels_.size(); ++k)
            h = std::min(h, levels_[k] - levels_[k - 1]);
        return h;
    }

    /// Lower level of terrace n (−∞ below the lowest explicit level).
    double lower(int n) const {
        if (isUniform()) return (n - 0.5) * step_;
        const int s = n + zeroSlot_;
        return s <= 0 ? -std::numeric_limits<double>::infinity() : levels_[s - 1];
    }
    /// Upper level of terrace n (+∞ above the highest explicit level).
    double upper(int n) const {
        if (isUniform()) return (n + 0.5) * step_;
        const int s = n + zeroSlot_;
        return s >= static_cast<int>(levels_.size()) ? std::numeric_limits<double>::infinity()
                                                     : levels_[s];
    }
    /// Terraced energy of terrace n, kJ/mol.
    double energy(int n) const { return isUniform() ? n * step_ : energy_[n + zeroSlot_]; }
    int lowestTerrace() const { return isUniform() ? std::numeric_limits<int>::min() : -zeroSlot_; }
    int highestTerrace() const {
        return isUniform() ? std::numeric_limits<int>::max()
                           : static_cast<int>(levels_.size()) - zeroSlot_;
    }

    /// Terrace holding U when U is not on a level. On a level, the terrace the pair is heading
    /// into (by the sign of dU/dt; upwards when dU/dt = 0), so that no zero-time event follows.
    /// "On" a level means within `onLevel` of it: give the event search's level tolerance, for U
    /// evaluated at a level's radius lands a round-off on either side of the level, and one on
    /// the far side of the direction of motion would put the pair on the terrace it is leaving,
    /// an event at once (a lattice start at a level's radius: a cascade of such events at t = 0).
    int terraceOf(double U, double dUdt = 0.0, double onLevel = 0.0) const {
        int n;
        if (isUniform()) {
            n = static_cast<int>(std::floor(U / step_ + 0.5));
        } else {
            n = static_cast<int>(std::upper_bound(levels_.begin(), levels_.end(), U) -
                                 levels_.begin()) -
                zeroSlot_;
        }
        // Floor rounds a value exactly on a level into the upper terrace; correct for the sign.
        if (U <= lower(n) + onLevel && dUdt < 0.0) --n;
        if (U >= upper(n) - onLevel && dUdt >= 0.0) ++n;
        return n;
    }

    /// Reject a level within minimumClearance of the potential's minimum. Uniform levels of
    /// dmd.dV = step/kT (kT > 0 given) name the dV nearest theirs that put the minimum midway
    /// between two levels instead.
    void checkMinimum(double uMin, const std::string& key, double kT = 0.0) const {
        const double tol = minimumClearance * (uMin != 0.0 ? std::abs(uMin) : 1.0);
        if (isUniform()) {
            const double k = std::round(uMin / step_ + 0.5); // level index nearest the minimum
            if (std::abs((k - 0.5) * step_ - uMin) <= tol)
                throw SceneError(
                    key + ": a level falls on the potential minimum U = " + std::to_string(uMin) +
                    " kJ/mol (a terrace of zero width)" + midwaySteps(uMin, 1.0 - k, kT));
            return;
        }
        for (double L : levels_)
            if (std::abs(L - uMin) <= tol)
                throw SceneError(
                    key + ": level " + std::to_string(L) +
                    " kJ/mol falls on the potential minimum (a terrace of zero width)");
    }

private:
    /// With the minimum U_min < 0 on the j-th level below 0, at −(j − ½) ΔV: the heights that put
    /// it midway between two levels, ΔV = |U_min| / j (one more level above it) and |U_min| /
    /// (j − 1) (one fewer; for j = 1 none is left in the well), as "; dmd.dV = ..." in kT.
    static std::string midwaySteps(double uMin, double j, double kT) {
        if (!(kT > 0.0) || !(uMin < 0.0) || j < 1.0) return "";
        auto dV = [&](double levels) {
            std::ostringstream o;
            o.precision(6);
            o << -uMin / (levels * kT);
            return o.str();
        };
        if (j < 2.0)
            return "; dmd.dV = " + dV(j) + " puts it midway between two levels (a dmd.dV above " +
                   dV(j - 0.5) + " leaves no level in the well)";
        return "; dmd.dV = " + dV(j) + " or " + dV(j - 1.0) + " put it midway between two levels";
    }

    double step_ = 0.0;          // > 0: uniform levels
    std::vector<double> levels_; // explicit levels
    std::vector<double> energy_; // explicit: energy by slot (terrace n is slot n + zeroSlot_)
    int zeroSlot_ = 0;
};

/// Interaction range r_m (Å): beyond it U cannot reach either level bounding terrace 0.
template <PairPotential P>
double interactionRange(const TerraceLevels& levels, const P& potential) {
    double rm = 0.0;
    for (double u : {levels.lower(0), levels.upper(0)})
        if (std::isfinite(u)) rm = std::max(rm, static_cast<double>(potential.reachDistance(u)));
    return rm;
}

} // namespace terrace::dmd
