#pragma once
// Per-body candidate lists with a skin for event-driven dynamics (the Verlet list of Allen &
// Tildesley, "Computer Simulation of Liquids", sec. 5.2, kept valid by events instead of a
// displacement check), and the terrace index of every listed pair. Body i's list holds every j
// with |r_ij| ≤ r_m + skin when i's list was last rebuilt, or j's. The lists are symmetric (j
// listed by i ⇔ i listed by j), and a body's list is rebuilt, by an event, when it has moved
// skin/3 from where the list was built (its anchor). Why a third: lists are rebuilt one body at
// a time, so when i leaves a pair unlisted (|r_ij| > r_m + skin), j may already be up to skin/3
// from its own anchor, and before either rebuilds again i can move skin/3 and j as much as
// 2·skin/3 more (back through its anchor and out the other side, turned round by collisions):
// together at most the skin, so the pair is still no closer than r_m. (With skin/2, the usual
// rule for lists rebuilt all at once, the worst case closes 1.5 skins: a pair of the paper's rods
// at ΔV = 2 kT came 0.3 Å inside r_m unlisted, and crossed three levels unseen.) The torus
// (minimum-image) distance obeys the triangle inequality, so the argument holds across periodic
// images. Units: Å.
//
// The terrace index of each interacting pair is kept explicitly (DESIGN.md "Terraced potential";
// the "capture map" of Thomson, Lue & Bannerman, J. Chem. Phys. 140, 034105 (2014)): an event
// leaves U exactly on a level, where re-deriving the terrace from U is a coin toss, so an index
// changes only when the engine applies a transmission. A pair off terrace 0 is inside r_m, hence
// always listed: the index lives beside the partner in both bodies' lists, and an unlisted pair
// is on terrace 0.
//
// Laid out for a large system, like the agendas (dmd/agendas.hpp): each body owns a record of
// `capacity()` slots in one array, in the engine's body order, its size and spill first, then
// the partners (a prediction reads only these), then their terraces. The capacity is set from the
// number of bodies expected within reach at the mean density, with room for the liquid's
// fluctuations; a list that outgrows its record moves whole into a spill taken from a pool (a
// list is one contiguous run of partners) and back when it fits again. A std::vector per list and
// per body's terraces would add headers, heap-block overhead and the slack of the largest size
// each had reached to every body.
#include "core/huge_pages.hpp"
#include "core/vec.hpp"
#include "dmd/prefetch.hpp"
#include "dmd/spill_pool.hpp"
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <span>
#include <stdexcept>
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

/// Slots in each body's own record: the bodies expected within reach (r_m + skin, Å) at the mean
/// density n (Å⁻³), with room for fluctuations, at most the other bodies. The room is sized so
/// that a list beyond its record is rare; it then only costs a spill.
inline int listCapacity(double reach, double numberDensity, int nBodies) {
    const double expected = numberDensity * 4.0 / 3.0 * std::numbers::pi * reach * reach * reach;
    const double room = 1.2 * expected + 3.0;
    return static_cast<int>(std::clamp(std::ceil(room), 4.0, std::max(4.0, nBodies - 1.0)));
}

class NeighbourLists {
public:
    /// capacity: slots in each body's record (listCapacity).
    NeighbourLists(int nBodies, double skin, int capacity)
        : skin_(skin), capacity_(std::max(capacity, 1)), stride_(headerSlots + 2 * capacity_),
          record_(static_cast<std::size_t>(nBodies) * stride_, 0), anchor_(nBodies) {
        for (int i = 0; i < nBodies; ++i)
            record_[offset(i) + spillSlot] = -1;
    }

