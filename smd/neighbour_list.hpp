#pragma once
// Verlet neighbour list with a skin, built from a cell list (Frenkel & Smit, "Understanding
// Molecular Simulation", 2nd ed., sec. 5.3 and app. F): every pair closer than r_u + skin is
// listed once (i < j, for Newton's third law). The list stays exact -- it holds every pair closer
// than r_u -- until some body has moved more than skin/2 since the build, which triggers a rebuild.
//
// Periodic images: at the build, each body's unwrapped position r_i is split into its image in
// [0, L)³ and an offset (a multiple of L), and each listed pair stores which of the 27 neighbouring
// images of j is its minimum image (chosen with PeriodicBox::minimumImage). With L >= 2(r_u + skin)
// that image stays the minimum image of every listed pair within r_u until the next rebuild, so the
// pair loop needs no rounding: r_ij = x_i - x_j + shift, x = r - offset.
// Units: Å.
#include "core/box.hpp"
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

namespace terrace::smd {

struct NeighbourList {
    double reach = 0.0;                // r_u + skin, Å
    double skin = 0.0;                 // Å
    std::vector<std::size_t> start;    // pairs of i: entry[start[i] .. start[i+1])
    std::vector<std::uint32_t> entry;  // (j << imageBits) | image code
    std::array<Vec3, 27> imageShift{}; // added to x_i - x_j for each image code
    std::vector<Vec3> offset;          // r_i minus its image in the box at the build
    std::vector<Vec3> builtAt;         // r_i at the build
    long rebuilds = 0;                 // builds after the first

    static constexpr int imageBits = 5;
    static constexpr std::uint32_t imageMask = (1u << imageBits) - 1;

    std::size_t pairCount() const { return entry.size(); }
};

namespace detail {

/// Image code of the shift -L·n, n ∈ {-1, 0, 1}³, in base 3.
inline std::uint32_t imageCode(const Vec3& n) {
    const auto digit = [](double c) { return static_cast<std::uint32_t>(std::lround(c) + 1); };
    return digit(n.x()) * 9 + digit(n.y()) * 3 + digit(n.z());
}

/// Lists j > i within reach of i (x = positions in the box); candidate js come from `others`.
template <class Candidates>
void listPartners(NeighbourList& list, const PeriodicBox& box, std::span<const Vec3> x,
                  std::size_t i, Candidates&& others) {
    const double reach2 = list.reach * list.reach;
    others([&](std::size_t j) {
        if (j <= i) return;
        const Vec3 d = x[i] - x[j];
        const Vec3 dMin = box.minimumImage(d);
        if (dMin.squaredNorm() >= reach2) return;
        const Vec3 n = (d - dMin) / box.length; // dMin = d - L n
        list.entry.push_back(static_cast<std::uint32_t>(j << NeighbourList::imageBits) |
                             imageCode(n));
    });
}

} // namespace detail

/// Builds the list for unwrapped positions r (Å): through a cell list of cells at least
/// r_u + skin wide when the box holds three or more per edge, by all pairs otherwise.
inline void build(NeighbourList& list, const PeriodicBox& box, std::span<const Vec3> r) {
    const std::size_t n = r.size();
    if (n >= (std::size_t{1} << (32 - NeighbourList::imageBits)))
        throw std::length_error("smd neighbour list: too many bodies for 27-bit indices");
    for (int a = 0; a < 27; ++a) {
        const Vec3 m(a / 9 - 1, (a / 3) % 3 - 1, a % 3 - 1);
        list.imageShift[a] = -box.length * m;
    }
    std::vector<Vec3> x(n);
    list.offset.resize(n);
    list.builtAt.assign(r.begin(), r.end());
    for (std::size_t i = 0; i < n; ++i) {
        x[i] = box.wrap(r[i]);
        list.offset[i] = r[i] - x[i];
    }
    list.entry.clear();
    list.start.assign(n + 1, 0);

    const int cellsPerEdge = static_cast<int>(std::floor(box.length / list.reach));
    if (cellsPerEdge < 3) { // neighbouring cells would repeat: list by all pairs
        for (std::size_t i = 0; i < n; ++i) {
            list.start[i] = list.entry.size();
            detail::listPartners(list, box, x, i, [n](auto&& visit) {
                for (std::size_t j = 0; j < n; ++j)
                    visit(j);
            });
        }
        list.start[n] = list.entry.size();
        return;
    }
    // Cell list as a counting sort: bodies of cell c are member[first[c] .. first[c+1]).
    const int m = cellsPerEdge;
    const double cellsPerLength = m / box.length;
    const auto cellCoord = [&](double c) { return std::min(m - 1, int(c * cellsPerLength)); };
    std::vector<int> cellOf(n), first(std::size_t(m) * m * m + 1, 0), member(n);
    for (std::size_t i = 0; i < n; ++i) {
        const int c = (cellCoord(x[i].x()) * m + cellCoord(x[i].y())) * m + cellCoord(x[i].z());
        cellOf[i] = c;
        ++first[c + 1];
    }
    for (std::size_t c = 1; c < first.size(); ++c)
        first[c] += first[c - 1];
    std::vector<int> fill(first.begin(), first.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
        member[fill[cellOf[i]]++] = static_cast<int>(i);

    const auto wrapCell = [m](int c) { return (c + m) % m; };
    for (std::size_t i = 0; i < n; ++i) {
        list.start[i] = list.entry.size();
        const int cx = cellOf[i] / (m * m), cy = (cellOf[i] / m) % m, cz = cellOf[i] % m;
        detail::listPartners(list, box, x, i, [&](auto&& visit) {
            for (int dx = -1; dx <= 1; ++dx)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dz = -1; dz <= 1; ++dz) {
                        const int c =
                            (wrapCell(cx + dx) * m + wrapCell(cy + dy)) * m + wrapCell(cz + dz);
                        for (int k = first[c]; k < first[c + 1]; ++k)
                            visit(std::size_t(member[k]));
                    }
        });
    }
    list.start[n] = list.entry.size();
}

/// True once some body has moved more than skin/2 since the build: two such bodies could then
/// have come within r_u unlisted.
inline bool needsRebuild(const NeighbourList& list, std::span<const Vec3> r) {
    const double limit2 = 0.25 * list.skin * list.skin;
    for (std::size_t i = 0; i < r.size(); ++i)
        if ((r[i] - list.builtAt[i]).squaredNorm() > limit2) return true;
    return false;
}

} // namespace terrace::smd
