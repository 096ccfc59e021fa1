#pragma once
// Whether a lattice start has melted by the end of equilibration. Two order parameters of the
// bodies then, each warned about with its value when above its threshold, naming the key that
// lengthens equilibration (run.equilibrate_ps):
//   translational  S(k₁)/N = |(1/N) Σ_j e^{i k₁·r_j}|², averaged over the first reciprocal
//                  vectors k₁ of the lattice the scene started on (state.lattice,
//                  core/start_lattice.hpp): sc (100) along x, y and z, fcc the (111) family, bcc
//                  the (110) family; 1 on the lattice; in a liquid S(k) is of order 1, so S/N of
//                  order 1/N. Threshold max(0.1, 20/N).
//   orientational  S2, the largest eigenvalue of Q = (1/N) Σ_j (3/2 u_j u_jᵀ − 1/2), u_j the
//                  bodies' axes (rotating bodies only, so not the spheres among rods, whose
//                  axes never move): 1 when aligned; isotropic axes give
//                  0.82/√N on average and 1.75/√N at the 99.5th percentile (measured over 400
//                  draws each at N 64, 216 and 512). Threshold max(0.1, 3/√N).
// Explicit starts (state.particles) are not judged: they have no lattice.
#include "core/engine.hpp"
#include "core/scene.hpp"
#include "core/snapshot.hpp"
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace terrace::cli {

struct LatticeOrder {
    double translational = 0.0; // S(k₁)/N, averaged over the first reciprocal vectors
    double s2 = 0.0;            // 0 for spheres
    int turning = 0;            // the bodies S2 is over: all that rotate (not a sphere among rods)
};

/// Accumulates the order parameters body by body (a large system's bodies in pieces).
class LatticeOrderSum {
public:
    /// The lattice of the scene's start: its kind, cells and first reciprocal vectors.
    explicit LatticeOrderSum(const Scene& scene);
    void add(const Snapshot& bodies, bool rotating);
    LatticeOrder result() const;

private:
    std::vector<Vec3> k_;         // the first reciprocal vectors, 1/Å
    std::vector<double> re_, im_; // Σ cos, Σ sin of k·r, one per vector
    Mat3 q_ = Mat3::Zero();
    int n_ = 0, turning_ = 0;
    bool rotating_ = false;
    std::vector<bool> fixedAxis_; // by species: a sphere among rods, whose axis S2 leaves out
};

/// The warning for a lattice start still ordered (nullopt when melted, or not a lattice start).
std::optional<std::string> meltWarning(const Scene& scene, const LatticeOrder& order, int bodies,
                                       bool rotating);

/// The order of the engine's bodies now, read 4096 at a time.
template <Engine E>
LatticeOrder latticeOrder(const Scene& scene, const E& engine, int bodies, bool rotating) {
    LatticeOrderSum sum(scene);
    std::vector<int> piece;
    for (int begin = 0; begin < bodies; begin += 4096) {
        piece.clear();
        for (int b = begin; b < std::min(bodies, begin + 4096); ++b)
            piece.push_back(b);
        sum.add(engine.snapshot(std::span<const int>(piece)), rotating);
    }
    return sum.result();
}

} // namespace terrace::cli