    double skin() const { return skin_; }
    int capacity() const { return capacity_; }
    /// How far a body may move from its anchor before its list must be rebuilt, Å.
    double relistDistance() const { return relistFraction * skin_; }
    int size(int i) const { return record_[offset(i) + sizeSlot]; }
    /// i's partners, in the order they were listed. Valid until the lists next change.
    std::span<const std::int32_t> partners(int i) const {
        const std::int32_t s = record_[offset(i) + spillSlot];
        const std::size_t n = static_cast<std::size_t>(size(i));
        return s < 0 ? std::span<const std::int32_t>(&record_[offset(i) + headerSlots], n)
                     : std::span<const std::int32_t>(spill_[s].partner.data(), n);
    }
    const Vec3& anchor(int i) const { return anchor_[i]; }
    /// Asks the caches for i's record: its size, partners and their terraces (a rod's 176 B,
    /// three or four lines as it falls), which an event of i's or a relist beside it walks.
    [[gnu::always_inline]] void prefetch(int i) const {
        prefetchLines(&record_[offset(i)], stride_ * sizeof(std::int32_t));
    }

    /// The terrace index of the pair (i, j): 0 when it is not listed.
    int terrace(int i, int j) const {
        const View v = view(i);
        for (int k = 0; k < v.size; ++k)
            if (v.partner[k] == j) return v.terrace[k];
        return 0;
    }
    /// The same, where j is likely i's partner in slot k (a caller walking i's list): no scan.
    int terrace(int i, int j, int k) const {
        const View v = view(i);
        if (k >= 0 && k < v.size && v.partner[k] == j) return v.terrace[k];
        return terrace(i, j);
    }
    /// Puts the pair (i, j) on terrace n, on both sides. A pair off terrace 0 must be listed.
    void setTerrace(int i, int j, int n) {
        const bool onI = setOne(i, j, n), onJ = setOne(j, i, n);
        if (onI != onJ) throw std::logic_error("dmd: a pair listed on one side only");
        if (!onI && n != 0)
            throw std::logic_error("dmd: a pair off terrace 0 that the lists do not hold");
    }
    /// f(i, j, terrace) once per pair off terrace 0 (i < j).
    template <class F> void forEachPairOffZero(F&& f) const {
        for (int i = 0; i < static_cast<int>(anchor_.size()); ++i) {
            const View v = view(i);
            for (int k = 0; k < v.size; ++k)
                if (v.terrace[k] != 0 && i < v.partner[k])
                    f(i, int(v.partner[k]), int(v.terrace[k]));
        }
    }

    /// Replaces i's list by `within` (none of them i, no duplicates), listed on both sides, and
    /// anchors it at r. The pairs i keeps keep their terraces; a pair off terrace 0 must be kept
    /// (it is inside r_m, and `within` holds everything within r_m + skin).
    void rebuild(int i, std::span<const int> within, const Vec3& r) {
        kept_.clear();
        {
            const View v = view(i);
            for (int k = 0; k < v.size; ++k)
                if (v.terrace[k] != 0) kept_.push_back({v.partner[k], v.terrace[k]});
        }
        detach(i);
        for (const int j : within) {
            append(i, j);
            append(j, i);
        }
        for (const Kept& p : kept_)
            setTerrace(i, p.partner, p.terrace);
        anchor_[i] = r;
    }

    std::size_t bytesReserved() const {
        std::size_t b = record_.capacity() * sizeof(std::int32_t) +
                        anchor_.capacity() * sizeof(Vec3) + spill_.capacity() * sizeof(Spill) +
                        freeSpill_.capacity() * sizeof(int);
        for (const Spill& s : spill_)
            b += s.partner.capacity() * sizeof(std::int32_t) +
                 s.terrace.capacity() * sizeof(std::int32_t);
        return b;
    }
    /// Lists held in a spill now.
    std::size_t spilled() const { return spill_.size() - freeSpill_.size(); }
    /// Spills kept in all (held or idle).
    std::size_t spillsKept() const { return spill_.size(); }
    /// Frees the spills a passing crowd left idle (dmd/spill_pool.hpp compactPool).
    void compactSpills() {
        compactPool(spill_, freeSpill_, [&](auto&& renumber) {
            for (int i = 0; i < static_cast<int>(anchor_.size()); ++i)
                if (record_[offset(i) + spillSlot] >= 0) renumber(record_[offset(i) + spillSlot]);
        });
    }

private:
    // A record: size, spill (index into spill_, or −1), then capacity_ partners and as many
    // terraces.
    static constexpr int sizeSlot = 0, spillSlot = 1, headerSlots = 2;
    struct Spill {
        std::vector<std::int32_t> partner, terrace;
    };
    struct Kept {
        std::int32_t partner, terrace;
    };
    struct View {
        std::int32_t* partner;
        std::int32_t* terrace;
        int size;
    };

