#pragma once
// Per-body candidate lists with a skin for event-driven dynamics (the Verlet list of Allen &
// Tildesley, "Computer Simulation of Liquids", sec. 5.2, kept valid by events instead of a
// displacement check). Body i's list holds every j with |r_ij| ≤ r_m + skin when i's list
// was last rebuilt, or j's. The lists are symmetric (j listed by i ⇔ i listed by j), and a body's
// list is rebuilt, by an event, when it has moved skin/2 from where the list was built (its
// anchor). Why that suffices: a pair unlisted at a rebuild is farther apart than r_m + skin; to
// come within r_m their relative displacement must exceed the skin, so one of the two moves more
// than skin/2 from its anchor first and rebuilds. The torus (minimum-image) distance obeys the
// triangle inequality, so the argument holds across periodic images. Units: Å.
#include "core/vec.hpp"
#include <algorithm>
#include <cstddef>
#include <vector>

namespace terrace::dmd {

class NeighbourLists {
public:
    NeighbourLists(int nBodies, double skin) : skin_(skin), partners_(nBodies), anchor_(nBodies) {}

    double skin() const { return skin_; }
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
