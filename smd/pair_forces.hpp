#pragma once
// Total force, torque, potential energy and virial of the smoothed continuous potential
// (core/smoothed_potential.hpp) by a loop over the Verlet list, each pair once with Newton's third
// law: F_j -= F_ij, τ_i += τ_ij, τ_j += τ_ji. The molecular virial W = Σ_pairs r_ij·F_ij takes the
// centre-of-mass separations (switch term included, as it is part of F_ij): the pressure of a
// rigid-body fluid is P = (2 K_trans + W)/(3V) (Allen & Tildesley, 2nd ed., sec. 2.4), torques do
// no work on the volume. Units: kJ/mol/Å, kJ/mol, kJ/mol, kJ/mol.
// allPairsForces() is the slow, obviously correct O(N²) minimum-image path the list is tested
// against. Lennard-Jones spheres take the four-lane loop of smd/lj_pairs_avx2.hpp where the
// processor has AVX2, the scalar loop here otherwise.
#include "core/smoothed_potential.hpp"
#include "core/system.hpp"
#include "smd/lj_pairs_avx2.hpp"
#include "smd/neighbour_list.hpp"
#include "smd/pair_kernels.hpp"
#include <array>
#include <span>
#include <type_traits>
#include <vector>

namespace terrace::smd {

/// Per-body forces and torques (lab frame) and the total smoothed potential energy.
struct Forces {
    std::vector<Vec3> force;
    std::vector<Vec3> torque;
    double potential = 0.0;
    double virial = 0.0;  // Σ r_ij·F_ij, kJ/mol
    long evaluations = 0; // pairs found within r_u

    void reset(std::size_t n) {
        force.assign(n, Vec3::Zero());
        torque.assign(n, Vec3::Zero());
        potential = 0.0;
        virial = 0.0;
        evaluations = 0;
    }
};

/// Accumulates every listed pair within r_u into out, per list slot. x[a] = r - list.offset[a]
/// for the body in slot a; orientation[a] its orientation (core/body_orientation.hpp), read only
/// for potentials that read bodies. The portable loop, one pair at a time.
template <PairPotential P>
[[gnu::flatten]] void
accumulateListedPairsScalar(Forces& out, const Smoothed<P>& potentialIn, const NeighbourList& list,
                            std::span<const Vec3> x,
                            std::span<const typename P::Orientation> orientation) {
    using Orientation = typename P::Orientation;
    using Kernel = PairKernel<Smoothed<P>>;
    // Local copies and raw pointers: the force stores below could otherwise alias the parameters
    // and the vectors' bookkeeping, forcing reloads in every iteration.
    const Smoothed<P> potential = potentialIn;
    const std::array<Vec3, 27> shift = list.imageShift;
    const double outer2 = potential.range() * potential.range();
    const Orientation none = unusedOrientation<P>();
    const std::size_t* start = list.start.data();
    const std::uint32_t* entry = list.entry.data();
    const Vec3* xs = x.data();
    const Orientation* orientations = orientation.data();
    Vec3* force = out.force.data();
    Vec3* torque = out.torque.data();
    double u = 0.0, w = 0.0;
    long evaluations = 0;
    const std::size_t n = x.size();
    const std::size_t entries = list.entry.size();
    // The partner of the entry this far ahead is fetched into the cache now: at 10⁶ bodies the
    // partners' positions, axes, forces and torques span megabytes, and a rod pair's arithmetic
    // (~100 cycles) hides the wait for them.
    constexpr std::size_t prefetchAhead = 8;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 xi = xs[i];
        const Orientation& si = readsBodies<P> ? orientations[i] : none;
        Vec3 fi(0.0, 0.0, 0.0), ti(0.0, 0.0, 0.0); // not Vec3::Zero(): an out-of-line call at -O2
        const std::size_t end = start[i + 1];
        for (std::size_t k = start[i]; k < end; ++k) {
            if (k + prefetchAhead < entries) {
                const std::size_t p = entry[k + prefetchAhead] >> NeighbourList::imageBits;
                __builtin_prefetch(xs + p);
                __builtin_prefetch(force + p, 1);
                if constexpr (readsBodies<P>) __builtin_prefetch(orientations + p);
                if constexpr (isOrientational<P>) __builtin_prefetch(torque + p, 1);
            }
            const std::uint32_t e = entry[k];
            const std::size_t j = e >> NeighbourList::imageBits;
            const Vec3 rij = xi - xs[j] + shift[e & NeighbourList::imageMask];
            const double r2 = rij.squaredNorm();
            if constexpr (Kernel::evaluatesBeyondCutoff) {
                evaluations += r2 < outer2;
            } else {
                if (r2 >= outer2) continue;
                ++evaluations;
            }
            const Orientation& sj = readsBodies<P> ? orientations[j] : none;
            const auto f = Kernel::evaluate(potential, rij, r2, si, sj);
            u += f.U;
            w += rij.dot(f.F);
            fi += f.F;
            force[j] -= f.F;
            if constexpr (isOrientational<P>) {
                ti += f.tauI;
                torque[j] += f.tauJ;
            }
        }
        force[i] += fi;
        if constexpr (isOrientational<P>) torque[i] += ti;
    }
    out.potential += u;
    out.virial += w;
    out.evaluations += evaluations;
}

/// accumulateListedPairsScalar, or for Lennard-Jones spheres on a processor with AVX2 the
/// four-lane loop: the same pairs and per-pair values, summed in another order.
template <PairPotential P>
void accumulateListedPairs(Forces& out, const Smoothed<P>& potential, const NeighbourList& list,
                           std::span<const Vec3> x,
                           std::span<const typename P::Orientation> orientation) {
#if TERRACE_SMD_AVX2
    if constexpr (std::is_same_v<P, LJPotential>) {
        if (avx2Available()) {
            const PairSums sums = accumulateLJPairsAvx2(potential, list, x, out.force);
            out.potential += sums.potential;
            out.virial += sums.virial;
            out.evaluations += sums.evaluations;
            return;
        }
    }
#endif
    accumulateListedPairsScalar(out, potential, list, x, orientation);
}

/// Reference: every pair, minimum image by PeriodicBox, same smoothed interaction.
template <BodyKind K, PairPotential P> Forces allPairsForces(const System<K, Smoothed<P>>& sys) {
    Forces out;
    out.reset(sys.bodies.size());
    for (int i = 0; i < sys.size(); ++i)
        for (int j = i + 1; j < sys.size(); ++j) {
            const auto &bi = sys.bodies[i], &bj = sys.bodies[j];
            const Vec3 rij = sys.box.minimumImage(bi.r - bj.r);
            const double r = rij.norm();
            if (r >= sys.potential.range()) continue;
            const PairForce f =
                sys.potential.evaluate(rij, orientationOf<P, K>(bi), orientationOf<P, K>(bj));
            ++out.evaluations;
            out.potential += f.U;
            out.virial += rij.dot(f.F);
            out.force[i] += f.F;
            out.force[j] -= f.F;
            out.torque[i] += f.tauI;
            out.torque[j] += f.tauJ;
        }
    return out;
}

} // namespace terrace::smd
