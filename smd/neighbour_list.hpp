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
#include "smd/simd.hpp"
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

constexpr std::uint32_t sameImage = 13; // image code of k = (0, 0, 0)

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

/// Every pair closer than the reach among bodies sorted into m³ cells (slots first[c] ..
/// first[c+1] in cell c, positions x per slot, in the box): for each slot a, the later slots of
/// its own cell, then those of the half stencil.
inline void listCellPairs(NeighbourList& list, int m, std::span<const int> first,
                          std::span<const Vec3> x) {
    const double reach2 = list.reach * list.reach;
    std::array<std::pair<int, std::uint32_t>, 62> stencil;
    for (int cx = 0; cx < m; ++cx)
        for (int cy = 0; cy < m; ++cy)
            for (int cz = 0; cz < m; ++cz) {
                halfStencil(m, cx, cy, cz, stencil);
                const int c = (cx * m + cy) * m + cz;
                for (int a = first[c]; a < first[c + 1]; ++a) {
                    list.start[a] = list.entry.size();
                    const Vec3 xa = x[a];
                    for (int b = a + 1; b < first[c + 1]; ++b) // own cell: later slots
                        if ((xa - x[b]).squaredNorm() < reach2)
                            list.entry.push_back(pack(b, sameImage));
                    for (const auto& [cell, image] : stencil) {
                        const Vec3 xs = xa + list.imageShift[image];
                        for (int b = first[cell]; b < first[cell + 1]; ++b)
                            if ((xs - x[b]).squaredNorm() < reach2)
                                list.entry.push_back(pack(b, image));
                    }
                }
            }
}

#if TERRACE_SMD_AVX2
/// The shuffle that packs the 32-bit lanes set in a 4-bit mask to the front (AVX2 has no
/// compress instruction): byte indices for _mm_shuffle_epi8, per mask.
constexpr std::array<std::array<std::uint8_t, 16>, 16> compressLanes() {
    std::array<std::array<std::uint8_t, 16>, 16> table{};
    for (int mask = 0; mask < 16; ++mask) {
        int out = 0;
        for (int lane = 0; lane < 4; ++lane)
            if (mask >> lane & 1) {
                for (int byte = 0; byte < 4; ++byte)
                    table[mask][4 * out + byte] = std::uint8_t(4 * lane + byte);
                ++out;
            }
        for (; out < 4; ++out) // unused lanes: anything, they are overwritten or cut off
            for (int byte = 0; byte < 4; ++byte)
                table[mask][4 * out + byte] = 0x80;
    }
    return table;
}

/// Candidate positions by component, and the squared reach.
struct Candidates {
    const double *x, *y, *z;
    __m256d reach2;
};

/// The entries of candidate slots [b, end) of one cell closer than the reach to (sx, sy, sz),
/// stored from out on with this image code; returns the new end.
TERRACE_AVX2_INLINE inline std::uint32_t* scanCell(std::uint32_t* out, const Candidates& p,
                                                   __m256d sx, __m256d sy, __m256d sz, int b,
                                                   int end, std::uint32_t image) {
    static constexpr auto shuffles = compressLanes();
    const __m128i laneStep =
        _mm_set_epi32(3 << NeighbourList::imageBits, 2 << NeighbourList::imageBits,
                      1 << NeighbourList::imageBits, 0);
    for (; b < end; b += 4) {
        const __m256d dx = _mm256_sub_pd(sx, _mm256_loadu_pd(p.x + b));
        const __m256d dy = _mm256_sub_pd(sy, _mm256_loadu_pd(p.y + b));
        const __m256d dz = _mm256_sub_pd(sz, _mm256_loadu_pd(p.z + b));
        const __m256d d2 = _mm256_add_pd(
            _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_mul_pd(dz, dz));
        const int within = _mm256_movemask_pd(_mm256_cmp_pd(d2, p.reach2, _CMP_LT_OQ)) &
                           (0xF >> std::max(0, 4 - (end - b)));
        const __m128i entries = _mm_add_epi32(_mm_set1_epi32(int(pack(b, image))), laneStep);
        const __m128i order =
            _mm_loadu_si128(reinterpret_cast<const __m128i*>(shuffles[within].data()));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out), _mm_shuffle_epi8(entries, order));
        out += __builtin_popcount(within);
    }
    return out;
}

