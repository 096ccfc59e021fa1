#pragma once
// Verlet neighbour list with a skin, built from a cell list (Frenkel & Smit, "Understanding
// Molecular Simulation", 2nd ed., sec. 5.3 and app. F): every pair closer than r_u + skin is
// listed once (Newton's third law). The list stays exact -- it holds every pair closer than r_u --
// until some body has moved more than skin/2 since the build, which triggers a rebuild.
//
// Slots: the list numbers bodies by slot, the order of the cell sort (order[slot] = body), so
// that neighbours sit close in memory; the pair loop works on per-slot arrays.
// Periodic images: at the build, each body's unwrapped position r is split into its image in
// [0, L)³ and an offset (a multiple of L), and each listed pair stores which of the 27 neighbouring
// images of the partner is the nearest. With L >= 2(r_u + skin) that image stays the minimum image
// of every listed pair within r_u until the next rebuild, so the pair loop needs no rounding:
//     r_ab = x_a - x_b + shift,   x = r - offset   (a, b slots).
// Units: Å.
#include "core/box.hpp"
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>
#include <stdexcept>
#include <vector>

namespace terrace::smd {

struct NeighbourList {
    double reach = 0.0;                // r_u + skin, Å
    double skin = 0.0;                 // Å
    std::vector<int> order;            // body in each slot
    std::vector<std::size_t> start;    // pairs of slot a: entry[start[a] .. start[a+1])
    std::vector<std::uint32_t> entry;  // (partner slot << imageBits) | image code
    std::array<Vec3, 27> imageShift{}; // added to x_a - x_b for each image code
    std::vector<Vec3> offset;          // per slot: r minus its image in the box at the build
    std::vector<Vec3> builtAt;         // per body: r at the build
    long rebuilds = 0;                 // builds after the first

    static constexpr int imageBits = 5;
    static constexpr std::uint32_t imageMask = (1u << imageBits) - 1;

