#include "core/initial_state.hpp"
#include <functional>

namespace terrace {

std::mt19937_64 namedStream(std::uint64_t seed, const std::string& purpose) {
    // Mix the purpose into the seed through seed_seq so that streams of different purposes are
    // unrelated even for neighbouring seeds. std::hash of a string is not specified to be stable
    // across library versions, so hash the bytes ourselves (FNV-1a).
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : purpose)
        h = (h ^ c) * 1099511628211ull;
    std::seed_seq seq{std::uint32_t(seed), std::uint32_t(seed >> 32), std::uint32_t(h),
                      std::uint32_t(h >> 32)};
    return std::mt19937_64(seq);
}

namespace detail {

std::vector<Vec3> cubicLattice(int n, double boxLength) {
    int m = static_cast<int>(std::ceil(std::cbrt(double(n)) - 1e-9));
    while (m * m * m < n)
        ++m;
    const double a = boxLength / m;
    std::vector<Vec3> sites;
    sites.reserve(n);
    for (int x = 0; x < m && int(sites.size()) < n; ++x)
        for (int y = 0; y < m && int(sites.size()) < n; ++y)
            for (int z = 0; z < m && int(sites.size()) < n; ++z)
                sites.emplace_back((x + 0.5) * a, (y + 0.5) * a, (z + 0.5) * a);
    return sites;
}

Lattice elongatedLattice(int n, double boxLength, double aspect) {
    Lattice l;
    if (aspect == 1.0) {
        l.sites = cubicLattice(n, boxLength);
        l.m = l.mz = static_cast<int>(std::ceil(std::cbrt(double(n)) - 1e-9));
        while (l.m * l.m * l.m < n)
            l.m = ++l.mz;
    } else {
        // m² mz ≥ N with (L/mz) / (L/m) = m/mz ≈ aspect: m ≈ (N aspect)^(1/3)
        l.m = std::max(1, static_cast<int>(std::ceil(std::cbrt(n * aspect) - 1e-9)));
        l.mz = std::max(1, (n + l.m * l.m - 1) / (l.m * l.m));
        const double a = boxLength / l.m, c = boxLength / l.mz;
        l.sites.reserve(n);
        for (int x = 0; x < l.m && int(l.sites.size()) < n; ++x)
            for (int y = 0; y < l.m && int(l.sites.size()) < n; ++y)
                for (int z = 0; z < l.mz && int(l.sites.size()) < n; ++z)
                    l.sites.emplace_back((x + 0.5) * a, (y + 0.5) * a, (z + 0.5) * c);
    }
    l.spacing = Vec3(boxLength / l.m, boxLength / l.m, boxLength / l.mz);
    return l;
}

Vec3 randomUnitVector(std::mt19937_64& rng) {
    std::normal_distribution<double> gauss(0.0, 1.0);
    while (true) { // a normalised Gaussian vector is uniform on the sphere
        const Vec3 g(gauss(rng), gauss(rng), gauss(rng));
        const double n = g.norm();
        if (n > 1e-8) return g / n;
    }
}

Mat3 randomRotation(std::mt19937_64& rng) {
    std::normal_distribution<double> gauss(0.0, 1.0);
    // A normalised Gaussian 4-vector is a uniform unit quaternion, i.e. Haar measure on SO(3).
    Quat q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
    q.normalize();
    return q.toRotationMatrix();
}

Vec3 anyPerpendicular(const Vec3& s) {
    const Vec3 trial = std::abs(s.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    return (trial - trial.dot(s) * s).normalized();
}

} // namespace detail
} // namespace terrace
