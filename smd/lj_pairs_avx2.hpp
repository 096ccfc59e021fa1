#pragma once
// The SMD pair loop for Lennard-Jones spheres, four listed partners at a time with AVX2: the
// kernel of smd/pair_kernels.hpp (PairKernel<Smoothed<LJPotential>>),
//     s6 = (σ²/r²)³,   U = 4ε(s6² - s6),   F_ij = 24ε(2 s6² - s6)/r² · r_ij,
// times the switch of core/smoothed_cutoff.hpp (paper eqs. 22-23) between r_l and r_u,
//     U_s = g U,   F_s = (g f - U g'(r) r/r²) r_ij   (f = F/r),
// evaluated lane by lane with the same operations in the same order, so that each pair's U and
// F are those of the scalar kernel bit for bit; only the order of the sums differs (force on
// body i, U, and the virial, here Σ f r² rather than Σ r_ij·F_ij), which is round-off.
//
// Why: the scalar loop spends its time per listed pair mostly on two branches the predictor
// cannot learn (r < r_u and r > r_l each hold for roughly half the listed pairs) and on the
// latency of a division and a square root per pair. Here every lane computes the switch and the
// cutoff is a mask: no data-dependent branch, one vector division and one vector square root per
// four pairs. Pairs beyond r_u (about a quarter of the list) cost their lane.
// The partner's force is still subtracted pair by pair (Newton's third law over the half list);
// a full list (not tried) would drop that scatter but double the divisions and square roots.
// Positions and forces are copied into arrays of four doubles per body for the loop, so that
// each partner costs one aligned load and one load-subtract-store.
//
// Chosen at run time (smd/simd.hpp); without AVX2, the scalar loop of smd/pair_forces.hpp.
// Units: Å, kJ/mol, kJ/mol/Å.
#include "core/lj_potential.hpp"
#include "core/smoothed_potential.hpp"
#include "smd/neighbour_list.hpp"
#include "smd/simd.hpp"
#include <cstdint>
#include <span>
#include <vector>

namespace terrace::smd {

/// What a pair loop adds up besides the per-body forces.
struct PairSums {
    double potential = 0.0; // kJ/mol
    double virial = 0.0;    // Σ r_ij·F_ij, kJ/mol
    long evaluations = 0;   // pairs within r_u
};

#if TERRACE_SMD_AVX2

namespace detail {

/// The constants of the lane kernel, each broadcast to the four lanes.
struct LJLanes {
    __m256d sigma2, fourEps, twentyFourEps, one, two, minusSix;
    __m256d inner2, outer2, rl, ru, ruMinus3rl, invWidthCubed, beyond;
};

TERRACE_AVX2_INLINE inline LJLanes ljLanes(const Smoothed<LJPotential>& model) {
    const LJPotential& lj = model.bare;
    const SmoothedCutoff& cut = model.cut;
    const double rl = cut.inner(), ru = cut.outer();
    // 1/(r_u - r_l)³ as SmoothedCutoff computes it, so that g and g' round alike.
    const double invWidthCubed = 1.0 / ((ru - rl) * (ru - rl) * (ru - rl));
    return {_mm256_set1_pd(lj.sigma * lj.sigma),
            _mm256_set1_pd(4.0 * lj.epsilon),
            _mm256_set1_pd(24.0 * lj.epsilon),
            _mm256_set1_pd(1.0),
            _mm256_set1_pd(2.0),
            _mm256_set1_pd(-6.0),
            _mm256_set1_pd(rl * rl),
            _mm256_set1_pd(ru * ru),
            _mm256_set1_pd(rl),
            _mm256_set1_pd(ru),
            _mm256_set1_pd(ru - 3.0 * rl),
            _mm256_set1_pd(invWidthCubed),
            _mm256_set1_pd(4.0 * ru * ru)};
}

/// A 3-vector padded to four doubles, (x, y, z, 0): one aligned load or store.
struct alignas(32) Padded {
    double v[4];
};

/// (x, y, z, 0) of a Vec3.
TERRACE_AVX2_INLINE inline __m256d padded(const Vec3& v) {
    return _mm256_set_pd(0.0, v.z(), v.y(), v.x());
}

/// Lanes of x²+y²+z² for four (x, y, z, 0) vectors, summed as (x² + y²) + z².
TERRACE_AVX2_INLINE inline __m256d squaredNorms(__m256d d0, __m256d d1, __m256d d2, __m256d d3) {
    const __m256d h01 = _mm256_hadd_pd(_mm256_mul_pd(d0, d0), _mm256_mul_pd(d1, d1));
    const __m256d h23 = _mm256_hadd_pd(_mm256_mul_pd(d2, d2), _mm256_mul_pd(d3, d3));
    // h01 = (x0²+y0², x1²+y1², z0²+0, z1²+0), likewise h23.
    return _mm256_add_pd(_mm256_permute2f128_pd(h01, h23, 0x20),
                         _mm256_permute2f128_pd(h01, h23, 0x31));
}

/// U_s and f_s = |F_s|/r of four pairs at squared separations r2 (each > 0), zero beyond r_u.
/// The operations and their order are those of PairKernel<Smoothed<LJPotential>> and of
/// SmoothedCutoff::switching and switchingSlope.
TERRACE_AVX2_INLINE inline void ljLaneKernel(const LJLanes& c, __m256d r2, __m256d& u,
                                             __m256d& forceOverR) {
    const __m256d inv2 = _mm256_div_pd(c.one, r2);
    const __m256d s2 = _mm256_mul_pd(c.sigma2, inv2);
    const __m256d s6 = _mm256_mul_pd(_mm256_mul_pd(s2, s2), s2);
    const __m256d uBare = _mm256_mul_pd(_mm256_mul_pd(c.fourEps, s6), _mm256_sub_pd(s6, c.one));
    const __m256d twoS6MinusOne = _mm256_sub_pd(_mm256_mul_pd(c.two, s6), c.one);
    const __m256d fBare =
        _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(c.twentyFourEps, s6), twoS6MinusOne), inv2);
    // The switch, for every lane; kept only where r² > r_l².
    const __m256d r = _mm256_sqrt_pd(r2);
    const __m256d a = _mm256_sub_pd(c.ru, r);
    const __m256d g = _mm256_mul_pd(
        _mm256_mul_pd(_mm256_mul_pd(a, a), _mm256_add_pd(c.ruMinus3rl, _mm256_mul_pd(c.two, r))),
        c.invWidthCubed);
    const __m256d slope = _mm256_mul_pd(
        _mm256_mul_pd(_mm256_mul_pd(c.minusSix, a), _mm256_sub_pd(r, c.rl)), c.invWidthCubed);
    const __m256d fSwitched =
        _mm256_sub_pd(_mm256_mul_pd(g, fBare),
                      _mm256_mul_pd(_mm256_mul_pd(uBare, slope), _mm256_mul_pd(r, inv2)));
    const __m256d uSwitched = _mm256_mul_pd(uBare, g);
    const __m256d inShell = _mm256_cmp_pd(r2, c.inner2, _CMP_GT_OQ);
    const __m256d inRange = _mm256_cmp_pd(r2, c.outer2, _CMP_LT_OQ);
    u = _mm256_and_pd(inRange, _mm256_blendv_pd(uBare, uSwitched, inShell));
    forceOverR = _mm256_and_pd(inRange, _mm256_blendv_pd(fBare, fSwitched, inShell));
}

