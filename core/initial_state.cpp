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
