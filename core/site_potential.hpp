#pragma once
// A rigid molecule of Lennard-Jones interaction sites (the paper's site-site form, eq. 5): every
// body carries the same sites at fixed body-frame offsets d_a from its centre of mass, and
//     U = Σ_a Σ_b 4ε_ab[(σ_ab/d_ab)^12 − (σ_ab/d_ab)^6],   d_ab = r_ij + D_ia − D_jb,
//     F_ij = Σ_ab f_ab,   τ_ij = Σ_ab D_ia × f_ab,   τ_ji = −Σ_ab D_jb × f_ab,
// with D_ia the lab offset of site a of body i and f_ab = −∂U_ab/∂d_ab the force on site a of i
// due to site b of j. Unlike sites are mixed by the Lorentz–Berthelot rules, σ_ab = (σ_a + σ_b)/2
// (H. A. Lorentz, Ann. Phys. 248, 127 (1881)) and ε_ab = √(ε_a ε_b) (D. Berthelot, C. R. Acad. Sci.
// 126, 1703 (1898)). Every site pair is plain, uncut Lennard-Jones: the model's cutoff acts on the
// centre distance, in the wrapper (core/smoothed_potential.hpp), so that U_s stays a function of
// the centres' separation times a switch, as for the rods.
//
// Two attitudes: Axis reads the lab image u of the body z axis (a linear molecule, all sites on
// that axis, D = d_z u), Frame the rotation Q body -> lab (D = Q d). Units: Å, kJ/mol, g/mol.
#include "core/pair_potential.hpp"
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace terrace {

/// One interaction site: body-frame offset r from the centre of mass (Å), ε (kJ/mol), σ (Å), and
/// the mass (g/mol) that the inertia helpers below use (the potential never reads it).
struct Site {
    Vec3 r = Vec3::Zero();
    double epsilon = 0.0;
    double sigma = 0.0;
    double mass = 0.0;
};

/// The lab offset of a site at body offset d: along the axis for a linear molecule (d lies on the
/// body z axis, whose image is `axis`), Q d for a frame.
inline Vec3 siteOffset(const Vec3& axis, const Vec3& d) {
    return d.z() * axis;
}
inline Vec3 siteOffset(const Mat3& frame, const Vec3& d) {
    return frame * d;
}

template <AttitudeUse use> struct SitePotential {
    static_assert(use == AttitudeUse::Axis || use == AttitudeUse::Frame,
                  "a site molecule reads its axis (linear molecule) or its frame");
    static constexpr std::string_view name = "sites";
    static constexpr AttitudeUse attitude = use;
    using Orientation = OrientationFor<use>;
    /// Fixed capacity, so that the potential (copied into the engines' pair loops) holds no heap.
    static constexpr int maxSites = 6;

    /// The potential of these sites; throws std::invalid_argument on a count outside
    /// [1, maxSites], σ ≤ 0, ε < 0, no site with ε > 0, a non-finite entry, a negative mass, or
    /// (Axis) a site off the body z axis.
    static SitePotential fromSites(const std::vector<Site>& sites) {
        const auto fail = [](const std::string& what) {
            throw std::invalid_argument("site potential: " + what);
        };
        const int n = static_cast<int>(sites.size());
        if (n < 1 || n > maxSites) {
            std::ostringstream o;
            o << n << " sites given; a site molecule has 1 to " << maxSites;
            fail(o.str());
        }
        double scale = 0.0; // the molecule's length scale, for the on-axis test
        bool interacts = false;
        for (int a = 0; a < n; ++a) {
            const Site& s = sites[a];
            std::ostringstream o;
            o << "site " << a << ": ";
            if (!s.r.allFinite() || !std::isfinite(s.epsilon) || !std::isfinite(s.sigma) ||
                !std::isfinite(s.mass))
                fail(o.str() + "non-finite position, ε, σ or mass");
            if (!(s.sigma > 0.0)) {
                o << "σ = " << s.sigma << " Å; it must be positive";
                fail(o.str());
            }
            if (s.epsilon < 0.0) {
                o << "ε = " << s.epsilon << " kJ/mol; it must not be negative";
                fail(o.str());
            }
            if (s.mass < 0.0) {
                o << "mass = " << s.mass << " g/mol; it must not be negative";
                fail(o.str());
            }
            interacts = interacts || s.epsilon > 0.0;
            scale = std::max({scale, s.r.norm(), s.sigma});
        }
        // All ε = 0 would make U ≡ 0, reached at every distance: no finite reach for u = 0.
        if (!interacts) fail("no site has ε > 0: the molecules would never interact");
        if constexpr (use == AttitudeUse::Axis) {
            // The axis potential reads d_z alone; an off-axis offset would be dropped silently.
            for (int a = 0; a < n; ++a) {
                const Vec3& r = sites[a].r;
                if (std::abs(r.x()) > 1e-12 * scale || std::abs(r.y()) > 1e-12 * scale) {
                    std::ostringstream o;
                    o << "site " << a << " at (" << r.transpose()
                      << ") Å is off the body z axis; a linear (axis) molecule has all its sites "
                         "on it (use the frame form for a nonlinear one)";
                    fail(o.str());
                }
            }
        }
        SitePotential p;
        p.count_ = n;
        for (int a = 0; a < n; ++a) {
            p.sites_[a] = sites[a];
            p.radius_[a] = sites[a].r.norm();
        }
        for (int a = 0; a < n; ++a) {
            for (int b = 0; b < n; ++b) {
                const double sigma = p.mixedSigma(a, b);
                p.mixed_[a][b] = {4.0 * p.mixedEpsilon(a, b), sigma * sigma,
                                  std::pow(2.0, 1.0 / 6.0) * sigma};
            }
        }
        return p;
    }

    int siteCount() const { return count_; }
    const Site& site(int a) const { return sites_[a]; }
    /// Lorentz–Berthelot mixing of sites a and b.
    double mixedSigma(int a, int b) const { return 0.5 * (sites_[a].sigma + sites_[b].sigma); }
    double mixedEpsilon(int a, int b) const {
        return std::sqrt(sites_[a].epsilon * sites_[b].epsilon);
    }

    PairForce evaluate(const Vec3& rij, const Orientation& oi, const Orientation& oj) const {
        std::array<Vec3, maxSites> di, dj; // lab offsets D_ia, D_jb
        offsets(oi, oj, di, dj);
        // Σ_b f_ab per site a of i and Σ_a f_ab per site b of j: a cross product per site, not
        // per pair, gives the torques.
        std::array<Vec3, maxSites> fj;
        for (int b = 0; b < count_; ++b)
            fj[b].setZero();
        PairForce out;
        for (int a = 0; a < count_; ++a) {
            const Vec3 ra = rij + di[a];
            Vec3 fa = Vec3::Zero();
            for (int b = 0; b < count_; ++b) {
                const Vec3 d = ra - dj[b];
                const Mixed& m = mixed_[a][b];
                const double inverse2 = 1.0 / d.squaredNorm(); // the one division
                const double s2 = m.sigma2 * inverse2;
                const double s6 = s2 * s2 * s2;
                const double s12 = s6 * s6;
                out.U += m.fourEpsilon * (s12 - s6);
                // f_ab = −U'(|d|) d/|d| = (24ε/|d|²)[2(σ/|d|)^12 − (σ/|d|)^6] d
                const Vec3 f = (6.0 * m.fourEpsilon * (2.0 * s12 - s6) * inverse2) * d;
                fa += f;
                fj[b] += f;
            }
            out.F += fa;
            out.tauI += di[a].cross(fa);
        }
        for (int b = 0; b < count_; ++b)
            out.tauJ -= dj[b].cross(fj[b]);
        return out;
    }

    double energy(const Vec3& rij, const Orientation& oi, const Orientation& oj) const {
        std::array<Vec3, maxSites> di, dj;
        offsets(oi, oj, di, dj);
        double U = 0.0;
        for (int a = 0; a < count_; ++a) {
            const Vec3 ra = rij + di[a];
            for (int b = 0; b < count_; ++b) {
                // The arithmetic of evaluate(), so that both give U to the bit.
                const Mixed& m = mixed_[a][b];
                const double inverse2 = 1.0 / (ra - dj[b]).squaredNorm();
                const double s2 = m.sigma2 * inverse2;
                const double s6 = s2 * s2 * s2;
                const double s12 = s6 * s6;
                U += m.fourEpsilon * (s12 - s6);
            }
        }
        return U;
    }

    /// Σ_ab (−ε_ab) = −(Σ_a √ε_a)²: every pair at the bottom of its own well at once. Exact for one
    /// site; with more, the pairs cannot all sit at their minima together, the more so the longer
    /// the molecule is against σ. Random sampling in the test finds −3.95ε for a dumbbell of bond
    /// σ/3 (bound −4ε), −1.86 for a planar triatomic (bound −2.07) and −8.9 for a skew four-site
    /// molecule 2 Å across (bound −11.4 kJ/mol): loose by a few to ~25 %. Loose only lowers the
    /// bottom terrace (a level there makes an empty terrace), never misses a configuration.
    double minimumEnergy() const {
        double sum = 0.0;
        forPairs([&](const PairBound& p) { sum -= p.epsilon; });
        return sum;
    }

    /// A lower bound of U over all orientations at centre distance r: each site distance lies in
    /// [r − ρ_a − ρ_b, r + ρ_a + ρ_b] (ρ = |d|, the triangle inequality), where the lowest value of
    /// its Lennard-Jones term is at its minimum 2^(1/6)σ_ab if that is inside, else at the end
    /// nearer to it (the curve falls towards the minimum from either side). The sum of the
    /// terms' minima is not reached in general (they need different orientations). It is
    /// non-decreasing in r wherever r + ρ_a + ρ_b ≥ 2^(1/6)σ_ab for every pair -- over the whole
    /// tail, where the cutoff wrapper bisects it -- and exact for a single site.
    double lowestEnergyAt(double r) const {
        double sum = 0.0;
        forPairs([&](const PairBound& p) {
            sum += lj(std::clamp(p.bottom, r - p.span, r + p.span), p.epsilon, p.sigma);
        });
        return sum;
    }

    /// An upper bound of the largest centre distance at which U = u for some orientation (0 if U
    /// never equals u), exact for a single site; rounded outwards by a few roundings of U.
    ///  - u < 0: every term is at least its Lennard-Jones value at max(2^(1/6)σ_ab, r − ρ_a − ρ_b)
    ///    (the lowest over all site distances ≥ r − ρ_a − ρ_b), so U ≥ L(r) = Σ_ab of those, which
    ///    rises from minimumEnergy() (for r small) towards 0⁻: the reach is the largest r with
    ///    L(r) ≤ u, bracketed by doubling and bisected to 1e-13 relative. Finite, as L → 0 > u.
    ///  - u ≥ 0: U ≤ Σ_ab max(0, LJ_ab(d_ab)) ≤ H(r) = Σ_ab max(0, LJ_ab(r − ρ_a − ρ_b)) (the
    ///    positive part falls with distance; +∞ at or below 0), which falls to 0 at
    ///    R0 = max_ab(σ_ab + ρ_a + ρ_b) over pairs with ε_ab > 0: the reach of u = 0 is R0 (U ≥ 0
    ///    needs some term ≥ 0, some d_ab ≤ σ_ab); of u > 0, the largest r with H(r) ≥ u, bisected.
    double reachDistance(double u) const {
        constexpr double relative = 1e-13;
        constexpr double roundings = 64.0 * std::numeric_limits<double>::epsilon();
        double lo = 0.0, hi = 0.0;
        if (u < 0.0) {
            const double uMin = minimumEnergy();
            if (u <= uMin) return 0.0; // below every configuration (or only touching it, as LJ)
            // L's terms are all negative there, so its round-off is relative to |L|: a few
            // roundings of slack make hi err outwards (and, being relative, still let L rise
            // above u however close u is to 0).
            const auto reached = [&](double r) { return tailBound(r) * (1.0 - roundings) <= u; };
            // L = uMin < u as long as every pair can still sit at its minimum.
            forPairs([&](const PairBound& p) { lo = std::max(lo, p.bottom + p.span); });
            hi = 2.0 * lo;
            while (reached(hi)) {
                lo = hi;
                hi *= 2.0;
            }
            while (hi - lo > relative * hi) {
                const double mid = 0.5 * (lo + hi);
                (reached(mid) ? lo : hi) = mid;
            }
            return hi;
        }
        forPairs([&](const PairBound& p) {
            if (p.epsilon > 0.0) hi = std::max(hi, p.sigma + p.span);
        });
        const double slack = roundings * u;
        const auto reached = [&](double r) { return wallBound(r) >= u - slack; };
        if (u == 0.0 || reached(hi)) return hi;
        while (hi - lo > relative * hi) { // H(0) = +∞ ≥ u > H(hi)
            const double mid = 0.5 * (lo + hi);
            (reached(mid) ? lo : hi) = mid;
        }
        return hi;
    }

    /// The range of U over every configuration whose centre separation differs from rij by at
    /// most `shift` (Å) and whose bodies are turned by at most turnI, turnJ (rad) from oi, oj
    /// (core/pair_potential.hpp RangeBounded). A site ρ from its centre then moves by at most ρ
    /// times the angle (an arc is no shorter than its chord), so the distance of sites a and b
    /// stays within δ = shift + ρ_a turnI + ρ_b turnJ of its value now; over that interval their
    /// LJ is least at its bottom 2^(1/6)σ_ab, or at the end nearer it, and greatest at an end.
    /// +∞ above when two sites could meet.
    EnergyRange energyRange(const Vec3& rij, const Orientation& oi, const Orientation& oj,
                            double shift, double turnI, double turnJ) const {
        std::array<Vec3, maxSites> di, dj;
        offsets(oi, oj, di, dj);
        const auto lj = [](const Mixed& m, double x) {
            const double s2 = m.sigma2 / (x * x);
            const double s6 = s2 * s2 * s2;
            return m.fourEpsilon * (s6 * s6 - s6);
        };
        EnergyRange out;
        for (int a = 0; a < count_; ++a) {
            const Vec3 ra = rij + di[a];
            for (int b = 0; b < count_; ++b) {
                const Mixed& m = mixed_[a][b];
                if (m.fourEpsilon == 0.0) continue;
                const double d = (ra - dj[b]).norm();
                const double delta = shift + radius_[a] * turnI + radius_[b] * turnJ;
                const double lo = d - delta, hi = d + delta;
                if (!(lo > 0.0)) {
                    out.lo += lj(m, std::min(m.bottom, hi));
                    out.hi = std::numeric_limits<double>::infinity();
                    continue;
                }
                out.lo += lj(m, std::clamp(m.bottom, lo, hi));
                out.hi += std::max(lj(m, lo), lj(m, hi));
            }
        }
        return out;
    }

    /// The largest site offset max_a |d_a| (Å): a site lies within this of its body's centre.
    double extent() const {
        double rho = 0.0;
        for (int a = 0; a < count_; ++a)
            rho = std::max(rho, radius_[a]);
        return rho;
    }

private:
    struct Mixed {
        double fourEpsilon = 0.0; // 4ε_ab, kJ/mol
        double sigma2 = 0.0;      // σ_ab², Å²
        double bottom = 0.0;      // 2^(1/6)σ_ab, Å: where the pair's LJ is least
    };
    /// What the bounds need of a site pair.
    struct PairBound {
        double epsilon, sigma, bottom; // ε_ab, σ_ab, 2^(1/6)σ_ab
        double span;                   // ρ_a + ρ_b: how far the site distance can stray from r
    };

    std::array<Site, maxSites> sites_{};
    std::array<double, maxSites> radius_{}; // |d_a|, Å: kept for energyRange, the hold screen
    std::array<std::array<Mixed, maxSites>, maxSites> mixed_{};
    int count_ = 0;

    void offsets(const Orientation& oi, const Orientation& oj, std::array<Vec3, maxSites>& di,
                 std::array<Vec3, maxSites>& dj) const {
        for (int a = 0; a < count_; ++a) {
            di[a] = siteOffset(oi, sites_[a].r);
            dj[a] = siteOffset(oj, sites_[a].r);
        }
    }

    template <class Fn> void forPairs(Fn&& fn) const {
        const double twoToTheSixth = std::pow(2.0, 1.0 / 6.0);
        for (int a = 0; a < count_; ++a) {
            for (int b = 0; b < count_; ++b) {
                const double sigma = mixedSigma(a, b);
                fn(PairBound{mixedEpsilon(a, b), sigma, twoToTheSixth * sigma,
                             radius_[a] + radius_[b]});
            }
        }
    }

    /// 4ε[(σ/x)^12 − (σ/x)^6], with the limits the bounds need: 0 for ε = 0, +∞ for x ≤ 0.
    static double lj(double x, double epsilon, double sigma) {
        if (epsilon == 0.0) return 0.0;
        if (x <= 0.0) return std::numeric_limits<double>::infinity();
        return detail::lennardJones(x, epsilon, sigma).U;
    }
    /// L(r) of reachDistance(): non-decreasing, a lower bound of U at centre distance r.
    double tailBound(double r) const {
        double sum = 0.0;
        forPairs([&](const PairBound& p) {
            sum += lj(std::max(p.bottom, r - p.span), p.epsilon, p.sigma);
        });
        return sum;
    }
    /// H(r) of reachDistance(): non-increasing, an upper bound of U at centre distance r.
    double wallBound(double r) const {
        double sum = 0.0;
        forPairs(
            [&](const PairBound& p) { sum += std::max(0.0, lj(r - p.span, p.epsilon, p.sigma)); });
        return sum;
    }
};

/// The sites' centre of mass, Σ m d / Σ m (Å, body frame); throws if the total mass is not
/// positive.
inline Vec3 siteCentreOfMass(const std::vector<Site>& sites) {
    double mass = 0.0;
    Vec3 moment = Vec3::Zero();
    for (const Site& s : sites) {
        mass += s.mass;
        moment += s.mass * s.r;
    }
    if (!(mass > 0.0))
        throw std::invalid_argument("site molecule: the total mass must be positive");
    return moment / mass;
}

/// The inertia tensor of the sites as point masses about the body origin (the centre of mass when
/// the offsets are taken from it): I = Σ m (|d|² 1 − d dᵀ), g/mol Å², body frame.
inline Mat3 siteInertiaTensor(const std::vector<Site>& sites) {
    Mat3 inertia = Mat3::Zero();
    for (const Site& s : sites)
        inertia += s.mass * (s.r.squaredNorm() * Mat3::Identity() - s.r * s.r.transpose());
    return inertia;
}

/// Whether the offsets are in the principal frame the engines assume (body-frame inertia
/// diagonal, origin at the centre of mass): |centre of mass| ≤ tol · max|d| and every off-diagonal
/// element of I within tol · (its largest diagonal element).
inline bool sitesInPrincipalFrame(const std::vector<Site>& sites, double tol = 1e-9) {
    double length = 0.0;
    for (const Site& s : sites)
        length = std::max(length, s.r.norm());
    if (siteCentreOfMass(sites).norm() > tol * length) return false;
    const Mat3 inertia = siteInertiaTensor(sites);
    const double scale = inertia.diagonal().maxCoeff();
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            if (i != j && std::abs(inertia(i, j)) > tol * scale) return false;
        }
    }
    return true;
}

} // namespace terrace
