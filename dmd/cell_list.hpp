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
#include "core/huge_pages.hpp"
#include "core/vec.hpp"
#include "dmd/prefetch.hpp"
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace terrace::dmd {

class CellList {
public:
    /// Cells of edge ≥ minEdge (Å) in a box of edge boxLength (Å), for nBodies bodies.
    CellList(double boxLength, double minEdge, int nBodies) {
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

    /// The Morton (Z-order) code of the cell holding r (Å, any periodic image): the bits of its
    /// three wrapped cell coordinates interleaved, so that cells close in space mostly get close
    /// codes. Bodies numbered by it lie close in memory when they lie close in space.
    std::uint64_t mortonCode(const Vec3& r) const {
        std::uint64_t code = 0;
        for (int a = 0; a < 3; ++a)
            code |= spreadBits(static_cast<std::uint64_t>(
                        wrap(static_cast<std::int64_t>(std::floor(r[a] / edge_)))))
                    << (2 - a);
        return code;
    }
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

    /// Asks the caches for body i's cell coordinates, which its next crossing time reads.
    [[gnu::always_inline]] void prefetch(int i) const {
        prefetchLines(&coord_[i], sizeof(coord_[i]));
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
        forEachNeighbourWithin(i, nullptr, 0.0, std::forward<F>(f));
    }

    /// As forEachNeighbour, but skips the cells that lie wholly farther than `reach` (Å) from
    /// body i, at r (its position now, inside its cell; nullptr: none skipped; reach ≤ edge(),
    /// which holds for the engine's lists, whose cells are made as wide as their reach). With cells
    /// a little wider than the reach, as the engine's are, about 12 of the 27 drop out, mostly the
    /// corners, and a list rebuild scans that many fewer bodies.
    template <class F>
    void forEachNeighbourWithin(int i, const Vec3* r, double reach, F&& f) const {
        if (single()) {
            for (int j = head_[0]; j >= 0; j = next_[j])
                if (j != i) f(j);
            return;
        }
        // The three wrapped coordinates along each axis, once: 9 integer divisions instead of the
        // 162 of wrapping every neighbouring cell's coordinates afresh. With the squared gaps
        // from r to the slabs of cells below, at and above i's along each axis (0 for its own);
        // a neighbouring cell is at least as far as its three gaps make together, whichever
        // periodic image of it a body is taken in, since the cells are at least `reach` wide.
        const auto& c = coord_[i];
        std::array<int, 3> x, y, z;
        std::array<std::array<double, 3>, 3> gap{};
        for (int d = 0; d < 3; ++d) {
            x[d] = wrap(c[0] + d - 1);
            y[d] = wrap(c[1] + d - 1);
            z[d] = wrap(c[2] + d - 1);
        }
        double limit = std::numeric_limits<double>::infinity();
        if (r) {
            assert(reach <= edge_ * (1.0 + 1e-9));
            for (int a = 0; a < 3; ++a) {
                const double below = std::max(0.0, (*r)[a] - static_cast<double>(c[a]) * edge_);
                const double above = std::max(0.0, static_cast<double>(c[a] + 1) * edge_ - (*r)[a]);
                gap[a] = {below * below, 0.0, above * above};
            }
            // A relative margin far above the round-off of positions and faces.
            limit = reach * reach * (1.0 + 1e-9);
        }
        // The cells first, then their first bodies, then the chains: each stage's reads are asked
        // of memory together, where walking cell after cell would wait for each head in turn.
        std::array<int, 27> first;
        int cells = 0;
        for (int dx = 0; dx < 3; ++dx)
            for (int dy = 0; dy < 3; ++dy) {
                const double gxy = gap[0][dx] + gap[1][dy];
                for (int dz = 0; dz < 3; ++dz)
                    if (gxy + gap[2][dz] <= limit) {
                        first[cells] = (x[dx] * n_ + y[dy]) * n_ + z[dz];
                        __builtin_prefetch(&head_[first[cells]]);
                        ++cells;
                    }
            }
        for (int c = 0; c < cells; ++c) {
            first[c] = head_[first[c]];
            if (first[c] >= 0) __builtin_prefetch(&next_[first[c]]);
        }
        for (int c = 0; c < cells; ++c)
            for (int j = first[c]; j >= 0; j = next_[j])
                if (j != i) f(j);
    }

    std::size_t bytesReserved() const {
        return (head_.capacity() + next_.capacity() + prev_.capacity() + cell_.capacity()) *
                   sizeof(int) +
               coord_.capacity() * sizeof(coord_[0]);
    }

private:
    /// The low 21 bits of x spread to every third bit (bit k to bit 3k).
    static std::uint64_t spreadBits(std::uint64_t x) {
        x &= 0x1fffff;
        x = (x | x << 32) & 0x1f00000000ffffull;
        x = (x | x << 16) & 0x1f0000ff0000ffull;
        x = (x | x << 8) & 0x100f00f00f00f00full;
        x = (x | x << 4) & 0x10c30c30c30c30c3ull;
        x = (x | x << 2) & 0x1249249249249249ull;
        return x;
    }
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

    int n_ = 1;
    double edge_ = 0.0;
    BodyArray<int> head_, next_, prev_, cell_;
    BodyArray<std::array<std::int64_t, 3>> coord_;
};

} // namespace terrace::dmd
