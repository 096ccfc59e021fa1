#pragma once
// The lattices a scene can start on (state.lattice), filling the cubic box of side L:
//   sc   simple cubic, one site per cell; with state.lattice_aspect ≠ 1 its cell is stretched
//        along z (m cells along x and y, mz along z)
//   fcc  face-centred cubic, four sites per conventional cell: 12 nearest neighbours at a/√2
//   bcc  body-centred cubic, two sites per conventional cell: 8 nearest neighbours at a√3/2
// A start of N bodies takes the first N sites of the smallest lattice of m³ conventional cells
// that holds them (B m³ ≥ N, B sites per cell), cell by cell (x slowest, z fastest), the sites of
// a cell together. Positions within a cell are in half cells: a site's half-cell coordinates
// h = 2·cell + basis, which lets a neighbour be found by adding an integer offset.
#include "core/vec.hpp"
#include <array>
#include <span>
#include <string>
#include <vector>

namespace terrace {

enum class LatticeKind { SimpleCubic, FaceCentred, BodyCentred };

/// "sc", "fcc" or "bcc" (as state.lattice holds them); std::invalid_argument for another.
LatticeKind latticeKind(const std::string& name);
const char* latticeName(LatticeKind kind);

/// Up to six site indices, held in place (a start of 10⁸ bodies asks for each body's).
struct SiteList {
    std::array<long, 6> index{};
    int count = 0;
    const long* begin() const { return index.data(); }
    const long* end() const { return index.data() + count; }
};

/// A lattice's geometry, without its sites (a melt check of 10⁸ bodies needs no list of them).
struct LatticeShape {
    LatticeKind kind = LatticeKind::SimpleCubic;
    int m = 0, mz = 0;        // conventional cells along x and y, along z
    Vec3 cell = Vec3::Zero(); // the conventional cell's edges, Å
    double nearest = 0.0;     // the nearest-neighbour distance, Å

    /// Sites per conventional cell: 1, 4, 2.
    int basisSize() const;
    /// All sites of the lattice, B m² mz (≥ the bodies placed on it).
    long sites() const;
    /// Site i's position, Å, inside the box.
    Vec3 site(long i) const;
    /// The nearest neighbours of site i on one side (the other half are those that have i on
    /// theirs): 3 for sc (along x, y, z), 6 for fcc, 4 for bcc; periodic, so in a lattice of one
    /// or two cells a neighbour may be i itself or repeat.
    SiteList forwardNeighbours(long i) const;
    /// The second shell of fcc and bcc on one side: 3 of the 6 at the cell edge a, along x, y
    /// and z, the same periodic way; none for sc, whose nearest shell already lies along the axes.
    SiteList forwardSecondNeighbours(long i) const;
    /// The first reciprocal-lattice vectors at which a perfect lattice's structure factor is N,
    /// one of each ± pair, 1/Å: sc (100), (010), (001) (per axis: the cell may be stretched);
    /// fcc the (111) family (4); bcc the (110) family (6). (A simple-cubic (100) vector is
    /// extinct on fcc and bcc: their basis sums to 0 there.)
    std::vector<Vec3> firstReciprocal() const;

private:
    /// The sites at these offsets from site i, in half cells.
    SiteList sitesAtOffsets(long i, std::span<const std::array<int, 3>> offsets) const;
};

/// The lattice of an n-body start in a box of side L. An aspect ≠ 1 stretches the simple-cubic
/// cell (m ≈ (N aspect)^(1/3) cells across, mz = ⌈N/m²⌉ along z); fcc and bcc take aspect 1 only
/// (the scene refuses another, core/scene_state.cpp): stretched, they are neither.
LatticeShape latticeShape(int n, double boxLength, LatticeKind kind, double aspect = 1.0);

/// The first n sites of the lattice, in its order.
std::vector<Vec3> latticeSites(const LatticeShape& shape, int n);

} // namespace terrace
