// Site-site molecules (core/site_potential.hpp):
//  - hand-worked values for a dumbbell (side by side, end to end) and a planar three-site molecule;
//  - F_ij = -∂U/∂r_ij and torques from dU = -τ·δθ under small rotations of either body (fourth-
//    order central differences of U), for linear (axis) and nonlinear (frame) molecules;
//  - F_ij + F_ji = 0, the exchange of i and j, τ_ij + τ_ji + r_ij × F_ij = 0 (paper eq. 6), and
//    invariance under a common rotation;
//  - one site at the origin is Lennard-Jones; axis and frame forms agree on a linear molecule;
//  - minimumEnergy(), lowestEnergyAt() and reachDistance() are valid bounds, also through the
//    smoothed cutoff's reach;
//  - the inertia helpers and fromSites()'s rejections.
#include "core/lj_potential.hpp"
#include "core/site_potential.hpp"
#include "core/smoothed_potential.hpp"

#include "pair_checks.hpp"
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace terrace::test_site_potential {

using pairchecks::centralDerivative;
using pairchecks::closeRelative;
using pairchecks::randomUnit;

using AxisSites = SitePotential<AttitudeUse::Axis>;
using FrameSites = SitePotential<AttitudeUse::Frame>;
static_assert(PairPotential<AxisSites> && PairPotential<FrameSites>);
static_assert(PairPotential<Smoothed<AxisSites>> && PairPotential<Smoothed<FrameSites>>);

constexpr double kEps = std::numeric_limits<double>::epsilon();
// Hand-worked values were evaluated in double precision from the listed distances.
constexpr double kReferenceTol = 1e-12;
// Analytic derivatives against finite differences of U (issue 2's accuracy target).
constexpr double kFiniteDifferenceTol = 1e-7;
// Where a force or torque vanishes, compare against this fraction of its natural scale (ε/σ, ε):
// U's round-off over the step stays well below, a wrong sign or factor far above.
constexpr double kVanishingFraction = 1e-3;
// Identities that hold term by term up to a handful of roundings of the largest term.
constexpr double kRoundOffTol = 256.0 * kEps;
// The range of U over no motion is U itself, to the round-off of its bounds' arithmetic.
constexpr double kStillRangeTol = 1e-9;
// Moments and centres of mass of a few sites with O(1) coordinates and masses: a few ulp.
constexpr double kInertiaTol = 1e-14; // g/mol Å², or relative where scaled
constexpr double kCentreTol = 1e-16;  // Å: the water model's centre, placed at the origin by hand
// Steps of the fourth-order stencil: truncation ~h⁴ on the wall against round-off ~eps·U/h.
constexpr double kTranslationStep = 3e-4; // Å
constexpr double kRotationStep = 3e-4;    // rad
// No site pair closer than this fraction of its σ_ab in the derivative tests (moderate overlap).
constexpr double kClosestSitePair = 0.8;
constexpr int kConfigurations = 150;
constexpr std::uint64_t kSeed = 20240917;

Mat3 randomRotation(std::mt19937_64& rng) {
    std::normal_distribution<double> gauss;
    return Quat(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized().toRotationMatrix();
}
Mat3 rotation(const Vec3& axis, double angle) {
    return Eigen::AngleAxisd(angle, axis).toRotationMatrix();
}

// ---------------------------------------------------------------------------------------------
// Molecules.

// A dumbbell: two identical sites at z = ±ℓ/2.
constexpr double kBond = 1.0, kSigma = 3.0, kEpsilon = 1.0, kSiteMass = 14.0;
std::vector<Site> dumbbell() {
    return {{Vec3(0, 0, 0.5 * kBond), kEpsilon, kSigma, kSiteMass},
            {Vec3(0, 0, -0.5 * kBond), kEpsilon, kSigma, kSiteMass}};
}
// Three unlike sites on a line (every mixing rule at work, no symmetry).
std::vector<Site> linearTriatomic() {
    return {{Vec3(0, 0, -1.2), 0.8, 3.0, 16.0},
            {Vec3(0, 0, 0.1), 0.3, 2.8, 12.0},
            {Vec3(0, 0, 1.0), 1.2, 3.3, 19.0}};
}
// A planar, water-like molecule (not a water model: the light sites interact too).
std::vector<Site> planarTriatomic() {
    return {{Vec3(0, -0.0656, 0), 0.65, 3.15, 16.0},
            {Vec3(0.757, 0.52, 0), 0.1, 2.0, 1.0},
            {Vec3(-0.757, 0.52, 0), 0.1, 2.0, 1.0}};
}
// Four unlike sites in general position (no plane, no symmetry).
std::vector<Site> skewTetratomic() {
    return {{Vec3(0.8, 0.1, -0.3), 1.0, 3.0, 12.0},
            {Vec3(-0.5, 0.7, 0.2), 0.5, 2.5, 14.0},
            {Vec3(-0.2, -0.9, 0.4), 1.5, 3.4, 16.0},
            {Vec3(0.1, 0.2, 0.9), 0.2, 2.0, 1.0}};
}

struct Molecule {
    const char* name;
    std::vector<Site> sites;
};

template <class P> std::vector<Molecule> molecules() {
    std::vector<Molecule> list = {{"dumbbell", dumbbell()}, {"linear", linearTriatomic()}};
    if constexpr (P::attitude == AttitudeUse::Frame) {
        list.push_back({"planar", planarTriatomic()});
        list.push_back({"skew", skewTetratomic()});
    }
    return list;
}

template <class P> typename P::Orientation randomOrientation(std::mt19937_64& rng) {
    if constexpr (P::attitude == AttitudeUse::Frame)
        return randomRotation(rng);
    else
        return randomUnit(rng);
}
template <class P> typename P::Orientation identityOrientation() {
    if constexpr (P::attitude == AttitudeUse::Frame)
        return Mat3::Identity();
    else
        return Vec3::UnitZ();
}

/// A site's lab offset, written out here rather than taken from the header.
Vec3 labOffset(const Vec3& axis, const Site& s) {
    return s.r.z() * axis;
}
Vec3 labOffset(const Mat3& frame, const Site& s) {
    return frame * s.r;
}

/// The smallest site distance in units of its σ_ab.
template <class O>
double closestSitePair(const std::vector<Site>& sites, const Vec3& rij, const O& oi, const O& oj) {
    double closest = std::numeric_limits<double>::infinity();
    for (const Site& a : sites) {
        for (const Site& b : sites) {
            const double d = (rij + labOffset(oi, a) - labOffset(oj, b)).norm();
            closest = std::min(closest, d / (0.5 * (a.sigma + b.sigma)));
        }
    }
    return closest;
}

double largestSigma(const std::vector<Site>& sites) {
    double sigma = 0.0;
    for (const Site& s : sites)
        sigma = std::max(sigma, s.sigma);
    return sigma;
}
double largestEpsilon(const std::vector<Site>& sites) {
    double epsilon = 0.0;
    for (const Site& s : sites)
        epsilon = std::max(epsilon, s.epsilon);
    return epsilon;
}

template <class P> struct Config {
    Vec3 rij;
    typename P::Orientation oi, oj;
};

/// Random pairs with centre distances from deep overlap to the tail, none closer than
/// kClosestSitePair σ_ab at any site pair.
template <class P> std::vector<Config<P>> moderateConfigs(const Molecule& m, std::uint64_t seed) {
    const P p = P::fromSites(m.sites);
    const double sigma = largestSigma(m.sites);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> rDist(0.5 * sigma, 2.0 * sigma + 2.0 * p.extent());
    std::vector<Config<P>> configs;
    while (static_cast<int>(configs.size()) < kConfigurations) {
        const Config<P> c{rDist(rng) * randomUnit(rng), randomOrientation<P>(rng),
                          randomOrientation<P>(rng)};
        if (closestSitePair(m.sites, c.rij, c.oi, c.oj) >= kClosestSitePair) configs.push_back(c);
    }
    return configs;
}

// ---------------------------------------------------------------------------------------------
// Hand-worked values.

TEST(SitePotentialReference, DumbbellSideBySide) {
    // Axes both along z, r_ij = r x̂, r = 3.5 Å, ℓ = 1 Å: like sites (++, --) at r, unlike (+-, -+)
    // at s = √(r² + ℓ²) = √13.25 Å. With LJ(x) = 4[(3/x)^12 - (3/x)^6] kJ/mol:
    //     LJ(3.5) = -0.9572084907712044,   LJ(√13.25) = -0.8607011856994005,
    //     U = 2 LJ(r) + 2 LJ(s) = -3.635819352941210 kJ/mol.
    // The force is along x̂, F = -dU/dr = -[2 LJ'(r) + 2 LJ'(s) r/s] with LJ'(3.5) =
    // 0.5625242659312202, LJ'(s) = 0.77118203857015 kJ/mol/Å: F_x = -2.608068528013777 kJ/mol/Å.
    // The ± mirror images cancel the torques: the + site's pull (z-component +) on i is matched by
    // the - site's (z-component -) about the centre.
    const AxisSites p = AxisSites::fromSites(dumbbell());
    const Vec3 z = Vec3::UnitZ();
    const PairForce f = p.evaluate(Vec3(3.5, 0, 0), z, z);
    EXPECT_TRUE(closeRelative(f.U, -3.635819352941210, kReferenceTol, 0.0));
    EXPECT_TRUE(closeRelative(f.F, Vec3(-2.608068528013777, 0, 0), kReferenceTol, 0.0));
    EXPECT_LE(f.tauI.norm(), kRoundOffTol * 10.0);
    EXPECT_LE(f.tauJ.norm(), kRoundOffTol * 10.0);
    EXPECT_EQ(p.energy(Vec3(3.5, 0, 0), z, z), f.U);
}

TEST(SitePotentialReference, DumbbellEndToEnd) {
    // Axes both along z, r_ij = r ẑ, r = 4 Å: like sites at r, the near pair (- of i, + of j) at
    // r - ℓ = 3 Å = σ, the far pair at r + ℓ = 5 Å:
    //     U = 2 LJ(4) + LJ(3) + LJ(5) = 2(-0.5852086544036865) + 0 + (-0.17791687065599995)
    //       = -1.348334179463373 kJ/mol,
    //     F_z = -[2 LJ'(4) + LJ'(3) + LJ'(5)] = -[2(0.6877548694610596) - 24/3 + 0.20305168957440]
    //         = 6.421438571503481 kJ/mol/Å (repelled: the near pair sits on the wall);
    // every force is along the common axis: no torque.
    const AxisSites p = AxisSites::fromSites(dumbbell());
    const Vec3 z = Vec3::UnitZ();
    const PairForce f = p.evaluate(Vec3(0, 0, 4.0), z, z);
    EXPECT_TRUE(closeRelative(f.U, -1.348334179463373, kReferenceTol, 0.0));
    EXPECT_TRUE(closeRelative(f.F, Vec3(0, 0, 6.421438571503481), kReferenceTol, 0.0));
    EXPECT_EQ(f.tauI, Vec3::Zero());
    EXPECT_EQ(f.tauJ, Vec3::Zero());
    // Flipping either axis swaps the + and - sites of identical atoms: the same pair.
    EXPECT_TRUE(closeRelative(p.energy(Vec3(0, 0, 4.0), -z, z), f.U, kRoundOffTol, 0.0));
}

TEST(SitePotentialReference, PlanarMoleculeInAFrame) {
    // Sites A (0, 1, 0) and B (0, -1, 0) with σ = 3 Å, ε = 1 kJ/mol, C (1, 0, 0) with σ = 2 Å,
    // ε = 0.5 kJ/mol; mixed AC: σ = 2.5 Å, ε = √0.5. Body i unrotated at r_ij = (4, 1, 0), body j
    // turned 90° about z (Q_j: (x, y) -> (-y, x)): j's sites at A (-1, 0, 0), B (1, 0, 0),
    // C (0, 1, 0); i's at A (4, 2, 0), B (4, 0, 0), C (5, 1, 0) relative to j's centre.
    // Separations:
    //     AA (5, 2) √29   AB (3, 2) √13   AC (4, 1) √17
    //     BA (5, 0) 5     BB (3, 0) 3     BC (4,-1) √17
    //     CA (6, 1) √37   CB (4, 1) √17   CC (5, 0) 5
    // U = LJ_AA(3) + LJ_AA(√13) + LJ_AA(5) + LJ_AA(√29) + 3 LJ_AC(√17) + LJ_AC(√37) + LJ_CC(5)
    //   = 0 - 0.8868567204544453 - 0.17791687065599995 - 0.11598832386734882
    //     + 3(-0.13356796539563068) - 0.013566929608620031 - 0.008158445568000003
    //   = -1.603191186341306 kJ/mol.
    // Each f_ab = 24ε_ab[2(σ_ab/d)^12 - (σ_ab/d)^6] d_ab/d²; summed, and crossed with i's offsets
    // (τ_ij) and j's (τ_ji = -Σ D_jb × f_ab): everything lies in the xy plane, torques along z.
    const FrameSites p = FrameSites::fromSites({{Vec3(0, 1, 0), 1.0, 3.0, 1.0},
                                                {Vec3(0, -1, 0), 1.0, 3.0, 1.0},
                                                {Vec3(1, 0, 0), 0.5, 2.0, 1.0}});
    const Mat3 qj = rotation(Vec3::UnitZ(), std::numbers::pi / 2);
    const PairForce f = p.evaluate(Vec3(4, 1, 0), Mat3::Identity(), qj);
    EXPECT_TRUE(closeRelative(f.U, -1.603191186341306, kReferenceTol, 0.0));
    EXPECT_TRUE(
        closeRelative(f.F, Vec3(6.503492601840182, -0.5054890508478669, 0.0), kReferenceTol, 0.0));
    EXPECT_TRUE(closeRelative(f.tauI, Vec3(0, 0, 8.484533437564806), kReferenceTol, 0.0));
    EXPECT_TRUE(closeRelative(f.tauJ, Vec3(0, 0, 0.04091536766684399), 1e-10, 0.0));
}

// ---------------------------------------------------------------------------------------------
// Derivatives and identities, for axis and frame molecules.

template <class P> class SiteContract : public ::testing::Test {};
using SitePotentials = ::testing::Types<AxisSites, FrameSites>;
TYPED_TEST_SUITE(SiteContract, SitePotentials);

TYPED_TEST(SiteContract, ForceAndTorquesAreMinusDerivativesOfU) {
    using P = TypeParam;
    std::uint64_t seed = kSeed;
    for (const Molecule& m : molecules<P>()) {
        const P p = P::fromSites(m.sites);
        const double forceFloor =
            kVanishingFraction * largestEpsilon(m.sites) / largestSigma(m.sites);
        const double torqueFloor = kVanishingFraction * largestEpsilon(m.sites);
        for (const Config<P>& c : moderateConfigs<P>(m, ++seed)) {
            const PairForce f = p.evaluate(c.rij, c.oi, c.oj);
            EXPECT_EQ(f.U, p.energy(c.rij, c.oi, c.oj));
            Vec3 gradU, dUdThetaI, dUdThetaJ;
            for (int a = 0; a < 3; ++a) {
                const Vec3 e = Vec3::Unit(a);
                gradU[a] =
                    centralDerivative([&](double h) { return p.energy(c.rij + h * e, c.oi, c.oj); },
                                      kTranslationStep);
                // Turning body i by δθ about e (its axis, or its whole frame: Q <- R(δθ) Q)
                // changes U by -τ_ij·e δθ; likewise for j.
                dUdThetaI[a] = centralDerivative(
                    [&](double h) {
                        const typename P::Orientation oi = rotation(e, h) * c.oi;
                        return p.energy(c.rij, oi, c.oj);
                    },
                    kRotationStep);
                dUdThetaJ[a] = centralDerivative(
                    [&](double h) {
                        const typename P::Orientation oj = rotation(e, h) * c.oj;
                        return p.energy(c.rij, c.oi, oj);
                    },
                    kRotationStep);
            }
            const double r = c.rij.norm();
            EXPECT_TRUE(closeRelative(f.F, -gradU, kFiniteDifferenceTol, forceFloor))
                << m.name << ", r = " << r;
            EXPECT_TRUE(closeRelative(f.tauI, -dUdThetaI, kFiniteDifferenceTol, torqueFloor))
                << m.name << ", r = " << r;
            EXPECT_TRUE(closeRelative(f.tauJ, -dUdThetaJ, kFiniteDifferenceTol, torqueFloor))
                << m.name << ", r = " << r;
            if constexpr (P::attitude == AttitudeUse::Axis) {
                // Sites on the axis pull along lines through it: no torque about the axis.
                EXPECT_LE(std::abs(f.tauI.dot(c.oi)), kRoundOffTol * (f.tauI.norm() + 1.0));
                EXPECT_LE(std::abs(f.tauJ.dot(c.oj)), kRoundOffTol * (f.tauJ.norm() + 1.0));
            }
        }
    }
}

TYPED_TEST(SiteContract, ActionReactionExchangeAndRotation) {
    using P = TypeParam;
    std::uint64_t seed = kSeed + 100;
    for (const Molecule& m : molecules<P>()) {
        const P p = P::fromSites(m.sites);
        std::mt19937_64 rng(seed + 50);
        for (const Config<P>& c : moderateConfigs<P>(m, ++seed)) {
            const PairForce ij = p.evaluate(c.rij, c.oi, c.oj);
            const PairForce ji = p.evaluate(-c.rij, c.oj, c.oi);
            // The sums run in another order, hence round-off of the largest term, not equality.
            const double scaleU = std::abs(ij.U) + largestEpsilon(m.sites);
            const double scaleF = ij.F.norm() + 1e-3;
            const double scaleT = ij.tauI.norm() + ij.tauJ.norm() + 1e-3;
            EXPECT_NEAR(ji.U, ij.U, kRoundOffTol * scaleU) << m.name;
            EXPECT_LE((ij.F + ji.F).norm(), kRoundOffTol * scaleF) << m.name;
            EXPECT_LE((ij.tauI - ji.tauJ).norm(), kRoundOffTol * scaleT) << m.name;
            EXPECT_LE((ij.tauJ - ji.tauI).norm(), kRoundOffTol * scaleT) << m.name;
            // Angular momentum (paper eq. 6): r_i×F + r_j×(-F) + τ_ij + τ_ji = 0.
            const Vec3 total = c.rij.cross(ij.F) + ij.tauI + ij.tauJ;
            EXPECT_LE(total.norm(), kRoundOffTol * (c.rij.norm() * scaleF + scaleT)) << m.name;
            // A common rotation rotates F and the torques and leaves U.
            const Mat3 rot = randomRotation(rng);
            const typename P::Orientation oi = rot * c.oi, oj = rot * c.oj;
            const PairForce turned = p.evaluate(rot * c.rij, oi, oj);
            EXPECT_NEAR(turned.U, ij.U, kRoundOffTol * scaleU) << m.name;
            EXPECT_LE((turned.F - rot * ij.F).norm(), kRoundOffTol * scaleF) << m.name;
            EXPECT_LE((turned.tauI - rot * ij.tauI).norm(), kRoundOffTol * scaleT) << m.name;
            EXPECT_LE((turned.tauJ - rot * ij.tauJ).norm(), kRoundOffTol * scaleT) << m.name;
        }
    }
}

TYPED_TEST(SiteContract, OneSiteAtTheCentreIsLennardJones) {
    using P = TypeParam;
    const LJPotential lj{1.7, 3.4};
    const P p = P::fromSites({{Vec3::Zero(), lj.epsilon, lj.sigma, 20.0}});
    std::mt19937_64 rng(kSeed + 200);
    for (int n = 0; n < 200; ++n) {
        const Vec3 rij = (0.85 + 2.0 * n / 200.0) * lj.sigma * randomUnit(rng);
        const auto oi = randomOrientation<P>(rng), oj = randomOrientation<P>(rng);
        const PairForce f = p.evaluate(rij, oi, oj);
        const PairForce g = lj.evaluate(rij, Vec3::UnitZ(), Vec3::UnitZ());
        // σ²/d² here, (σ/d)² there: equal to a few roundings of the larger of the two terms
        // (U and F cancel between them near σ and near the minimum).
        const double r = rij.norm(), s6 = std::pow(lj.sigma / r, 6);
        const double termU = 4.0 * lj.epsilon * s6 * (s6 + 1.0);
        EXPECT_TRUE(closeRelative(f.U, g.U, kRoundOffTol, termU)) << "r = " << r;
        EXPECT_TRUE(closeRelative(f.F, g.F, kRoundOffTol, 12.0 * termU / r)) << "r = " << r;
        EXPECT_EQ(f.tauI, Vec3::Zero());
        EXPECT_EQ(f.tauJ, Vec3::Zero());
        EXPECT_TRUE(closeRelative(p.lowestEnergyAt(r), lj.lowestEnergyAt(r), kRoundOffTol, 0.0));
    }
    EXPECT_EQ(p.minimumEnergy(), lj.minimumEnergy());
    EXPECT_EQ(p.extent(), 0.0);
    // The reach by bisection meets the closed-form roots; near the bottom of the well the root
    // is ill-conditioned (U - u is quadratic there), for either computation.
    for (double u : {-0.99, -0.7, -0.3, -0.01, 0.0, 0.5, 10.0, 1e3}) {
        const double tol = u < -0.9 ? 1e-7 : 1e-11;
        EXPECT_TRUE(closeRelative(p.reachDistance(u * lj.epsilon), lj.reachDistance(u * lj.epsilon),
                                  tol, 0.0))
            << "u = " << u << " ε";
    }
    EXPECT_EQ(p.reachDistance(-lj.epsilon), 0.0);
    EXPECT_EQ(p.reachDistance(-2.0 * lj.epsilon), 0.0);
}

TEST(SitePotential, AxisAndFrameAgreeOnALinearMolecule) {
    std::mt19937_64 rng(kSeed + 300);
    for (const auto& sites : {dumbbell(), linearTriatomic()}) {
        const AxisSites axis = AxisSites::fromSites(sites);
        const FrameSites frame = FrameSites::fromSites(sites);
        for (int n = 0; n < 100; ++n) {
            // The frame's third column is the image of body z: the axis.
            const Mat3 qi = randomRotation(rng), qj = randomRotation(rng);
            const Vec3 rij = (2.0 + 6.0 * n / 100.0) * randomUnit(rng);
            const PairForce a = axis.evaluate(rij, Vec3(qi.col(2)), Vec3(qj.col(2)));
            const PairForce f = frame.evaluate(rij, qi, qj);
            const double scale = std::abs(a.U) + 1.0;
            EXPECT_NEAR(f.U, a.U, kRoundOffTol * scale);
            EXPECT_LE((f.F - a.F).norm(), kRoundOffTol * (a.F.norm() + 1.0));
            EXPECT_LE((f.tauI - a.tauI).norm(), kRoundOffTol * (a.tauI.norm() + 1.0));
            EXPECT_LE((f.tauJ - a.tauJ).norm(), kRoundOffTol * (a.tauJ.norm() + 1.0));
        }
        EXPECT_EQ(axis.minimumEnergy(), frame.minimumEnergy());
        EXPECT_EQ(axis.reachDistance(-0.1), frame.reachDistance(-0.1));
        EXPECT_EQ(axis.lowestEnergyAt(4.0), frame.lowestEnergyAt(4.0));
    }
}

// ---------------------------------------------------------------------------------------------
// Bounds.

TYPED_TEST(SiteContract, MinimumAndLowestEnergyAreLowerBounds) {
    using P = TypeParam;
    std::uint64_t seed = kSeed + 400;
    for (const Molecule& m : molecules<P>()) {
        const P p = P::fromSites(m.sites);
        double sum = 0.0; // Σ_ab ε_ab, written out
        for (const Site& a : m.sites)
            for (const Site& b : m.sites)
                sum += std::sqrt(a.epsilon * b.epsilon);
        EXPECT_NEAR(p.minimumEnergy(), -sum, kRoundOffTol * sum) << m.name;
        const double sigma = largestSigma(m.sites);
        std::mt19937_64 rng(++seed);
        std::uniform_real_distribution<double> rDist(0.2 * sigma, 3.0 * sigma + 2.0 * p.extent());
        double lowest = 0.0;
        for (int n = 0; n < 20000; ++n) {
            const double r = rDist(rng);
            const Vec3 rij = r * randomUnit(rng);
            const auto oi = randomOrientation<P>(rng), oj = randomOrientation<P>(rng);
            const double U = p.energy(rij, oi, oj);
            lowest = std::min(lowest, U);
            EXPECT_GE(U, p.minimumEnergy()) << m.name;
            // Round-off of the largest (negative) terms only: positive ones make U larger.
            EXPECT_GE(U, p.lowestEnergyAt(r) - kRoundOffTol * sum) << m.name << ", r = " << r;
        }
        // How loose minimumEnergy() is, for the record (the header's comment quotes the dumbbell).
        std::cout << m.name << ": lowest U sampled " << lowest << ", minimumEnergy() "
                  << p.minimumEnergy() << '\n';
        // Over the tail lowestEnergyAt() is non-decreasing (the cutoff wrapper bisects it there).
        double start = 0.0;
        for (const Site& a : m.sites)
            for (const Site& b : m.sites)
                start = std::max(start, std::pow(2.0, 1.0 / 6.0) * 0.5 * (a.sigma + b.sigma) -
                                            a.r.norm() - b.r.norm());
        double previous = p.lowestEnergyAt(start);
        for (int k = 1; k <= 2000; ++k) {
            const double r = start + 0.01 * k;
            const double now = p.lowestEnergyAt(r);
            EXPECT_GE(now, previous) << m.name << ", r = " << r;
            previous = now;
        }
        EXPECT_LT(previous, 0.0);
    }
}

TYPED_TEST(SiteContract, NoOrientationReachesALevelBeyondItsReach) {
    // For u < 0 every pair beyond reachDistance(u) lies above u (U → 0⁻ far out and never
    // crosses u), for u ≥ 0 below it: scanned outwards from the reach along random rays with
    // random orientations.
    using P = TypeParam;
    std::uint64_t seed = kSeed + 500;
    for (const Molecule& m : molecules<P>()) {
        const P p = P::fromSites(m.sites);
        const double uMin = p.minimumEnergy(), eps = largestEpsilon(m.sites);
        const double sigma = largestSigma(m.sites);
        std::mt19937_64 rng(++seed);
        for (double u : {0.95 * uMin, 0.7 * uMin, 0.4 * uMin, 0.1 * uMin, 0.01 * uMin, 0.0,
                         0.5 * eps, 5.0 * eps, 100.0 * eps}) {
            const double reach = p.reachDistance(u);
            ASSERT_TRUE(std::isfinite(reach)) << m.name << ", u = " << u;
            ASSERT_GT(reach, 0.0) << m.name << ", u = " << u;
            for (int n = 0; n < 100; ++n) {
                const Vec3 dir = randomUnit(rng);
                const auto oi = randomOrientation<P>(rng), oj = randomOrientation<P>(rng);
                for (int k = 0; k < 200; ++k) {
                    const double r = reach * (1.0 + 1e-9) + 3.0 * sigma * k / 200.0;
                    const double U = p.energy(r * dir, oi, oj);
                    if (u < 0.0)
                        EXPECT_GT(U, u) << m.name << ", u = " << u << ", r = " << r;
                    else
                        EXPECT_LT(U, u) << m.name << ", u = " << u << ", r = " << r;
                }
            }
        }
        // Levels just below 0 are reached far out, but at a finite distance.
        for (double u : {-1e-6 * eps, -1e-12 * eps, -1e-300}) {
            const double reach = p.reachDistance(u);
            EXPECT_TRUE(std::isfinite(reach)) << m.name << ", u = " << u;
            EXPECT_GT(reach, p.reachDistance(0.01 * uMin)) << m.name << ", u = " << u;
        }
        EXPECT_EQ(p.reachDistance(uMin), 0.0);
        EXPECT_EQ(p.reachDistance(1.5 * uMin), 0.0);
        // Deeper levels are reached only closer in, higher walls only closer in too.
        EXPECT_LT(p.reachDistance(0.9 * uMin), p.reachDistance(0.1 * uMin));
        EXPECT_GT(p.reachDistance(0.0), p.reachDistance(10.0 * eps));
    }
}

TEST(SitePotential, SmoothedReachIsValid) {
    // Through the cutoff wrapper: beyond r_l the reach of a shallow level solves g·Ulow = u with
    // Ulow = lowestEnergyAt(); no orientation reaches the level farther out.
    const AxisSites bare = AxisSites::fromSites(dumbbell());
    const Smoothed<AxisSites> model{bare, SmoothedCutoff{2.5 * kSigma, 3.0 * kSigma}};
    std::mt19937_64 rng(kSeed + 600);
    for (double u : {-0.05, -0.01, -0.002}) {
        const double reach = model.reachDistance(u);
        EXPECT_GT(reach, model.cut.inner()) << u;
        EXPECT_LE(reach, std::min(bare.reachDistance(u), model.range())) << u;
        for (int k = 0; k < 2000; ++k) {
            const double r = reach * (1.0 + 1e-9) + (model.range() - reach) * k / 2000.0;
            EXPECT_GT(model.energy(r * randomUnit(rng), randomUnit(rng), randomUnit(rng)), u) << u;
        }
    }
}

/// A configuration moved within the limits of energyRange: the separation by up to `shift`, each
/// body turned about a random axis by up to its angle.
template <class P>
typename P::Orientation turned(const typename P::Orientation& o, const Vec3& axis, double angle) {
    return rotation(axis, angle) * o; // the axis, or the frame's columns, turned alike
}

// energyRange (the DMD hold screen's bound) holds U over every configuration it claims to cover,
// bare and through the cutoff wrapper, and is tight for no motion.
template <class P> void expectRangeHolds() {
    std::mt19937_64 rng(kSeed + 700);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const Molecule& mol : molecules<P>()) {
        const P bare = P::fromSites(mol.sites);
        const Smoothed<P> model{bare, SmoothedCutoff{2.5 * kSigma, 3.0 * kSigma}};
        for (int k = 0; k < 300; ++k) {
            const Vec3 rij = (0.9 + 2.4 * unit(rng)) * kSigma * randomUnit(rng);
            const auto oi = randomOrientation<P>(rng), oj = randomOrientation<P>(rng);
            const double shift = 0.3 * unit(rng), turnI = 0.4 * unit(rng), turnJ = 0.4 * unit(rng);
            const EnergyRange still = model.energyRange(rij, oi, oj, 0.0, 0.0, 0.0);
            const double u0 = model.energy(rij, oi, oj);
            EXPECT_NEAR(still.lo, u0, kStillRangeTol * std::max(1.0, std::abs(u0))) << mol.name;
            EXPECT_NEAR(still.hi, u0, kStillRangeTol * std::max(1.0, std::abs(u0))) << mol.name;
            const EnergyRange range = model.energyRange(rij, oi, oj, shift, turnI, turnJ);
            const EnergyRange bareRange = bare.energyRange(rij, oi, oj, shift, turnI, turnJ);
            for (int m = 0; m < 50; ++m) {
                const Vec3 r = rij + shift * unit(rng) * randomUnit(rng);
                const auto ti = turned<P>(oi, randomUnit(rng), turnI * unit(rng));
                const auto tj = turned<P>(oj, randomUnit(rng), turnJ * unit(rng));
                const double u = model.energy(r, ti, tj), ub = bare.energy(r, ti, tj);
                const double slack = 1e-12 * std::max(1.0, std::abs(u));
                EXPECT_GE(u, range.lo - slack) << mol.name;
                EXPECT_LE(u, range.hi + slack) << mol.name;
                EXPECT_GE(ub, bareRange.lo - slack) << mol.name;
                EXPECT_LE(ub, bareRange.hi + slack) << mol.name;
            }
        }
    }
}

TEST(SitePotential, EnergyRangeHoldsOverTheMotionItCovers) {
    expectRangeHolds<AxisSites>();
    expectRangeHolds<FrameSites>();
}

// ---------------------------------------------------------------------------------------------
// Inertia and input checks.

TEST(SiteInertia, DumbbellAndPerpendicularAxes) {
    // Dumbbell: I = 2m(ℓ/2)² about x and y, 0 about its axis.
    const auto db = dumbbell();
    const Mat3 I = siteInertiaTensor(db);
    const double perp = 2.0 * kSiteMass * 0.25 * kBond * kBond;
    EXPECT_TRUE(I.isApprox(Vec3(perp, perp, 0.0).asDiagonal().toDenseMatrix(), 1e-15));
    EXPECT_EQ(siteCentreOfMass(db), Vec3::Zero());
    EXPECT_TRUE(sitesInPrincipalFrame(db));

    // A planar molecule in the xy plane, centre of mass at the origin, mirror-symmetric in x:
    // principal, with I3 = I1 + I2 (the perpendicular-axis theorem).
    const double yO = -0.0656, yH = -16.0 * yO / 2.0;
    const std::vector<Site> water = {{Vec3(0, yO, 0), 0.65, 3.15, 16.0},
                                     {Vec3(0.757, yH, 0), 0.0, 1.0, 1.0},
                                     {Vec3(-0.757, yH, 0), 0.0, 1.0, 1.0}};
    const Mat3 Iw = siteInertiaTensor(water);
    EXPECT_NEAR(Iw(2, 2), Iw(0, 0) + Iw(1, 1), kInertiaTol * Iw(2, 2));
    EXPECT_NEAR(Iw(0, 0), 16.0 * yO * yO + 2.0 * yH * yH, kInertiaTol);
    EXPECT_NEAR(Iw(1, 1), 2.0 * 0.757 * 0.757, kInertiaTol);
    EXPECT_LE(siteCentreOfMass(water).norm(), kCentreTol);
    EXPECT_TRUE(sitesInPrincipalFrame(water));
    // Shifted off the centre of mass, or turned in its plane, it is no longer principal.
    std::vector<Site> shifted = water, turned = water;
    for (Site& s : shifted)
        s.r += Vec3(0.01, 0, 0);
    for (Site& s : turned)
        s.r = rotation(Vec3::UnitZ(), 0.3) * s.r;
    EXPECT_FALSE(sitesInPrincipalFrame(shifted));
    EXPECT_FALSE(sitesInPrincipalFrame(turned));
    // The parallel-axis theorem: I about the shifted origin = I + M(|c|² 1 - c cᵀ).
    const Vec3 c = -siteCentreOfMass(shifted);
    const Mat3 expected = Iw + 18.0 * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
    EXPECT_TRUE(siteInertiaTensor(shifted).isApprox(expected, 1e-13));
    EXPECT_THROW(siteCentreOfMass({{Vec3::Zero(), 1.0, 1.0, 0.0}}), std::invalid_argument);
}

/// fromSites(sites) throws std::invalid_argument whose message contains `needle`.
template <class P>
::testing::AssertionResult rejected(const std::vector<Site>& sites, const std::string& needle) {
    try {
        (void)P::fromSites(sites);
    } catch (const std::invalid_argument& e) {
        if (std::string(e.what()).find(needle) != std::string::npos)
            return ::testing::AssertionSuccess();
        return ::testing::AssertionFailure() << "message \"" << e.what() << "\" lacks " << needle;
    }
    return ::testing::AssertionFailure() << "accepted";
}

TEST(SitePotential, FromSitesRejectsBadInput) {
    const Site ok{Vec3::Zero(), 1.0, 3.0, 1.0};
    EXPECT_TRUE(rejected<FrameSites>({}, "0 sites given"));
    EXPECT_TRUE(rejected<FrameSites>(std::vector<Site>(7, ok), "7 sites given"));
    EXPECT_TRUE(rejected<FrameSites>({ok, {Vec3::UnitX(), 1.0, 0.0, 1.0}}, "site 1: σ = 0"));
    EXPECT_TRUE(rejected<FrameSites>({{Vec3::UnitX(), 1.0, -2.0, 1.0}}, "σ = -2"));
    EXPECT_TRUE(rejected<AxisSites>({ok, {Vec3::UnitZ(), -1.0, 3.0, 1.0}}, "ε = -1"));
    EXPECT_TRUE(rejected<AxisSites>({{Vec3::Zero(), 0.0, 3.0, 1.0}}, "no site has ε > 0"));
    EXPECT_TRUE(rejected<AxisSites>({{Vec3::Zero(), 1.0, 3.0, -1.0}}, "mass = -1"));
    EXPECT_TRUE(rejected<AxisSites>({{Vec3(NAN, 0, 0), 1.0, 3.0, 1.0}}, "non-finite"));
    EXPECT_TRUE(rejected<AxisSites>({ok, {Vec3(1e-6, 0, 1.0), 1.0, 3.0, 1.0}}, "off the body z"));
    // The frame form takes any geometry; six sites are allowed.
    EXPECT_NO_THROW((void)FrameSites::fromSites({ok, {Vec3(1e-6, 0, 1.0), 1.0, 3.0, 1.0}}));
    EXPECT_NO_THROW((void)FrameSites::fromSites(std::vector<Site>(6, ok)));
    // A site with ε = 0 (a mass point) is fine next to an interacting one.
    EXPECT_NO_THROW((void)AxisSites::fromSites({ok, {Vec3::UnitZ(), 0.0, 1.0, 1.0}}));
}

} // namespace terrace::test_site_potential