    std::size_t offset(int i) const { return static_cast<std::size_t>(i) * stride_; }
    View view(int i) const {
        auto* self = const_cast<NeighbourLists*>(this);
        std::int32_t* rec = &self->record_[offset(i)];
        if (rec[spillSlot] < 0)
            return {rec + headerSlots, rec + headerSlots + capacity_, rec[sizeSlot]};
        Spill& s = self->spill_[rec[spillSlot]];
        return {s.partner.data(), s.terrace.data(), rec[sizeSlot]};
    }

    bool setOne(int i, int j, int n) {
        const View v = view(i);
        for (int k = 0; k < v.size; ++k)
            if (v.partner[k] == j) {
                v.terrace[k] = n;
                return true;
            }
        return false;
    }

    /// Lists j at the end of i's list, on terrace 0; a full record moves into a spill.
    void append(int i, int j) {
        std::int32_t* rec = &record_[offset(i)];
        const int n = rec[sizeSlot];
        if (rec[spillSlot] < 0 && n == capacity_) {
            const int s = takeSpill();
            rec = &record_[offset(i)];
            spill_[s].partner.assign(rec + headerSlots, rec + headerSlots + n);
            spill_[s].terrace.assign(rec + headerSlots + capacity_,
                                     rec + headerSlots + capacity_ + n);
            rec[spillSlot] = s;
        }
        if (rec[spillSlot] < 0) {
            rec[headerSlots + n] = j;
            rec[headerSlots + capacity_ + n] = 0;
        } else {
            spill_[rec[spillSlot]].partner.push_back(j);
            spill_[rec[spillSlot]].terrace.push_back(0);
        }
        rec[sizeSlot] = n + 1;
    }

    /// Removes i from every list and empties i's; the others keep their order.
    void detach(int i) {
        const View mine = view(i);
        for (int k = 0; k < mine.size; ++k)
            removeFrom(mine.partner[k], i);
        truncate(i, 0);
    }
    void removeFrom(int j, int i) {
        const View v = view(j);
        int k = 0;
        while (k < v.size && v.partner[k] != i)
            ++k;
        if (k == v.size) throw std::logic_error("dmd: a pair listed on one side only");
        std::copy(v.partner + k + 1, v.partner + v.size, v.partner + k);
        std::copy(v.terrace + k + 1, v.terrace + v.size, v.terrace + k);
        truncate(j, v.size - 1);
    }
    /// Keeps i's first n entries; a spilled list that fits its record again moves back.
    void truncate(int i, int n) {
        std::int32_t* rec = &record_[offset(i)];
        rec[sizeSlot] = n;
        const int s = rec[spillSlot];
        if (s < 0) return;
        Spill& sp = spill_[s];
        if (n > capacity_) {
            sp.partner.resize(static_cast<std::size_t>(n));
            sp.terrace.resize(static_cast<std::size_t>(n));
            return;
        }
        std::copy(sp.partner.begin(), sp.partner.begin() + n, rec + headerSlots);
        std::copy(sp.terrace.begin(), sp.terrace.begin() + n, rec + headerSlots + capacity_);
        sp.partner.clear();
        sp.terrace.clear();
        freeSpill_.push_back(s);
        rec[spillSlot] = -1;
    }
    int takeSpill() { return takeFromPool(spill_, freeSpill_); }

    double skin_;
    int capacity_;
    std::size_t stride_;
    BodyArray<std::int32_t> record_; // a record of stride_ slots per body
    BodyArray<Vec3> anchor_;
    std::vector<Spill> spill_; // lists beyond their records, pooled
    std::vector<int> freeSpill_;
    std::vector<Kept> kept_; // rebuild: i's pairs off terrace 0
};

} // namespace terrace::dmd