/// Running totals of the loop, four lanes each.
struct LaneSums {
    __m256d potential, virial;
    long evaluations;
};

/// Four listed partners of body xi (entries e[0..3]; lanes at and past `lanes` are padding):
/// their forces go to fi and, with the opposite sign, to force[j]. Positions and forces are
/// (x, y, z, 0), one load or store each.
TERRACE_AVX2_INLINE inline void fourPairs(const LJLanes& c, const std::uint32_t* e, int lanes,
                                          __m256d xi, const Padded* xs, const __m256d* shift,
                                          Padded* force, __m256d& fi, LaneSums& sums) {
    constexpr unsigned bits = NeighbourList::imageBits;
    constexpr std::uint32_t mask = NeighbourList::imageMask;
    const std::size_t j0 = e[0] >> bits, j1 = e[1] >> bits, j2 = e[2] >> bits, j3 = e[3] >> bits;
    // r_ij = (x_i - x_j) + shift, as in the scalar loop.
    const __m256d d0 =
        _mm256_add_pd(_mm256_sub_pd(xi, _mm256_load_pd(xs[j0].v)), shift[e[0] & mask]);
    const __m256d d1 =
        _mm256_add_pd(_mm256_sub_pd(xi, _mm256_load_pd(xs[j1].v)), shift[e[1] & mask]);
    const __m256d d2 =
        _mm256_add_pd(_mm256_sub_pd(xi, _mm256_load_pd(xs[j2].v)), shift[e[2] & mask]);
    const __m256d d3 =
        _mm256_add_pd(_mm256_sub_pd(xi, _mm256_load_pd(xs[j3].v)), shift[e[3] & mask]);
    __m256d r2 = squaredNorms(d0, d1, d2, d3);
    if (lanes < 4) { // padding lanes: put them beyond r_u, where the kernel returns zeros
        const __m256d lane = _mm256_set_pd(3.0, 2.0, 1.0, 0.0);
        const __m256d padding = _mm256_cmp_pd(lane, _mm256_set1_pd(lanes), _CMP_GE_OQ);
        r2 = _mm256_blendv_pd(r2, c.beyond, padding);
    }
    __m256d u, f;
    ljLaneKernel(c, r2, u, f);
    sums.potential = _mm256_add_pd(sums.potential, u);
    sums.virial = _mm256_add_pd(sums.virial, _mm256_mul_pd(f, r2));
    sums.evaluations +=
        __builtin_popcount(_mm256_movemask_pd(_mm256_cmp_pd(r2, c.outer2, _CMP_LT_OQ)));
    // F_ij = f r_ij, lane by lane.
    const __m256d f0 = _mm256_mul_pd(_mm256_permute4x64_pd(f, 0x00), d0);
    const __m256d f1 = _mm256_mul_pd(_mm256_permute4x64_pd(f, 0x55), d1);
    const __m256d f2 = _mm256_mul_pd(_mm256_permute4x64_pd(f, 0xAA), d2);
    const __m256d f3 = _mm256_mul_pd(_mm256_permute4x64_pd(f, 0xFF), d3);
    fi = _mm256_add_pd(_mm256_add_pd(fi, _mm256_add_pd(f0, f1)), _mm256_add_pd(f2, f3));
    // Padding lanes carry zero forces to their (valid) stand-in partner.
    _mm256_store_pd(force[j0].v, _mm256_sub_pd(_mm256_load_pd(force[j0].v), f0));
    _mm256_store_pd(force[j1].v, _mm256_sub_pd(_mm256_load_pd(force[j1].v), f1));
    _mm256_store_pd(force[j2].v, _mm256_sub_pd(_mm256_load_pd(force[j2].v), f2));
    _mm256_store_pd(force[j3].v, _mm256_sub_pd(_mm256_load_pd(force[j3].v), f3));
}

