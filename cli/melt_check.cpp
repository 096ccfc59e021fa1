#include "cli/melt_check.hpp"
#include "core/start_lattice.hpp"
#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>

namespace terrace::cli {

LatticeOrderSum::LatticeOrderSum(const Scene& scene) {
    const int n = scene.state.particles.empty() ? scene.state.n : int(scene.state.particles.size());
    k_ = latticeShape(n, scene.boxLength(), latticeKind(scene.state.lattice),
                      scene.state.lattice_aspect)
             .firstReciprocal();
    re_.assign(k_.size(), 0.0);
    im_.assign(k_.size(), 0.0);
    for (const auto& s : scene.species)
        fixedAxis_.push_back(s.kind == "sphere");
}

void LatticeOrderSum::add(const Snapshot& bodies, bool rotating) {
    rotating_ = rotating;
    for (int j = 0; j < bodies.size(); ++j) {
        const Vec3& r = bodies.position[j];
        for (std::size_t v = 0; v < k_.size(); ++v) {
            const double phase = k_[v].dot(r);
            re_[v] += std::cos(phase);
            im_[v] += std::sin(phase);
        }
        const bool fixed = !bodies.species.empty() && fixedAxis_.at(bodies.species[j]);
        if (rotating && !fixed) {
            const Vec3& u = bodies.axis[j];
            q_ += 1.5 * u * u.transpose() - 0.5 * Mat3::Identity();
            ++turning_;
        }
        ++n_;
    }
}

LatticeOrder LatticeOrderSum::result() const {
    LatticeOrder o;
    if (n_ == 0) return o;
    const double vectors = double(k_.size());
    for (std::size_t v = 0; v < k_.size(); ++v)
        o.translational += (re_[v] * re_[v] + im_[v] * im_[v]) / (vectors * double(n_) * n_);
    if (rotating_ && turning_ > 0) {
        Eigen::SelfAdjointEigenSolver<Mat3> eig(q_ / double(turning_));
        o.s2 = eig.eigenvalues().maxCoeff();
        o.turning = turning_;
    }
    return o;
}

std::optional<std::string> meltWarning(const Scene& scene, const LatticeOrder& order, int bodies,
                                       bool rotating) {
    if (!scene.state.particles.empty() || bodies < 2) return std::nullopt;
    const double tLimit = std::max(0.1, 20.0 / bodies);
    const int turning = order.turning > 0 ? order.turning : bodies;
    const double sLimit = std::max(0.1, 3.0 / std::sqrt(double(turning)));
    const bool ordered = order.translational > tLimit, aligned = rotating && order.s2 > sLimit;
    if (!ordered && !aligned) return std::nullopt;
    auto show = [](double x) {
        char t[32];
        std::snprintf(t, sizeof t, "%.3g", x);
        return std::string(t);
    };
    std::string what;
    if (ordered)
        what = "the lattice's structure factor S(k1)/N = " + show(order.translational) + " > " +
               show(tLimit) + " (a liquid: ~1/N)";
    if (aligned)
        what += std::string(ordered ? ", " : "") + "orientational order S2 = " + show(order.s2) +
                " > " + show(sLimit) + " (isotropic: ~0.8/sqrt(N))";
    return "the lattice start has not melted after run.equilibrate_ps = " +
           show(scene.run.equilibrate_ps) + " ps: " + what + "; raise run.equilibrate_ps";
}

} // namespace terrace::cli
