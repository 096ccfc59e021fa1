#pragma once
// Cell list for event-driven dynamics (Rapaport, J. Comput. Phys. 34, 184 (1980); Allen &
// Tildesley, "Computer Simulation of Liquids", sec. 5.3). The periodic box is cut into n³ cubic
// cells of edge w = L/n ≥ r_m, so that every pair closer than r_m lies in the same or adjacent
// cells. Bodies keep unwrapped positions, hence unwrapped integer cell coordinates c = ⌊r/w⌋;
// the cell is c mod n. A body changes cell only through a cell-crossing event, which moves c by
// ±1 along one axis — never through ⌊r/w⌋ at the crossing time, where round-off could leave it in
// place and schedule the same crossing again at zero delay.
// With fewer than 3 cells per side the 27 neighbouring cells would repeat; then one cell holds
// every body and all pairs are neighbours (no crossing events). Units: Å, time unit 100 fs.
#include "core/vec.hpp"
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace terrace::dmd {

class CellList {
public:
    /// Cells of edge ≥ minEdge (Å) in a box of edge boxLength (Å), for nBodies bodies.
    CellList(double boxLength, double minEdge, int nBodies) : box_(boxLength) {
        // Relative safety margin: a cell must not come out a hair smaller than r_m by round-off.
        constexpr double edgeMargin = 1e-9;
        n_ = static_cast<int>(std::floor(boxLength / (minEdge * (1.0 + edgeMargin))));
        if (n_ < 3) n_ = 1;
        edge_ = boxLength / n_;
        head_.assign(static_cast<std::size_t>(n_) * n_ * n_, -1);
        next_.assign(nBodies, -1);
        prev_.assign(nBodies, -1);
        cell_.assign(nBodies, -1);
        coord_.assign(nBodies, {0, 0, 0});
    }

    int cellsPerSide() const { return n_; }
    double edge() const { return edge_; }
    bool single() const { return n_ == 1; }

    void insert(int i, const Vec3& r) {
        for (int a = 0; a < 3; ++a)
            coord_[i][a] = static_cast<std::int64_t>(std::floor(r[a] / edge_));
        link(i);
    }

    /// Body i crosses the face of its cell along axis a, upwards (dir = +1) or downwards (−1).
    void cross(int i, int axis, int dir) {
        unlink(i);
        coord_[i][axis] += dir;
        link(i);
    }

    /// Time until body i at r with velocity v leaves its cell, the axis and the direction.
    double crossingTime(int i, const Vec3& r, const Vec3& v, int& axis, int& dir) const {
        double best = std::numeric_limits<double>::infinity();
        if (single()) return best;
        for (int a = 0; a < 3; ++a) {
            if (v[a] == 0.0) continue;
            const double face = (coord_[i][a] + (v[a] > 0.0 ? 1 : 0)) * edge_;
            const double t = std::max(0.0, (face - r[a]) / v[a]);
            if (t < best) best = t, axis = a, dir = v[a] > 0.0 ? 1 : -1;
        }
        return best;
    }

    /// Calls f(j) for every body j ≠ i in i's cell and the 26 around it.
    template <class F> void forEachNeighbour(int i, F&& f) const {
        if (single()) {
            for (int j = head_[0]; j >= 0; j = next_[j])
                if (j != i) f(j);
            return;
        }
        // The three wrapped coordinates along each axis, once: 9 integer divisions instead of the
        // 162 of wrapping every neighbouring cell's coordinates afresh.
        const auto& c = coord_[i];
        std::array<int, 3> x, y, z;
        for (int d = 0; d < 3; ++d) {
            x[d] = wrap(c[0] + d - 1);
            y[d] = wrap(c[1] + d - 1);
            z[d] = wrap(c[2] + d - 1);
        }
        for (const int cx : x)
            for (const int cy : y)
                for (const int cz : z) {
                    const int cell = (cx * n_ + cy) * n_ + cz;
                    for (int j = head_[cell]; j >= 0; j = next_[j])
                        if (j != i) f(j);
                }
    }

    std::size_t bytesReserved() const {
        return (head_.capacity() + next_.capacity() + prev_.capacity() + cell_.capacity()) *
                   sizeof(int) +
               coord_.capacity() * sizeof(coord_[0]);
    }

private:
    int wrap(std::int64_t c) const { return static_cast<int>(((c % n_) + n_) % n_); }
    int index(std::int64_t x, std::int64_t y, std::int64_t z) const {
        return (wrap(x) * n_ + wrap(y)) * n_ + wrap(z);
    }
    void link(int i) {
        const int c = single() ? 0 : index(coord_[i][0], coord_[i][1], coord_[i][2]);
        cell_[i] = c;
        prev_[i] = -1;
        next_[i] = head_[c];
        if (head_[c] >= 0) prev_[head_[c]] = i;
        head_[c] = i;
    }
    void unlink(int i) {
        const int c = cell_[i];
        if (prev_[i] >= 0)
            next_[prev_[i]] = next_[i];
        else
            head_[c] = next_[i];
        if (next_[i] >= 0) prev_[next_[i]] = prev_[i];
    }

    double box_;
    int n_ = 1;
    double edge_ = 0.0;
    std::vector<int> head_, next_, prev_, cell_;
    std::vector<std::array<std::int64_t, 3>> coord_;
};

} // namespace terrace::dmd