/// listCellPairs four candidates at a time, without a branch on the distance test: the entries
/// of the candidates within reach are packed by a shuffle and stored, the end pointer moves by
/// their count. The same entries in the same order (up to pairs within round-off of the reach,
/// where the sum of squares may round differently).
TERRACE_AVX2 inline void listCellPairsAvx2(NeighbourList& list, int m, std::span<const int> first,
                                           std::span<const Vec3> x) {
    const std::size_t n = x.size();
    // Coordinates by component, padded by four far-away bodies for the loads past the end.
    std::vector<double> px(n + 4, 1e300), py(n + 4, 1e300), pz(n + 4, 1e300);
    for (std::size_t a = 0; a < n; ++a)
        px[a] = x[a].x(), py[a] = x[a].y(), pz[a] = x[a].z();
    const Candidates soa{px.data(), py.data(), pz.data(), _mm256_set1_pd(list.reach * list.reach)};
    std::size_t used = 0;
    std::array<std::pair<int, std::uint32_t>, 62> stencil;
    struct Run {
        int firstCell, lastCell;
        std::uint32_t image;
    };
    std::array<Run, 62> run;
    for (int cx = 0; cx < m; ++cx)
        for (int cy = 0; cy < m; ++cy)
            for (int cz = 0; cz < m; ++cz) {
                halfStencil(m, cx, cy, cz, stencil);
                const int c = (cx * m + cy) * m + cz;
                // Room for every candidate of every slot of this cell, plus a store's overhang.
                std::size_t candidates = first[c + 1] - first[c] + 4;
                for (const auto& [cell, image] : stencil)
                    candidates += first[cell + 1] - first[cell];
                const std::size_t need = used + (first[c + 1] - first[c]) * candidates;
                if (list.entry.size() < need) {
                    // Grown by an eighth, not doubled as resize() would: the buffer is the
                    // list, kept from build to build, and only its growth is zero-filled.
                    if (list.entry.capacity() < need) list.entry.reserve(need + need / 8);
                    list.entry.resize(need);
                }
                // Stencil cells that follow each other in memory with one image code (the five
                // along z at each (x, y) offset, unless they wrap) are one run of slots: one
                // scan, fewer loop exits to mispredict. The run after the own cell, (0, 0, 1..2),
                // continues the own cell's later slots.
                int runs = 0;
                for (const auto& [cell, image] : stencil)
                    if (runs > 0 && cell == run[runs - 1].lastCell + 1 &&
                        image == run[runs - 1].image)
                        run[runs - 1].lastCell = cell;
                    else
                        run[runs++] = {cell, cell, image};
                const bool joinsOwn = run[0].firstCell == c + 1 && run[0].image == sameImage;
                std::uint32_t* out = list.entry.data() + used;
                for (int a = first[c]; a < first[c + 1]; ++a) {
                    list.start[a] = std::size_t(out - list.entry.data());
                    __m256d sx = _mm256_set1_pd(px[a]), sy = _mm256_set1_pd(py[a]),
                            sz = _mm256_set1_pd(pz[a]);
                    const int ownEnd = joinsOwn ? first[run[0].lastCell + 1] : first[c + 1];
                    out = scanCell(out, soa, sx, sy, sz, a + 1, ownEnd, sameImage);
                    for (int k = joinsOwn ? 1 : 0; k < runs; ++k) {
                        const Vec3 xs = x[a] + list.imageShift[run[k].image];
                        sx = _mm256_set1_pd(xs.x()), sy = _mm256_set1_pd(xs.y()),
                        sz = _mm256_set1_pd(xs.z());
                        out = scanCell(out, soa, sx, sy, sz, first[run[k].firstCell],
                                       first[run[k].lastCell + 1], run[k].image);
                    }
                }
                used = std::size_t(out - list.entry.data());
            }
    list.entry.resize(used);
}
#endif

} // namespace detail

/// Builds the list for unwrapped body positions r (Å) through a cell list of cells half the
/// reach wide (finer cells scan less empty volume) when the box holds five of them per edge and
/// there are enough bodies to fill them, by all pairs otherwise.
/// The cell path is the AVX2 loop where the processor has it unless `avx2` is false (tests).
/// `visit`, when given, is a permutation of the bodies: the order in which they take their slots
/// (within each cell, and in the all-pairs path) instead of r's own order. A caller that keeps
/// its bodies in another order than the scene's passes the scene's order here, so that the slots,
/// and with them the pair loop's sums, come out the same whatever the order of r.
[[gnu::flatten]] inline void build(NeighbourList& list, const PeriodicBox& box,
                                   std::span<const Vec3> r, bool avx2 = avx2Available(),
                                   std::span<const int> visit = {}) {
    const std::size_t n = r.size();
    if (!visit.empty() && visit.size() != n)
        throw std::invalid_argument("smd neighbour list: the visiting order is not one per body");
    const auto body = [&](std::size_t k) { return visit.empty() ? int(k) : visit[k]; };
    if (n >= (std::size_t{1} << (32 - NeighbourList::imageBits)))
        throw std::length_error("smd neighbour list: too many bodies for 27-bit slots");
    for (int a = 0; a < 27; ++a)
        list.imageShift[a] = -box.length * Vec3(a / 9 - 1, (a / 3) % 3 - 1, a % 3 - 1);
    list.builtAt.assign(r.begin(), r.end());
    std::vector<Vec3> inBox(n);
    for (std::size_t i = 0; i < n; ++i)
        inBox[i] = box.wrap(r[i]);
    const std::size_t previous = list.entry.size();
    const auto clearEntries = [&] { // the AVX2 path overwrites them in place
        list.entry.clear();
        list.entry.reserve(previous + previous / 8);
    };
    list.start.assign(n + 1, 0);
    list.order.resize(n);
    list.offset.resize(n);

    const int m = detail::cellsPerEdge(box.length, list.reach, n);
    if (m == 0) {
        std::vector<Vec3> x(n); // per slot, in the box
        for (std::size_t slot = 0; slot < n; ++slot) {
            const int i = body(slot);
            list.order[slot] = i;
            x[slot] = inBox[i];
            list.offset[slot] = r[i] - inBox[i];
        }
        clearEntries();
        detail::listAllPairs(list, box, x);
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
    for (std::size_t k = 0; k < n; ++k) {
        const int i = body(k);
        const int slot = fill[cellOf[i]]++;
        list.order[slot] = i;
        x[slot] = inBox[i];
        list.offset[slot] = r[i] - inBox[i];
    }

#if TERRACE_SMD_AVX2
    if (avx2) {
        detail::listCellPairsAvx2(list, m, first, x);
        list.start[n] = list.entry.size();
        return;
    }
#else
    (void)avx2; // no AVX2 loop in this build
#endif
    clearEntries();
    detail::listCellPairs(list, m, first, x);
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
