#pragma once
// Per-body candidate lists with a skin for event-driven dynamics (the Verlet list of Allen &
// Tildesley, "Computer Simulation of Liquids", sec. 5.2, kept valid by events instead of a
// displacement check). Body i's list holds every j with |r_ij| ≤ r_m + skin when i's list
// was last rebuilt, or j's. The lists are symmetric (j listed by i ⇔ i listed by j), and a body's
// list is rebuilt, by an event, when it has moved skin/3 from where the list was built (its
// anchor). Why a third: lists are rebuilt one body at a time, so when i leaves a pair unlisted
// (|r_ij| > r_m + skin), j may already be up to skin/3 from its own anchor, and before either
// rebuilds again i can move skin/3 and j as much as 2·skin/3 more (back through its anchor and
// out the other side, turned round by collisions): together at most the skin, so the pair is
// still no closer than r_m. (With skin/2, the usual rule for lists rebuilt all at once, the
// worst case closes 1.5 skins: a pair of the paper's rods at ΔV = 2 kT came 0.3 Å inside r_m
// unlisted, and crossed three levels unseen.) The torus (minimum-image) distance obeys the
// triangle inequality, so the argument holds across periodic images. Units: Å.
#include "core/vec.hpp"
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

namespace terrace::dmd {

/// A body's list is rebuilt when it has moved this fraction of the skin from its anchor.
inline constexpr double relistFraction = 1.0 / 3.0;
/// Thinnest skin, as a fraction of r_m (tuned on the paper's dense rods, where it is also what
/// the shell rule below gives).
inline constexpr double minimumSkinFraction = 0.15;
/// Bodies aimed at in the shell r_m < r ≤ r_m + skin at the mean number density.
inline constexpr double shellBodies = 5.0;

/// Skin of the candidate lists. A rebuild (a scan of the neighbouring cells) comes every skin/3
/// of travel, and every listed partner is screened at each prediction: a thin skin suits a dense
/// liquid, where the shell fills quickly, and a wide one a gas, where a thin skin would rebuild
/// the lists many times between collisions for no partner gained. So the skin is chosen to hold
/// about `shellBodies` bodies (n: bodies per Å³), at least minimumSkinFraction r_m, and short of
/// reaching past half the box (Å).
inline double listSkin(double rm, double numberDensity, double boxLength) {
    const double shellVolume = shellBodies / numberDensity;
    const double wide = std::cbrt(rm * rm * rm + shellVolume / (4.0 / 3.0 * std::numbers::pi)) - rm;
    return std::max(minimumSkinFraction * rm, std::min(wide, 0.5 * boxLength - rm));
}

class NeighbourLists {
public:
    NeighbourLists(int nBodies, double skin) : skin_(skin), partners_(nBodies), anchor_(nBodies) {}

    double skin() const { return skin_; }
    /// How far a body may move from its anchor before its list must be rebuilt, Å.
    double relistDistance() const { return relistFraction * skin_; }
    const std::vector<int>& partners(int i) const { return partners_[i]; }
    const Vec3& anchor(int i) const { return anchor_[i]; }

    /// Removes i from every list; a rebuild then re-adds it to the partners it keeps.
    void detach(int i) {
        for (const int j : partners_[i]) {
            auto& back = partners_[j];
            back.erase(std::find(back.begin(), back.end(), i));
        }
        partners_[i].clear();
    }
    /// Lists the pair (i, j) on both sides; i must have been detached (no duplicates).
    void link(int i, int j) {
        partners_[i].push_back(j);
        partners_[j].push_back(i);
    }
    void setAnchor(int i, const Vec3& r) { anchor_[i] = r; }

    std::size_t bytesReserved() const {
        std::size_t b =
            partners_.capacity() * sizeof(partners_[0]) + anchor_.capacity() * sizeof(Vec3);
        for (const auto& p : partners_)
            b += p.capacity() * sizeof(int);
        return b;
    }

private:
    double skin_;
    std::vector<std::vector<int>> partners_;
    std::vector<Vec3> anchor_;
};

} // namespace terrace::dmd
