#include "core/start_lattice.hpp"
#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <stdexcept>

namespace terrace {

namespace {

using Half = std::array<int, 3>; // a position or offset in half cells

constexpr Half scBasis[] = {{0, 0, 0}};
constexpr Half fccBasis[] = {{0, 0, 0}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}};
constexpr Half bccBasis[] = {{0, 0, 0}, {1, 1, 1}};

// Half of each nearest shell, one of each ± pair.
constexpr Half scForward[] = {{2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
constexpr Half fccForward[] = {{1, 1, 0}, {1, -1, 0}, {1, 0, 1}, {1, 0, -1}, {0, 1, 1}, {0, 1, -1}};
constexpr Half bccForward[] = {{1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {1, -1, -1}};
// Half of fcc's and bcc's second shell, 6 at the cell edge a along the axes (a/√2 and a√3/2 out
// for the first): where bodies aligned along an axis meet end to end.
constexpr Half cubicSecondForward[] = {{2, 0, 0}, {0, 2, 0}, {0, 0, 2}};

std::span<const Half> basisOf(LatticeKind k) {
    switch (k) {
    case LatticeKind::FaceCentred:
        return fccBasis;
    case LatticeKind::BodyCentred:
        return bccBasis;
    default:
        return scBasis;
    }
}

std::span<const Half> forwardOf(LatticeKind k) {
    switch (k) {
    case LatticeKind::FaceCentred:
        return fccForward;
    case LatticeKind::BodyCentred:
        return bccForward;
    default:
        return scForward;
    }
}

/// The smallest m with b·m³ ≥ n.
int cellsPerSide(int n, int b) {
    int m = std::max(1, static_cast<int>(std::ceil(std::cbrt(double(n) / b) - 1e-9)));
    while (long(b) * m * m * m < n)
        ++m;
    while (m > 1 && long(b) * (m - 1) * (m - 1) * (m - 1) >= n)
        --m;
    return m;
}

} // namespace

LatticeKind latticeKind(const std::string& name) {
    if (name == "sc") return LatticeKind::SimpleCubic;
    if (name == "fcc") return LatticeKind::FaceCentred;
    if (name == "bcc") return LatticeKind::BodyCentred;
    throw std::invalid_argument("unknown lattice \"" + name + "\" (sc, fcc or bcc)");
}

const char* latticeName(LatticeKind kind) {
    switch (kind) {
    case LatticeKind::FaceCentred:
        return "fcc";
    case LatticeKind::BodyCentred:
        return "bcc";
    default:
        return "sc";
    }
}

int LatticeShape::basisSize() const {
    return static_cast<int>(basisOf(kind).size());
}

long LatticeShape::sites() const {
    return long(basisSize()) * m * m * mz;
}

Vec3 LatticeShape::site(long i) const {
    const int b = basisSize();
    const Half beta = basisOf(kind)[std::size_t(i % b)];
    const long c = i / b;
    const long cell3[3] = {c / (long(mz) * m), (c / mz) % m, c % mz};
    Vec3 r;
    for (int d = 0; d < 3; ++d)
        r[d] = kind == LatticeKind::SimpleCubic
                   ? (double(cell3[d]) + 0.5) * cell[d] // the centre of its cell, as always
                   : (double(cell3[d]) + (beta[d] + 0.5) / 2.0) * cell[d];
    return r;
}

SiteList LatticeShape::forwardNeighbours(long i) const {
    return sitesAtOffsets(i, forwardOf(kind));
}

SiteList LatticeShape::forwardSecondNeighbours(long i) const {
    if (kind == LatticeKind::SimpleCubic) return {};
    return sitesAtOffsets(i, cubicSecondForward);
}

SiteList LatticeShape::sitesAtOffsets(long i, std::span<const std::array<int, 3>> offsets) const {
    const auto basis = basisOf(kind);
    const int b = basisSize();
    const long c = i / b;
    const Half beta = basis[std::size_t(i % b)];
    const long cells[3] = {m, m, mz};
    const long h[3] = {2 * (c / (long(mz) * m)) + beta[0], 2 * ((c / mz) % m) + beta[1],
                       2 * (c % mz) + beta[2]};
    SiteList out;
    for (const Half& d : offsets) {
        long cellOf[3];
        Half betaOf{};
        for (int a = 0; a < 3; ++a) {
            const long period = 2 * cells[a];
            const long hj = ((h[a] + d[a]) % period + period) % period;
            cellOf[a] = hj / 2;
            betaOf[a] = int(hj % 2);
        }
        const auto at = std::find(basis.begin(), basis.end(), betaOf);
        // Every offset joins a site to a site of the same lattice: its basis is there.
        const long bj = long(at - basis.begin());
        out.index[std::size_t(out.count++)] =
            ((cellOf[0] * m + cellOf[1]) * mz + cellOf[2]) * b + bj;
    }
    return out;
}

std::vector<Vec3> LatticeShape::firstReciprocal() const {
    const double tau = 2.0 * std::numbers::pi;
    std::vector<Half> millers;
    switch (kind) {
    case LatticeKind::FaceCentred:
        millers = {{1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
        break;
    case LatticeKind::BodyCentred:
        millers = {{1, 1, 0}, {1, -1, 0}, {1, 0, 1}, {1, 0, -1}, {0, 1, 1}, {0, 1, -1}};
        break;
    default:
        millers = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    }
    std::vector<Vec3> k;
    for (const Half& hkl : millers)
        k.emplace_back(tau * hkl[0] / cell.x(), tau * hkl[1] / cell.y(), tau * hkl[2] / cell.z());
    return k;
}

LatticeShape latticeShape(int n, double boxLength, LatticeKind kind, double aspect) {
    LatticeShape s;
    s.kind = kind;
    if (kind == LatticeKind::SimpleCubic && aspect != 1.0) {
        // m² mz ≥ N with (L/mz) / (L/m) = m/mz ≈ aspect: m ≈ (N aspect)^(1/3)
        s.m = std::max(1, static_cast<int>(std::ceil(std::cbrt(n * aspect) - 1e-9)));
        s.mz = std::max(1, (n + s.m * s.m - 1) / (s.m * s.m));
    } else {
        s.m = s.mz = cellsPerSide(n, static_cast<int>(basisOf(kind).size()));
    }
    s.cell = Vec3(boxLength / s.m, boxLength / s.m, boxLength / s.mz);
    switch (kind) {
    case LatticeKind::FaceCentred:
        s.nearest = s.cell.x() / std::sqrt(2.0);
        break;
    case LatticeKind::BodyCentred:
        s.nearest = s.cell.x() * std::sqrt(3.0) / 2.0;
        break;
    default:
        s.nearest = std::min(s.cell.x(), s.cell.z());
    }
    return s;
}

std::vector<Vec3> latticeSites(const LatticeShape& shape, int n) {
    std::vector<Vec3> sites;
    sites.reserve(std::size_t(n));
    for (long i = 0; i < n && i < shape.sites(); ++i)
        sites.push_back(shape.site(i));
    return sites;
}

} // namespace terrace
