#pragma once
// Total force, torque and potential energy of the smoothed continuous potential (smoothed_cutoff
// .hpp) by a loop over the Verlet list, each pair once with Newton's third law: F_j -= F_ij,
// τ_i += τ_ij, τ_j += τ_ji. Units: kJ/mol/Å, kJ/mol, kJ/mol.
// allPairsForces() is the slow, obviously correct O(N²) minimum-image path the list is tested
// against.
#include "core/system.hpp"
#include "smd/neighbour_list.hpp"
#include "smd/pair_kernels.hpp"
#include "smd/smoothed_cutoff.hpp"
#include <span>
#include <vector>

namespace terrace::smd {

/// Per-body forces and torques (lab frame) and the total smoothed potential energy.
struct Forces {
    std::vector<Vec3> force;
    std::vector<Vec3> torque;
    double potential = 0.0;
    long evaluations = 0; // pairs found within r_u

    void reset(std::size_t n) {
        force.assign(n, Vec3::Zero());
        torque.assign(n, Vec3::Zero());
        potential = 0.0;
        evaluations = 0;
    }
};

/// Accumulates every listed pair within r_u into out, per list slot. x[a] = r - list.offset[a]
/// for the body in slot a; axis is read only for orientational potentials.
template <PairPotential P>
[[gnu::flatten]] void accumulateListedPairs(Forces& out, const P& potential,
                                            const SmoothedCutoff& cut, const NeighbourList& list,
                                            std::span<const Vec3> x, std::span<const Vec3> axis) {
    const double outer2 = cut.outer * cut.outer;
    const Vec3 noAxis = Vec3::UnitZ();
    double u = 0.0;
    long evaluations = 0;
    const std::size_t n = x.size();
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 xi = x[i];
        const Vec3& si = P::orientational ? axis[i] : noAxis;
        Vec3 fi = Vec3::Zero(), ti = Vec3::Zero();
        for (std::size_t k = list.start[i]; k < list.start[i + 1]; ++k) {
            const std::uint32_t e = list.entry[k];
            const std::size_t j = e >> NeighbourList::imageBits;
            const Vec3 rij = xi - x[j] + list.imageShift[e & NeighbourList::imageMask];
            const double r2 = rij.squaredNorm();
            if (r2 >= outer2) continue;
            const Vec3& sj = P::orientational ? axis[j] : noAxis;
            const PairForce f = PairKernel<P>::evaluate(potential, cut, rij, r2, si, sj);
            ++evaluations;
            u += f.U;
            fi += f.F;
            out.force[j] -= f.F;
            if constexpr (P::orientational) {
                ti += f.tauI;
                out.torque[j] += f.tauJ;
            }
        }
        out.force[i] += fi;
        if constexpr (P::orientational) out.torque[i] += ti;
    }
    out.potential += u;
    out.evaluations += evaluations;
}

/// Reference: every pair, minimum image by PeriodicBox, same smoothed interaction.
template <BodyKind K, PairPotential P>
Forces allPairsForces(const System<K, P>& sys, const SmoothedCutoff& cut) {
    Forces out;
    out.reset(sys.bodies.size());
    for (int i = 0; i < sys.size(); ++i)
        for (int j = i + 1; j < sys.size(); ++j) {
            const auto &bi = sys.bodies[i], &bj = sys.bodies[j];
            const Vec3 rij = sys.box.minimumImage(bi.r - bj.r);
            const double r = rij.norm();
            if (r >= cut.outer) continue;
            const PairForce f =
                smoothed(sys.potential.evaluate(rij, K::axis(bi), K::axis(bj)), rij, r, cut);
            ++out.evaluations;
            out.potential += f.U;
            out.force[i] += f.F;
            out.force[j] -= f.F;
            out.torque[i] += f.tauI;
            out.torque[j] += f.tauJ;
        }
    return out;
}

} // namespace terrace::smd
