// The start lattices (core/start_lattice.hpp): each site's nearest shell found by brute force
// over the periodic box against the lattice's own count and distance (12 at a/√2 fcc, 8 at a√3/2
// bcc, 6 at a sc), the forward neighbours against that shell, fcc's and bcc's second shell (6 at
// a) against theirs, the box filled by the smallest
// lattice that holds N, and the structure factor at the first reciprocal vectors.
#include "core/box.hpp"
#include "core/start_lattice.hpp"
#include <algorithm>
#include <complex>
#include <gtest/gtest.h>
#include <numbers>
#include <set>

namespace test_start_lattice {

using namespace terrace;

namespace {

constexpr double L = 30.0;
constexpr double distanceTol = 1e-9; // Å: distances between sites, to the box's round-off
constexpr double phaseTol = 1e-9;    // |(1/N) Σ e^{ik·r}| of a perfect lattice, to round-off

struct Case {
    LatticeKind kind;
    int cells;      // per side
    int shell;      // nearest neighbours
    double nearest; // in cell edges
};

const Case cases[] = {{LatticeKind::SimpleCubic, 4, 6, 1.0},
                      {LatticeKind::FaceCentred, 3, 12, 1.0 / std::numbers::sqrt2},
                      {LatticeKind::BodyCentred, 3, 8, std::numbers::sqrt3 / 2.0}};

int sitesPerCell(LatticeKind k) {
    return k == LatticeKind::FaceCentred ? 4 : k == LatticeKind::BodyCentred ? 2 : 1;
}

/// The pairs (i < j) of sites within the nearest distance, by brute force.
std::set<std::pair<long, long>> nearestPairs(const std::vector<Vec3>& r, double nearest) {
    PeriodicBox box;
    box.length = L;
    std::set<std::pair<long, long>> pairs;
    for (long i = 0; i < long(r.size()); ++i)
        for (long j = i + 1; j < long(r.size()); ++j) {
            const double d = box.minimumImage(r[i] - r[j]).norm();
            EXPECT_GT(d, nearest - distanceTol) << i << " " << j << ": closer than the shell";
            if (d < nearest + distanceTol) pairs.insert({i, j});
        }
    return pairs;
}

} // namespace

TEST(StartLattice, EverySiteHasItsShellAtTheNearestDistance) {
    for (const Case& c : cases) {
        const int n = sitesPerCell(c.kind) * c.cells * c.cells * c.cells;
        const LatticeShape shape = latticeShape(n, L, c.kind);
        ASSERT_EQ(shape.m, c.cells) << latticeName(c.kind);
        EXPECT_NEAR(shape.nearest, c.nearest * L / c.cells, distanceTol);
        const auto sites = latticeSites(shape, n);
        const auto pairs = nearestPairs(sites, shape.nearest);
        std::vector<int> coordination(std::size_t(n), 0);
        for (const auto& [i, j] : pairs)
            ++coordination[std::size_t(i)], ++coordination[std::size_t(j)];
        for (int i = 0; i < n; ++i)
            EXPECT_EQ(coordination[std::size_t(i)], c.shell) << latticeName(c.kind) << " " << i;
        // The forward neighbours are that shell, each pair from one side.
        std::set<std::pair<long, long>> forward;
        for (long i = 0; i < n; ++i)
            for (const long j : shape.forwardNeighbours(i))
                EXPECT_TRUE(forward.insert({std::min(i, j), std::max(i, j)}).second)
                    << latticeName(c.kind) << ": pair " << i << "-" << j << " twice";
        EXPECT_EQ(forward, pairs) << latticeName(c.kind);
    }
}

// fcc's and bcc's second shell, 6 at the cell edge a, is what forwardSecondNeighbours gives, each
// pair once; sc has none (its nearest shell lies along the axes already).
TEST(StartLattice, FccAndBccSecondShellIsAtTheCellEdge) {
    for (const Case& c : cases) {
        const int n = sitesPerCell(c.kind) * c.cells * c.cells * c.cells;
        const LatticeShape shape = latticeShape(n, L, c.kind);
        std::set<std::pair<long, long>> second;
        for (long i = 0; i < n; ++i)
            for (const long j : shape.forwardSecondNeighbours(i))
                EXPECT_TRUE(second.insert({std::min(i, j), std::max(i, j)}).second)
                    << latticeName(c.kind) << ": pair " << i << "-" << j << " twice";
        if (c.kind == LatticeKind::SimpleCubic) {
            EXPECT_TRUE(second.empty());
            continue;
        }
        // The pairs at a exactly, by brute force; none of them in the nearest shell.
        const auto sites = latticeSites(shape, n);
        const auto nearestShell = nearestPairs(sites, shape.nearest);
        const double a = shape.cell.x();
        std::set<std::pair<long, long>> shell;
        PeriodicBox box;
        box.length = L;
        for (long i = 0; i < n; ++i)
            for (long j = i + 1; j < n; ++j)
                if (std::abs(
                        box.minimumImage(sites[std::size_t(i)] - sites[std::size_t(j)]).norm() -
                        a) < distanceTol)
                    shell.insert({i, j});
        EXPECT_EQ(shell.size(), std::size_t(3 * n)) << latticeName(c.kind); // 6 each, halved
        EXPECT_EQ(second, shell) << latticeName(c.kind);
        EXPECT_TRUE(std::none_of(nearestShell.begin(), nearestShell.end(),
                                 [&](const auto& p) { return second.count(p) > 0; }));
    }
}

TEST(StartLattice, TheSmallestLatticeThatHoldsNFillsTheBox) {
    for (const Case& c : cases) {
        const int b = sitesPerCell(c.kind);
        for (const int n : {2, 31, 32, 33, 100, 500, 1000}) {
            const LatticeShape shape = latticeShape(n, L, c.kind);
            const long m = shape.m;
            EXPECT_EQ(shape.mz, shape.m);
            EXPECT_GE(b * m * m * m, n) << latticeName(c.kind) << " " << n;
            EXPECT_LT(b * (m - 1) * (m - 1) * (m - 1), n) << latticeName(c.kind) << " " << n;
            EXPECT_DOUBLE_EQ(shape.cell.x(), L / double(m));
            // The full lattice's number density is the box's when N fills it: B/a³ = B m³/L³.
            EXPECT_NEAR(b / std::pow(shape.cell.x(), 3), double(shape.sites()) / (L * L * L),
                        1e-15);
            for (const Vec3& r : latticeSites(shape, n))
                for (int d = 0; d < 3; ++d) {
                    EXPECT_GT(r[d], 0.0);
                    EXPECT_LT(r[d], L);
                }
        }
    }
    // 500 fcc bodies: 5³ cells of 4, every site used.
    EXPECT_EQ(latticeShape(500, L, LatticeKind::FaceCentred).sites(), 500);
    EXPECT_EQ(latticeShape(432, L, LatticeKind::BodyCentred).sites(), 432);
}

TEST(StartLattice, StructureFactorIsNAtTheFirstReciprocalVectors) {
    for (const Case& c : cases) {
        const int n = sitesPerCell(c.kind) * c.cells * c.cells * c.cells;
        const LatticeShape shape = latticeShape(n, L, c.kind);
        const auto sites = latticeSites(shape, n);
        const auto ks = shape.firstReciprocal();
        EXPECT_EQ(ks.size(), c.kind == LatticeKind::FaceCentred   ? 4u
                             : c.kind == LatticeKind::BodyCentred ? 6u
                                                                  : 3u);
        auto amplitude = [&](const Vec3& k) {
            std::complex<double> sum = 0.0;
            for (const Vec3& r : sites)
                sum += std::polar(1.0, k.dot(r));
            return std::abs(sum) / n;
        };
        for (const Vec3& k : ks)
            EXPECT_NEAR(amplitude(k), 1.0, phaseTol) << latticeName(c.kind);
        // The simple-cubic (100) vector of the conventional cell is extinct on fcc and bcc: the
        // vector a simple-cubic melt check would have used sees them as disordered.
        if (c.kind != LatticeKind::SimpleCubic) {
            EXPECT_NEAR(amplitude(Vec3(2.0 * std::numbers::pi / shape.cell.x(), 0, 0)), 0.0,
                        phaseTol)
                << latticeName(c.kind);
        }
    }
}

TEST(StartLattice, SimpleCubicIsTheLatticeItAlwaysWas) {
    // The sites at the cells' centres, x slowest and z fastest, as runs have always started.
    const LatticeShape shape = latticeShape(30, L, LatticeKind::SimpleCubic);
    ASSERT_EQ(shape.m, 4);
    const auto sites = latticeSites(shape, 30);
    ASSERT_EQ(sites.size(), 30u);
    EXPECT_EQ(sites[0], Vec3(0.5 * 7.5, 0.5 * 7.5, 0.5 * 7.5));
    EXPECT_EQ(sites[1], Vec3(0.5 * 7.5, 0.5 * 7.5, 1.5 * 7.5));
    EXPECT_EQ(sites[4], Vec3(0.5 * 7.5, 1.5 * 7.5, 0.5 * 7.5));
    EXPECT_EQ(sites[16], Vec3(1.5 * 7.5, 0.5 * 7.5, 0.5 * 7.5));
    // Stretched along z: fewer, longer cells along z.
    const LatticeShape stretched = latticeShape(512, L, LatticeKind::SimpleCubic, 3.0);
    EXPECT_EQ(stretched.m, 12);
    EXPECT_EQ(stretched.mz, 4);
    EXPECT_DOUBLE_EQ(stretched.nearest, L / 12);
}

TEST(StartLattice, NamesAreTheScenesValues) {
    for (const char* name : {"sc", "fcc", "bcc"})
        EXPECT_STREQ(latticeName(latticeKind(name)), name);
    EXPECT_THROW(latticeKind("hcp"), std::invalid_argument);
}

} // namespace test_start_lattice
