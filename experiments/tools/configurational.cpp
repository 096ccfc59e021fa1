#include "experiments/tools/configurational.hpp"
#include "core/initial_state.hpp"
#include "core/pressure.hpp"
#include "core/smoothed_potential.hpp"
#include "core/xyz.hpp"
#include <stdexcept>

namespace terrace::experiments {
namespace {

template <PairPotential P>
Configurational average(const std::vector<Snapshot>& frames, const Smoothed<P>& model, double mass,
                        double sigma, double epsilon) {
    Configurational c;
    const double range2 = model.range() * model.range();
    for (const Snapshot& f : frames) {
        const PeriodicBox box{f.boxLength};
        const double inverse = 1.0 / box.length;
        double U = 0.0, W = 0.0, v2 = 0.0;
        for (int i = 0; i < f.size(); ++i) {
            v2 += f.velocity[i].squaredNorm();
            for (int j = i + 1; j < f.size(); ++j) {
                const Vec3 rij = box.minimumImage(f.position[i] - f.position[j], inverse);
                if (rij.squaredNorm() >= range2) continue;
                const PairForce p = model.evaluate(rij, f.axis[i], f.axis[j]);
                U += p.U;
                W += rij.dot(p.F);
            }
        }
        const double pressure = virialPressure(0.5 * mass * v2, W, box.volume());
        c.potentialPerBody += U / f.size() / double(frames.size());
        c.pressureReduced += reducedPressure(pressure, sigma, epsilon) / double(frames.size());
    }
    c.frames = static_cast<int>(frames.size());
    return c;
}

} // namespace

Configurational configurational(const std::filesystem::path& dir) {
    const Scene scene = loadScene((dir / "scene.json").string());
    std::string partial;
    const auto frames = readTrajectory((dir / "trajectory.xyz").string(), &partial);
    if (frames.empty())
        throw std::runtime_error((dir / "trajectory.xyz").string() + ": no whole frame");
    const double m = scene.body.mass, sigma = scene.potential.sigma, eps = scene.potential.epsilon;
    if (scene.potential.kind == "rod-lj")
        return average(frames, Smoothed<RodPotential>{rodPotential(scene), sceneCutoff(scene)}, m,
                       sigma, eps);
    if (scene.potential.kind == "lj")
        return average(frames, Smoothed<LJPotential>{ljPotential(scene), sceneCutoff(scene)}, m,
                       sigma, eps);
    throw std::runtime_error("configurational: unknown potential.kind " + scene.potential.kind);
}

} // namespace terrace::experiments