    std::size_t pairCount() const { return entry.size(); }
};

namespace detail {

/// Cells of width >= reach/2, so that the 5³ stencil around a cell covers the reach; needs five
/// cells per edge (no cell met twice). Wider cells than that when the box is sparse: no more
/// than about two cells per body, since every cell costs a stencil walk even when empty.
/// Returns the number per edge, or 0 when the list is to be built by all pairs.
inline int cellsPerEdge(double boxLength, double reach, std::size_t bodies) {
    const int byWidth = static_cast<int>(std::floor(2.0 * boxLength / reach));
    const int byCount = static_cast<int>(std::cbrt(2.0 * double(bodies)));
    const int m = std::min(byWidth, byCount);
    return m >= 5 ? m : 0;
}

inline std::uint32_t pack(std::size_t slot, std::uint32_t image) {
    return static_cast<std::uint32_t>(slot << NeighbourList::imageBits) | image;
}

/// All pairs a < b by the nearest image (x in [0, L)³, so each component of x_a - x_b lies in
/// (-L, L) and the nearest image is the difference or one box length off).
inline void listAllPairs(NeighbourList& list, const PeriodicBox& box, std::span<const Vec3> x) {
    const double reach2 = list.reach * list.reach, half = 0.5 * box.length;
    const std::size_t n = x.size();
    for (std::size_t a = 0; a < n; ++a) {
        list.start[a] = list.entry.size();
        for (std::size_t b = a + 1; b < n; ++b) {
            Vec3 d = x[a] - x[b];
            std::uint32_t image = 0; // base-3 digits of k + 1, where the image shift is -L k
            for (int c = 0; c < 3; ++c) {
                const int k = int(d[c] > half) - int(d[c] < -half);
                d[c] -= k * box.length;
                image = 3 * image + static_cast<std::uint32_t>(k + 1);
            }
            if (d.squaredNorm() < reach2) list.entry.push_back(pack(b, image));
        }
    }
    list.start[n] = list.entry.size();
}

/// The half of the 5³ stencil that lies after cell (cx, cy, cz) in lexicographic order, so that
/// each pair of neighbouring cells is visited once: the neighbouring cell index and the image
/// code of the bodies found there.
inline void halfStencil(int m, int cx, int cy, int cz,
                        std::array<std::pair<int, std::uint32_t>, 62>& out) {
    for (int d = 63; d < 125; ++d) { // offset (0,0,0) has index 62
        const int c[3] = {cx + d / 25 - 2, cy + (d / 5) % 5 - 2, cz + d % 5 - 2};
        int cell = 0;
        std::uint32_t image = 0;
        for (int a = 0; a < 3; ++a) {
            // Past an edge the stencil wants the bodies of the wrapped cell at x_b + L·wrap:
            // r_ab = x_a - x_b - L·wrap, an image shift -L k with k = wrap.
            const int wrap = int(c[a] >= m) - int(c[a] < 0);
            cell = cell * m + c[a] - wrap * m;
            image = 3 * image + static_cast<std::uint32_t>(wrap + 1);
        }
        out[d - 63] = {cell, image};
    }
}

} // namespace detail

/// Builds the list for unwrapped body positions r (Å) through a cell list of cells half the
/// reach wide (finer cells scan less empty volume) when the box holds five of them per edge and
/// there are enough bodies to fill them, by all pairs otherwise.
[[gnu::flatten]] inline void build(NeighbourList& list, const PeriodicBox& box,
                                   std::span<const Vec3> r) {
    const std::size_t n = r.size();
    if (n >= (std::size_t{1} << (32 - NeighbourList::imageBits)))
        throw std::length_error("smd neighbour list: too many bodies for 27-bit slots");
    for (int a = 0; a < 27; ++a)
        list.imageShift[a] = -box.length * Vec3(a / 9 - 1, (a / 3) % 3 - 1, a % 3 - 1);
    list.builtAt.assign(r.begin(), r.end());
    std::vector<Vec3> inBox(n);
    for (std::size_t i = 0; i < n; ++i)
        inBox[i] = box.wrap(r[i]);
    const std::size_t previous = list.entry.size();
    list.entry.clear();
    list.entry.reserve(previous + previous / 8);
    list.start.assign(n + 1, 0);
    list.order.resize(n);
    list.offset.resize(n);

    const int m = detail::cellsPerEdge(box.length, list.reach, n);
    if (m == 0) {
        std::iota(list.order.begin(), list.order.end(), 0);
        for (std::size_t i = 0; i < n; ++i)
            list.offset[i] = r[i] - inBox[i];
        detail::listAllPairs(list, box, inBox);
        return;
    }
    // Counting sort into cells: the slots of cell c are first[c] .. first[c+1].
    const double cellsPerLength = m / box.length;
    const auto coord = [&](double c) { return std::min(m - 1, int(c * cellsPerLength)); };
    std::vector<int> cellOf(n), first(std::size_t(m) * m * m + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        cellOf[i] = (coord(inBox[i].x()) * m + coord(inBox[i].y())) * m + coord(inBox[i].z());
        ++first[cellOf[i] + 1];
    }
    std::partial_sum(first.begin(), first.end(), first.begin());
    std::vector<int> fill(first.begin(), first.end() - 1);
    std::vector<Vec3> x(n); // per slot, in the box
    for (std::size_t i = 0; i < n; ++i) {
        const int slot = fill[cellOf[i]]++;
        list.order[slot] = static_cast<int>(i);
        x[slot] = inBox[i];
        list.offset[slot] = r[i] - inBox[i];
    }

    const double reach2 = list.reach * list.reach;
    constexpr std::uint32_t sameImage = 13; // k = (0, 0, 0)
    std::array<std::pair<int, std::uint32_t>, 62> stencil;
    for (int cx = 0; cx < m; ++cx)
        for (int cy = 0; cy < m; ++cy)
            for (int cz = 0; cz < m; ++cz) {
                detail::halfStencil(m, cx, cy, cz, stencil);
                const int c = (cx * m + cy) * m + cz;
                for (int a = first[c]; a < first[c + 1]; ++a) {
                    list.start[a] = list.entry.size();
                    const Vec3 xa = x[a];
                    for (int b = a + 1; b < first[c + 1]; ++b) // own cell: later slots
                        if ((xa - x[b]).squaredNorm() < reach2)
                            list.entry.push_back(detail::pack(b, sameImage));
                    for (const auto& [cell, image] : stencil) {
                        const Vec3 xs = xa + list.imageShift[image];
                        for (int b = first[cell]; b < first[cell + 1]; ++b)
                            if ((xs - x[b]).squaredNorm() < reach2)
                                list.entry.push_back(detail::pack(b, image));
                    }
                }
            }
    list.start[n] = list.entry.size();
}

/// The largest squared displacement of any body since the build (Å²); NaN when a position is
/// not finite, so that a blown-up integration cannot pass for a quiet one.
inline double maxSquaredDisplacement(const NeighbourList& list, std::span<const Vec3> r) {
    double largest = 0.0;
    for (std::size_t i = 0; i < r.size(); ++i) {
        const double d2 = (r[i] - list.builtAt[i]).squaredNorm();
        if (std::isnan(d2)) return d2;
        largest = std::max(largest, d2);
    }
    return largest;
}

/// True once some body has moved more than skin/2 since the build: two such bodies could then
/// have come within r_u unlisted.
inline bool needsRebuild(const NeighbourList& list, std::span<const Vec3> r) {
    return !(maxSquaredDisplacement(list, r) <= 0.25 * list.skin * list.skin);
}

} // namespace terrace::smd