TERRACE_AVX2_INLINE inline double laneTotal(__m256d v) {
    alignas(32) double lane[4];
    _mm256_store_pd(lane, v);
    return (lane[0] + lane[1]) + (lane[2] + lane[3]);
}

} // namespace detail

/// Adds every listed pair's force to force[slot] (F_j -= F_ij over the half list) for x[a] =
/// r - list.offset[a], and returns U, the virial and the pairs within r_u. The contract of
/// accumulateListedPairs for Smoothed<LJPotential>; callable only when avx2Available().
TERRACE_AVX2 inline PairSums accumulateLJPairsAvx2(const Smoothed<LJPotential>& model,
                                                   const NeighbourList& list,
                                                   std::span<const Vec3> x, std::span<Vec3> force) {
    const detail::LJLanes c = detail::ljLanes(model);
    __m256d shift[27];
    for (int a = 0; a < 27; ++a)
        shift[a] = detail::padded(list.imageShift[a]);
    // Positions and forces padded to four doubles, kept from call to call (no page faults of a
    // fresh allocation at every step).
    const std::size_t n = x.size();
    thread_local std::vector<detail::Padded> paddedX, paddedForce;
    paddedX.resize(n);
    paddedForce.assign(n, detail::Padded{});
    for (std::size_t a = 0; a < n; ++a)
        _mm256_store_pd(paddedX[a].v, detail::padded(x[a]));
    const std::size_t* start = list.start.data();
    const std::uint32_t* entry = list.entry.data();
    const detail::Padded* xs = paddedX.data();
    detail::Padded* f = paddedForce.data();
    detail::LaneSums sums{_mm256_setzero_pd(), _mm256_setzero_pd(), 0};
    for (std::size_t i = 0; i < n; ++i) {
        const __m256d xi = _mm256_load_pd(xs[i].v);
        __m256d fi = _mm256_setzero_pd();
        std::size_t k = start[i];
        const std::size_t end = start[i + 1];
        for (; k + 4 <= end; k += 4)
            detail::fourPairs(c, entry + k, 4, xi, xs, shift, f, fi, sums);
        if (k < end) {
            // The last one to three partners; the padding lanes stand in body i itself, at zero
            // separation, which fourPairs moves beyond r_u.
            const std::uint32_t self = detail::pack(i, 13);
            std::uint32_t tail[4] = {self, self, self, self};
            for (std::size_t t = 0; k + t < end; ++t)
                tail[t] = entry[k + t];
            detail::fourPairs(c, tail, int(end - k), xi, xs, shift, f, fi, sums);
        }
        _mm256_store_pd(f[i].v, _mm256_add_pd(_mm256_load_pd(f[i].v), fi));
    }
    for (std::size_t a = 0; a < n; ++a)
        force[a] += Vec3(f[a].v[0], f[a].v[1], f[a].v[2]);
    return {detail::laneTotal(sums.potential), detail::laneTotal(sums.virial), sums.evaluations};
}

#endif // TERRACE_SMD_AVX2

} // namespace terrace::smd
