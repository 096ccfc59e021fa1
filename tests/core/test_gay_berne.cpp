// The Gay–Berne potential (core/gay_berne_potential.hpp):
//  - hand-computed contact distances and well depths of GB(3, 5, 2, 1) in the four classic
//    configurations (side by side, end to end, crossed, T);
//  - F_ij = −∂U/∂r_ij and torques from dU = −τ·δθ against finite differences of U, and dU/dt
//    (energyRate) against U along free motion and against eq. (13) with evaluate();
//  - action and reaction, exchange of the bodies, angular momentum, head-tail and rotational
//    invariance;
//  - the reduction to plain Lennard-Jones for spheres (κ = κ' = 1);
//  - minimumEnergy(), reachDistance() and lowestEnergyAt() as bounds, by brute-force search;
//  - problem()'s parameter checks.
#include "core/body_kind.hpp"
#include "core/gay_berne_potential.hpp"
#include "core/lj_potential.hpp"

#include "pair_checks.hpp"
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace terrace::test_gay_berne {

using pairchecks::centralDerivative;
using pairchecks::closeRelative;
using pairchecks::randomUnit;

static_assert(PairPotential<GayBernePotential>);

constexpr double kEps = std::numeric_limits<double>::epsilon();
// Hand-computed values are closed forms evaluated in double precision.
constexpr double kExactTol = 1e-12;
// The accuracy asked of analytic derivatives against finite differences of U.
constexpr double kFiniteDifferenceTol = 1e-7;
// Where a force, torque or rate nearly vanishes, compare against this fraction of its natural
// scale instead: well above U's round-off over the step, well below any wrong factor or sign.
constexpr double kVanishingFraction = 1e-3;
// Identities that hold term by term up to a handful of roundings of the largest term.
constexpr double kRoundOffTol = 64.0 * kEps;
// The same after the inputs were rotated, each component carrying its own rounding.
constexpr double kRotationTol = 1e-12;
// Force and torques at the bottom of a well: zero up to the round-off of its closed-form position.
constexpr double kStationaryTol = 1e-12;
// A bound found by bisection holds to its last bisection step (relative; absolute in Å).
constexpr double kBisectionTol = 1e-12;
constexpr double kLooseBoundSlack = 1e-9; // Å: the bisection locating the farthest crossing
// The range of U over no motion is U itself, to the round-off of its interval arithmetic.
constexpr double kStillRangeTol = 1e-9;
// Steps of the fourth-order stencil, balancing truncation (~h⁴) against round-off (~eps·U/h).
// Rotations take a smaller step than for the rods: with κ = 4.4, σ swings by ~(κ − 1)σ0 per radian
// and the stencil's truncation at 3e-4 rad reaches ~3e-7 along free motion; at 1e-4 the worst seen
// over 5000 random pairs per shape is ~2e-8 (round-off), and ~4e-10 for the force at 3e-4 Å.
constexpr double kTranslationStep = 3e-4; // Å
constexpr double kRotationStep = 1e-4;    // rad
constexpr double kTimeStep = 1e-4;        // time units
constexpr std::uint64_t kSeed = 19810601;

// The classic parametrisation GB(κ = 3, κ' = 5, μ = 2, ν = 1) in reduced units.
const GayBernePotential kReduced{.epsilon = 1.0, .sigma = 1.0};

// Shapes for the contract tests, with non-unit ε0 and σ0 so that a mix-up of ε0, σ0 and 1 shows:
// the classic prolate one, a discotic one (κ < 1, and κ' < 1: deeper face to face), and
// exponents off the fast paths (μ = 1.5, ν = 0.5; μ = 1, ν = 2).
const GayBernePotential kShapes[] = {
    {.epsilon = 1.3, .sigma = 3.1, .kappa = 3.0, .kappaPrime = 5.0, .mu = 2.0, .nu = 1.0},
    {.epsilon = 2.0, .sigma = 4.0, .kappa = 0.345, .kappaPrime = 0.2, .mu = 1.0, .nu = 2.0},
    {.epsilon = 0.7, .sigma = 2.5, .kappa = 4.4, .kappaPrime = 20.0, .mu = 1.5, .nu = 0.5},
};

::testing::Message describe(const GayBernePotential& p) {
    return ::testing::Message() << "GB(κ=" << p.kappa << ", κ'=" << p.kappaPrime << ", μ=" << p.mu
                                << ", ν=" << p.nu << ")";
}

struct PairConfig {
    Vec3 rij, ui, uj;
};

/// LJ₁ argument ranges x/σ0: the repulsive wall (kept off the overlapped cores), the well around
/// 2^{1/6}σ0, the tail.
struct Region {
    const char* name;
    double lo, hi;
};
constexpr Region kRegions[] = {{"wall", 0.85, 1.08}, {"well", 1.08, 1.35}, {"tail", 1.35, 3.0}};
constexpr int kSamplesPerRegion = 60;

/// Calls check(cfg, regionName) for random axes and directions, at centre distances that put the
/// shifted argument x = r − σ(u_i, u_j, r̂) + σ0 in each region.
template <class Check>
void forRandomPairs(const GayBernePotential& p, std::uint64_t seed, Check check) {
    std::mt19937_64 rng(seed);
    for (const Region& region : kRegions) {
        std::uniform_real_distribution<double> xDist(region.lo * p.sigma, region.hi * p.sigma);
        for (int n = 0; n < kSamplesPerRegion; ++n) {
            const Vec3 rHat = randomUnit(rng), ui = randomUnit(rng), uj = randomUnit(rng);
            const double r = xDist(rng) + p.contactDistance(rHat, ui, uj) - p.sigma;
            check(PairConfig{r * rHat, ui, uj}, region.name);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Known values of GB(3, 5, 2, 1), ε0 = σ0 = 1. χ = (9 − 1)/(9 + 1) = 4/5; κ'^(1/μ) = √5, so
// χ' = (√5 − 1)/(√5 + 1). U = ε LJ₁(r − σ + 1) is 0 at contact r = σ and −ε at r = σ − 1 + 2^(1/6).

const double kBottom = std::pow(2.0, 1.0 / 6.0);

struct Classic {
    const char* name;
    Vec3 ui, uj;  // r̂ = x̂ throughout
    double sigma; // contact distance, σ0
    double depth; // well depth, ε0
};

// Side by side, parallel (a = b = 0, c = 1): H(χ) = H(χ') = 0, so σ = 1 and ε2 = 1;
//   ε1 = (1 − χ²)^(−1/2) = (1 − 16/25)^(−1/2) = 5/3.
// End to end (a = b = c = 1): H(χ) = (χ/2)·4/(1 + χ) = 2χ/(1 + χ) = 8/9, so σ = (1/9)^(−1/2) = 3;
//   ε1 = 5/3 again, ε2 = 1 − 2χ'/(1 + χ') = (1 − χ')/(1 + χ') = 1/√5, so ε = (5/3)(1/5) = 1/3.
// Crossed (a = b = c = 0): σ = 1, ε = 1.
// T (a = 1, b = c = 0): H(χ) = (χ/2)(1 + 1) = χ, so σ = 1/√(1 − χ) = √5; ε1 = 1 and
//   ε2 = 1 − χ' = 2/(√5 + 1), so ε = 4/(√5 + 1)² = (3 − √5)/2.
const Classic kClassics[] = {
    {"side by side", Vec3::UnitZ(), Vec3::UnitZ(), 1.0, 5.0 / 3.0},
    {"end to end", Vec3::UnitX(), Vec3::UnitX(), 3.0, 1.0 / 3.0},
    {"crossed", Vec3::UnitY(), Vec3::UnitZ(), 1.0, 1.0},
    {"T", Vec3::UnitX(), Vec3::UnitZ(), std::sqrt(5.0), 0.5 * (3.0 - std::sqrt(5.0))},
};

TEST(GayBerneKnownValues, ClassicConfigurations) {
    const GayBernePotential& p = kReduced;
    EXPECT_NEAR(p.chi(), 0.8, kExactTol);
    EXPECT_NEAR(p.chiPrime(), (std::sqrt(5.0) - 1.0) / (std::sqrt(5.0) + 1.0), kExactTol);
    for (const Classic& k : kClassics) {
        SCOPED_TRACE(k.name);
        EXPECT_NEAR(p.contactDistance(Vec3::UnitX(), k.ui, k.uj), k.sigma, kExactTol);
        EXPECT_NEAR(p.wellDepth(Vec3::UnitX(), k.ui, k.uj), k.depth, kExactTol);
        // Zero at contact; −ε at the bottom of the well, where the force vanishes.
        EXPECT_NEAR(p.energy(k.sigma * Vec3::UnitX(), k.ui, k.uj), 0.0, kExactTol);
        const Vec3 rMin = (k.sigma - 1.0 + kBottom) * Vec3::UnitX();
        const PairForce f = p.evaluate(rMin, k.ui, k.uj);
        EXPECT_NEAR(f.U, -k.depth, kExactTol);
        EXPECT_NEAR(p.energy(rMin, k.ui, k.uj), -k.depth, kExactTol);
        EXPECT_LE(f.F.norm(), kStationaryTol);
        // All four are stationary in the orientations too (by symmetry): no torques.
        EXPECT_LE(f.tauI.norm(), kStationaryTol);
        EXPECT_LE(f.tauJ.norm(), kStationaryTol);
        // Repulsive just inside contact, attractive beyond the well.
        EXPECT_GT(p.evaluate(0.98 * k.sigma * Vec3::UnitX(), k.ui, k.uj).F.x(), 0.0);
        EXPECT_LT(p.evaluate((k.sigma + 0.5) * Vec3::UnitX(), k.ui, k.uj).F.x(), 0.0);
    }
    // κ' is the side-by-side over end-to-end well depth.
    const double side = p.energy(kBottom * Vec3::UnitX(), Vec3::UnitZ(), Vec3::UnitZ());
    const double end = p.energy((2.0 + kBottom) * Vec3::UnitX(), Vec3::UnitX(), Vec3::UnitX());
    EXPECT_NEAR(side / end, p.kappaPrime, kExactTol);
    // The deepest well is the side-by-side one.
    EXPECT_NEAR(p.minimumEnergy(), -5.0 / 3.0, kExactTol);
}

TEST(GayBerneKnownValues, DeepestWellOfEachShapeIsAttained) {
    // Parallel axes (c = 1) side by side when κ' ≥ 1, end to end when κ' < 1.
    for (const GayBernePotential& p : kShapes) {
        SCOPED_TRACE(describe(p));
        const Vec3 u = p.kappaPrime >= 1.0 ? Vec3::UnitZ() : Vec3::UnitX();
        const double r = p.contactDistance(Vec3::UnitX(), u, u) + (kBottom - 1.0) * p.sigma;
        EXPECT_NEAR(p.energy(r * Vec3::UnitX(), u, u), p.minimumEnergy(),
                    kExactTol * p.epsilon * 10.0);
    }
}

// ---------------------------------------------------------------------------------------------
// Derivatives against finite differences of U.

double forceFloor(const GayBernePotential& p) {
    return kVanishingFraction * p.epsilonMax() / p.sigma;
}
double torqueFloor(const GayBernePotential& p) {
    return kVanishingFraction * p.epsilonMax();
}

TEST(GayBerneDerivatives, ForceIsMinusGradientOfU) {
    for (const GayBernePotential& p : kShapes) {
        SCOPED_TRACE(describe(p));
        forRandomPairs(p, kSeed, [&](const PairConfig& c, const char* region) {
            const PairForce f = p.evaluate(c.rij, c.ui, c.uj);
            EXPECT_EQ(f.U, p.energy(c.rij, c.ui, c.uj));
            Vec3 gradU;
            for (int a = 0; a < 3; ++a) {
                const Vec3 e = Vec3::Unit(a);
                gradU[a] =
                    centralDerivative([&](double h) { return p.energy(c.rij + h * e, c.ui, c.uj); },
                                      kTranslationStep);
            }
            EXPECT_TRUE(closeRelative(f.F, -gradU, kFiniteDifferenceTol, forceFloor(p)))
                << region << ", r = " << c.rij.norm();
        });
    }
}

TEST(GayBerneDerivatives, TorquesFromSmallRotations) {
    // Turning u_i by δθ about the lab axis e changes U by −τ_ij·e δθ (likewise for j).
    for (const GayBernePotential& p : kShapes) {
        SCOPED_TRACE(describe(p));
        forRandomPairs(p, kSeed + 1, [&](const PairConfig& c, const char* region) {
            const PairForce f = p.evaluate(c.rij, c.ui, c.uj);
            Vec3 dUdThetaI, dUdThetaJ;
            for (int a = 0; a < 3; ++a) {
                const Vec3 e = Vec3::Unit(a);
                dUdThetaI[a] = centralDerivative(
                    [&](double h) { return p.energy(c.rij, rotationMatrix(e, h) * c.ui, c.uj); },
                    kRotationStep);
                dUdThetaJ[a] = centralDerivative(
                    [&](double h) { return p.energy(c.rij, c.ui, rotationMatrix(e, h) * c.uj); },
                    kRotationStep);
            }
            EXPECT_TRUE(closeRelative(f.tauI, -dUdThetaI, kFiniteDifferenceTol, torqueFloor(p)))
                << region << ", r = " << c.rij.norm();
            EXPECT_TRUE(closeRelative(f.tauJ, -dUdThetaJ, kFiniteDifferenceTol, torqueFloor(p)))
                << region << ", r = " << c.rij.norm();
            // U reads only the axis: no torque about it, so spin about the axis stays free.
            EXPECT_LE(std::abs(f.tauI.dot(c.ui)), kRoundOffTol * f.tauI.norm());
            EXPECT_LE(std::abs(f.tauJ.dot(c.uj)), kRoundOffTol * f.tauJ.norm());
        });
    }
}

TEST(GayBerneDerivatives, RateAlongFreeMotion) {
    // r(t) = r + v t, u(t) turned by ω t: dU/dt from energyRate() against a finite difference of
    // U, and against eq. (13) with evaluate()'s force and torques.
    std::mt19937_64 rng(kSeed + 2);
    std::normal_distribution<double> gauss;
    for (const GayBernePotential& p : kShapes) {
        SCOPED_TRACE(describe(p));
        forRandomPairs(p, kSeed + 3, [&](const PairConfig& c, const char* region) {
            const Vec3 v(gauss(rng), gauss(rng), gauss(rng));
            const Vec3 wi(gauss(rng), gauss(rng), gauss(rng));
            const Vec3 wj(gauss(rng), gauss(rng), gauss(rng));
            const auto energyAt = [&](double t) {
                const Mat3 Ri = rotationMatrix(wi / wi.norm(), wi.norm() * t);
                const Mat3 Rj = rotationMatrix(wj / wj.norm(), wj.norm() * t);
                return p.energy(c.rij + v * t, Ri * c.ui, Rj * c.uj);
            };
            const PairForce f = p.evaluate(c.rij, c.ui, c.uj);
            const double rate = dUdt(f, v, wi, wj);
            const double scale =
                f.F.norm() * v.norm() + f.tauI.norm() * wi.norm() + f.tauJ.norm() * wj.norm();
            const EnergyRate er = energyAndRate(p, c.rij, v, c.ui, wi, c.uj, wj);
            EXPECT_EQ(er.U, f.U);
            EXPECT_NEAR(er.dUdt, rate, kRoundOffTol * scale) << region;
            const double numeric = centralDerivative(energyAt, kTimeStep);
            EXPECT_TRUE(
                closeRelative(er.dUdt, numeric, kFiniteDifferenceTol, kVanishingFraction * scale))
                << region << ", r = " << c.rij.norm();
        });
    }
}

// ---------------------------------------------------------------------------------------------
// Symmetries.

TEST(GayBerneSymmetry, ActionReactionAndExchange) {
    std::mt19937_64 rng(kSeed + 4);
    std::uniform_real_distribution<double> boxDist(-15.0, 15.0);
    for (const GayBernePotential& p : kShapes) {
        SCOPED_TRACE(describe(p));
        forRandomPairs(p, kSeed + 5, [&](const PairConfig& c, const char* region) {
            // The pair seen from j: r_ji = −r_ij, the axes exchanged.
            const PairForce ij = p.evaluate(c.rij, c.ui, c.uj);
            const PairForce ji = p.evaluate(-c.rij, c.uj, c.ui);
            EXPECT_EQ(ij.U, ji.U) << region;
            EXPECT_EQ(p.energy(-c.rij, c.uj, c.ui), p.energy(c.rij, c.ui, c.uj)) << region;
            EXPECT_LE((ij.F + ji.F).norm(), kRoundOffTol * ij.F.norm()) << region;
            EXPECT_LE((ij.tauJ - ji.tauI).norm(), kRoundOffTol * ij.tauJ.norm()) << region;
            EXPECT_LE((ij.tauI - ji.tauJ).norm(), kRoundOffTol * ij.tauI.norm()) << region;
            // Angular momentum: τ_ij + τ_ji + r_ij × F_ij = 0, and about any origin.
            const double scale = c.rij.norm() * ij.F.norm() + ij.tauI.norm() + ij.tauJ.norm();
            EXPECT_LE((ij.tauI + ij.tauJ + c.rij.cross(ij.F)).norm(), kRoundOffTol * scale)
                << region;
            const Vec3 rj(boxDist(rng), boxDist(rng), boxDist(rng)), ri = rj + c.rij;
            const Vec3 total = ri.cross(ij.F) + rj.cross(ji.F) + ij.tauI + ji.tauI;
            const double far = (ri.norm() + rj.norm()) * ij.F.norm() + 2.0 * ij.tauI.norm();
            EXPECT_LE(total.norm(), kRoundOffTol * (far + scale)) << region;
        });
    }
}

TEST(GayBerneSymmetry, HeadTailAndRotationInvariance) {
    std::mt19937_64 rng(kSeed + 6);
    for (const GayBernePotential& p : kShapes) {
        SCOPED_TRACE(describe(p));
        forRandomPairs(p, kSeed + 7, [&](const PairConfig& c, const char* region) {
            const PairForce f = p.evaluate(c.rij, c.ui, c.uj);
            // Natural scales of U's changes, of the force and of the torques.
            const double r = c.rij.norm();
            const double scale = std::abs(f.U) + f.F.norm() * r + f.tauI.norm() + f.tauJ.norm();
            // An ellipsoid has no head: u → −u changes nothing (the torque −u × ∂U/∂u is even in
            // u, as ∂U/∂u is odd).
            for (const auto& [si, sj] : {std::pair{-1.0, 1.0}, {1.0, -1.0}, {-1.0, -1.0}}) {
                const PairForce g = p.evaluate(c.rij, si * c.ui, sj * c.uj);
                EXPECT_NEAR(g.U, f.U, kRoundOffTol * scale) << region;
                EXPECT_LE((g.F - f.F).norm(), kRoundOffTol * scale / r) << region;
                EXPECT_LE((g.tauI - f.tauI).norm(), kRoundOffTol * scale) << region;
                EXPECT_LE((g.tauJ - f.tauJ).norm(), kRoundOffTol * scale) << region;
            }
            // A common rotation R leaves U alone and turns F and the torques with it. The rotated
            // inputs carry round-off, which the steep wall amplifies (its curvature ~ 13 F/x):
            // hence the looser tolerance, still far below any wrong sign or factor.
            const double angle = std::uniform_real_distribution<double>(0.0, 3.0)(rng);
            const Mat3 R = rotationMatrix(randomUnit(rng), angle);
            const PairForce g = p.evaluate(R * c.rij, R * c.ui, R * c.uj);
            EXPECT_NEAR(g.U, f.U, kRotationTol * scale) << region;
            EXPECT_LE((g.F - R * f.F).norm(), kRotationTol * scale / r) << region;
            EXPECT_LE((g.tauI - R * f.tauI).norm(), kRotationTol * scale) << region;
            EXPECT_LE((g.tauJ - R * f.tauJ).norm(), kRotationTol * scale) << region;
        });
    }
}

// ---------------------------------------------------------------------------------------------
// Spheres: κ = κ' = 1 makes χ = χ' = 0, hence σ = σ0 and ε = ε0 whatever μ and ν.

TEST(GayBerneLimit, SpheresAreLennardJones) {
    const LJPotential lj{1.7, 3.4};
    std::mt19937_64 rng(kSeed + 8);
    for (const auto& [mu, nu] : {std::pair{0.0, 0.0}, {2.0, 1.0}, {1.5, 0.5}}) {
        const GayBernePotential p{.epsilon = lj.epsilon,
                                  .sigma = lj.sigma,
                                  .kappa = 1.0,
                                  .kappaPrime = 1.0,
                                  .mu = mu,
                                  .nu = nu};
        ASSERT_EQ(p.problem(), "");
        EXPECT_EQ(p.minimumEnergy(), lj.minimumEnergy());
        for (double u : {-0.9 * lj.epsilon, -0.2 * lj.epsilon, 0.0, 3.0 * lj.epsilon})
            EXPECT_NEAR(p.reachDistance(u), lj.reachDistance(u), kExactTol * lj.sigma);
        for (int n = 0; n < 200; ++n) {
            const double r = std::uniform_real_distribution<double>(0.85, 3.0)(rng) * lj.sigma;
            const Vec3 rij = r * randomUnit(rng), ui = randomUnit(rng), uj = randomUnit(rng);
            const PairForce g = p.evaluate(rij, ui, uj), s = lj.evaluate(rij, ui, uj);
            EXPECT_EQ(g.U, s.U) << "r = " << r;
            EXPECT_TRUE(closeRelative(g.F, s.F, kRoundOffTol, 0.0)) << "r = " << r;
            EXPECT_EQ(g.tauI, Vec3::Zero());
            EXPECT_EQ(g.tauJ, Vec3::Zero());
            EXPECT_EQ(p.lowestEnergyAt(r), lj.lowestEnergyAt(r));
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The bounds the engines plan with.

/// Axes for the brute-force searches: random ones, plus the four classic configurations about x̂
/// (which hold the extremes of σ and ε).
std::vector<PairConfig> searchAxes(std::mt19937_64& rng, int randomCount) {
    std::vector<PairConfig> out;
    for (const Classic& k : kClassics)
        out.push_back({Vec3::UnitX(), k.ui, k.uj});
    for (int n = 0; n < randomCount; ++n)
        out.push_back({randomUnit(rng), randomUnit(rng), randomUnit(rng)});
    return out;
}

TEST(GayBerneBounds, NothingBelowMinimumEnergyOrLowestEnergyAt) {
    std::mt19937_64 rng(kSeed + 9);
    for (const GayBernePotential& p : kShapes) {
        SCOPED_TRACE(describe(p));
        const double uMin = p.minimumEnergy();
        double lowest = std::numeric_limits<double>::infinity();
        const std::vector<PairConfig> axes = searchAxes(rng, 2000);
        const double rLo = 0.6 * p.sigmaMin(), rHi = p.sigmaMax() + 3.0 * p.sigma;
        for (int step = 0; step <= 300; ++step) {
            const double r = rLo + (rHi - rLo) * step / 300.0;
            const double bound = p.lowestEnergyAt(r);
            for (const PairConfig& c : axes) {
                const double U = p.energy(r * c.rij, c.ui, c.uj);
                lowest = std::min(lowest, U);
                EXPECT_GE(U, uMin - kRoundOffTol * p.epsilonMax());
                // Where the bound is attained (κ' < 1: end to end at σ_min), U and the bound
                // differ by x's round-off times the wall's slope, up to ~24 ε_max/σ0.
                ASSERT_GE(U, bound - kRoundOffTol * 24.0 * p.epsilonMax()) << "r = " << r;
            }
        }
        // The search comes close to the minimum (the classic axes attain it on the grid's scale).
        EXPECT_LT(lowest, 0.99 * uMin);
        // Beyond the well, the lower bound never falls as r grows (the reach bisection needs it).
        const double wellEnd = kBottom * p.sigma + p.sigmaMax() - p.sigma;
        double previous = p.lowestEnergyAt(wellEnd);
        for (double r = wellEnd; r < wellEnd + 5.0 * p.sigma; r += 0.01 * p.sigma) {
            const double now = p.lowestEnergyAt(r);
            EXPECT_GE(now, previous) << "r = " << r;
            previous = now;
        }
    }
}

/// The largest r ≤ rHi at which U(r r̂, u_i, u_j) = u, by scanning inward from rHi for the first
/// change of sign of U − u and bisecting it; 0 if there is none down to rLo.
double outermostCrossing(const GayBernePotential& p, const PairConfig& c, double u, double rLo,
                         double rHi) {
    const double h = 1e-3 * p.sigma;
    const auto above = [&](double r) { return p.energy(r * c.rij, c.ui, c.uj) > u; };
    const bool farAbove = above(rHi);
    for (double r = rHi; r > rLo; r -= h) {
        if (above(r - h) == farAbove) continue;
        double in = r - h, out = r;
        for (int k = 0; k < 60; ++k) {
            const double mid = 0.5 * (in + out);
            (above(mid) == farAbove ? out : in) = mid;
        }
        return out;
    }
    return 0.0;
}

TEST(GayBerneBounds, ReachDistanceBoundsEveryCrossing) {
    std::mt19937_64 rng(kSeed + 10);
    for (const GayBernePotential& p : kShapes) {
        SCOPED_TRACE(describe(p));
        const double eMax = p.epsilonMax(), slack = p.sigmaMax() - p.sigma;
        const std::vector<PairConfig> axes = searchAxes(rng, 150);
        for (double u : {-eMax, -0.999 * eMax, -0.7 * eMax, -0.3 * eMax, -0.02 * eMax, 0.0,
                         0.5 * eMax, 10.0 * eMax}) {
            const double reach = p.reachDistance(u);
            ASSERT_GT(reach, 0.0) << "u = " << u;
            double farthest = 0.0;
            for (const PairConfig& c : axes) {
                const double r = outermostCrossing(p, c, u, 0.6 * p.sigmaMin(), reach + p.sigma);
                farthest = std::max(farthest, r);
                EXPECT_LE(r, reach * (1.0 + kBisectionTol)) << "u = " << u;
            }
            // Not absurdly loose: when κ' ≥ 1 parallel axes side by side have the deepest well and
            // σ = σ0, so the bound exceeds their crossing by σ_max − σ0 at most. (When κ' < 1 the
            // deepest well is end to end, where σ differs from σ_max, and the bound is looser.)
            // At u = −ε_max the well is only touched, which a scan cannot see.
            if (p.kappaPrime >= 1.0 && u > -eMax) {
                EXPECT_LE(reach - farthest, slack + kLooseBoundSlack) << "u = " << u;
            }
            // The reach bisection of the smoothed cutoff ends at the same place.
            if (u < 0.0 && reach > kBottom * p.sigma + slack) {
                EXPECT_NEAR(p.lowestEnergyAt(reach), u, kBisectionTol * eMax) << "u = " << u;
            }
        }
        // Deeper than the deepest well: never.
        EXPECT_EQ(p.reachDistance(-eMax * (1.0 + 1e-12)), 0.0);
        EXPECT_EQ(p.reachDistance(-2.0 * eMax), 0.0);
        // u = 0 is reached end to end (prolate) or side by side (oblate) exactly at σ_max.
        EXPECT_NEAR(p.reachDistance(0.0), p.sigmaMax(), kExactTol * p.sigma);
    }
}

// ---------------------------------------------------------------------------------------------
// Overlapping cores and parameter checks.

// energyRange (the DMD hold screen's bound) holds U over every configuration it claims to cover —
// the centres moved by up to `shift`, each axis turned by up to its angle — and is U itself for
// no motion.
TEST(GayBerneBounds, EnergyRangeHoldsOverTheMotionItCovers) {
    std::mt19937_64 rng(kSeed + 21);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const GayBernePotential& p : kShapes) {
        SCOPED_TRACE(describe(p));
        for (int k = 0; k < 400; ++k) {
            const Vec3 rij =
                (p.sigmaMin() + (p.sigmaMax() + p.sigma) * unit(rng)) * randomUnit(rng);
            const Vec3 ui = randomUnit(rng), uj = randomUnit(rng);
            const double u0 = p.energy(rij, ui, uj);
            if (!std::isfinite(u0)) continue;
            const EnergyRange still = p.energyRange(rij, ui, uj, 0.0, 0.0, 0.0);
            EXPECT_NEAR(still.lo, u0, kStillRangeTol * std::max(1.0, std::abs(u0)));
            EXPECT_NEAR(still.hi, u0, kStillRangeTol * std::max(1.0, std::abs(u0)));
            const double shift = 0.2 * p.sigma * unit(rng);
            const double turnI = 0.3 * unit(rng), turnJ = 0.3 * unit(rng);
            const EnergyRange range = p.energyRange(rij, ui, uj, shift, turnI, turnJ);
            for (int m = 0; m < 50; ++m) {
                const Vec3 r = rij + shift * unit(rng) * randomUnit(rng);
                const Vec3 vi = rotationMatrix(randomUnit(rng), turnI * unit(rng)) * ui;
                const Vec3 vj = rotationMatrix(randomUnit(rng), turnJ * unit(rng)) * uj;
                const double u = p.energy(r, vi, vj);
                const double slack = 1e-12 * std::max(1.0, std::abs(u));
                EXPECT_GE(u, range.lo - slack);
                EXPECT_LE(u, range.hi + slack);
            }
        }
    }
}

TEST(GayBerneDomain, OverlappingCoresAreInfinitelyHigh) {
    const GayBernePotential& p = kReduced;
    // End to end, σ = 3: x = r − 2 ≤ 0 for r ≤ 2.
    for (double r : {2.0, 1.5, 0.0}) {
        const Vec3 rij = r * Vec3::UnitX();
        EXPECT_EQ(p.energy(rij, Vec3::UnitX(), Vec3::UnitX()),
                  std::numeric_limits<double>::infinity());
        const PairForce f = p.evaluate(rij, Vec3::UnitX(), Vec3::UnitX());
        EXPECT_EQ(f.U, std::numeric_limits<double>::infinity());
        EXPECT_EQ(f.F, Vec3::Zero());
    }
    EXPECT_EQ(p.lowestEnergyAt(0.0), std::numeric_limits<double>::infinity());
}

TEST(GayBerneParameters, ProblemNamesTheBadParameter) {
    EXPECT_EQ(GayBernePotential{}.problem(), "");
    for (const GayBernePotential& p : kShapes)
        EXPECT_EQ(p.problem(), "");
    EXPECT_EQ((GayBernePotential{.mu = 0.0, .nu = 0.0}).problem(), "");
    const double nan = std::numeric_limits<double>::quiet_NaN();
    struct Bad {
        GayBernePotential p;
        const char* key;
    };
    const Bad bad[] = {
        {{.epsilon = 0.0}, "epsilon"},
        {{.epsilon = -1.0}, "epsilon"},
        {{.sigma = 0.0}, "sigma"},
        {{.sigma = nan}, "sigma"},
        {{.kappa = 0.0}, "kappa"},
        {{.kappa = -3.0}, "kappa"},
        {{.kappaPrime = 0.0}, "kappaPrime"},
        {{.kappaPrime = nan}, "kappaPrime"},
        {{.mu = -1.0}, "mu"},
        {{.nu = -0.5}, "nu"},
        {{.nu = std::numeric_limits<double>::infinity()}, "nu"},
        {{.kappaPrime = 5.0, .mu = 1e-3}, "mu"}, // κ'^(1/μ) so large that χ' rounds to 1
    };
    for (const Bad& b : bad) {
        const std::string problem = b.p.problem();
        EXPECT_EQ(problem.rfind(std::string(b.key) + " must be", 0), 0u) << problem;
    }
}

} // namespace terrace::test_gay_berne
