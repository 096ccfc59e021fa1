#include "cli/design_command.hpp"
#include "cli/dispatch.hpp"
#include "cli/run_command.hpp"
#include "dmd/settings.hpp"
#include "dmd/terrace_design.hpp"
#include <cstdio>

namespace terrace::cli {

namespace {

/// The reference profile from the wall (U = 20 kT) out to the model's range (or 1.1 r_m for a
/// bare potential), with the terraced value of U on each point; columns r (Å), U and V (kJ/mol).
template <PairPotential P>
void printProfile(const dmd::TerraceLevels& levels, const P& model, double rm, double kT) {
    const double rIn = model.reachDistance(20.0 * kT);
    double rOut = 1.1 * rm;
    if constexpr (requires { model.range(); })
        if (std::isfinite(model.range())) rOut = std::max(rOut, model.range());
    constexpr int points = 2000;
    std::printf("r_A,U_kJ_per_mol,V_kJ_per_mol\n");
    for (int k = 0; k <= points; ++k) {
        const double r = rIn + (rOut - rIn) * k / points;
        const double u = dmd::profileEnergy(model, r);
        const double v = levels.energy(levels.terraceOf(u));
        std::printf("%.6f,%.9g,%.9g\n", r, u, v);
    }
}

} // namespace

int printDesign(const DesignRequest& request) {
    RunRequest run;
    run.scenePath = request.scenePath;
    run.overrides = request.overrides;
    run.quiet = true;
    const Scene scene = resolveScene(run);
    return withBodyAndPotential(scene, [&]<BodyKind K, PairPotential P>(const P& bare) {
        const auto model = sceneModel(scene, bare, true);
        const dmd::DmdSection section = dmd::readDmdSection(scene.dmd);
        const auto settings = dmd::readDmdSettings(section, model, scene.kT(),
                                                   std::numeric_limits<double>::infinity());
        const auto& L = settings.levels;
        if constexpr (isSteppedModel<P>) {
            // A step table is its own design: its terraces are the steps, bounded by radii.
            const StepPotential& p = *stepPotentialOf(model);
            const auto& t = p.table;
            std::printf("# %s: step table (potential.steps), %zu steps, hard core %.6g A; kT = "
                        "%.6g kJ/mol, r_m = %.6g A\n",
                        scene.name.c_str(), t.radii.size(), t.hardCore * p.sigma, scene.kT(),
                        settings.rm);
            // A mixture's pairs cross the same terraces, each at the radii below times its own
            // σ_ab over potential.sigma, and with the values below times ε_ab over
            // potential.epsilon (core/step_mixture.hpp).
            if constexpr (requires { model.bare.pairSigma(0, 0); }) {
                std::printf("# each pair at its own sigma_ab and epsilon_ab (the radii below times "
                            "sigma_ab / %.6g A, the values times epsilon_ab / %.6g kJ/mol):",
                            p.sigma, p.epsilon);
                const char* separator = " ";
                for (int a = 0; a < model.bare.species; ++a)
                    for (int b = a; b < model.bare.species; ++b, separator = ", ")
                        std::printf("%s%s-%s %.6g A %.6g kJ/mol", separator,
                                    scene.species[a].name.c_str(), scene.species[b].name.c_str(),
                                    model.bare.pairSigma(a, b),
                                    model.bare.pairEnergyScale(a, b) * p.epsilon);
                std::printf("\n");
            }
            std::printf("terrace,inner_A,outer_A,value_kJ_per_mol\n");
            for (int n = L.lowestTerrace(); n <= L.highestTerrace(); ++n) {
                const double outer = n == 0 ? std::numeric_limits<double>::infinity()
                                            : p.radialRoots(L.lower(n)).inner;
                const double inner =
                    n == L.highestTerrace() ? 0.0 : p.radialRoots(L.upper(n)).inner;
                std::printf("%d,%.9g,%.9g,%.9g\n", n, inner, outer, L.energy(n));
            }
            return 0;
        }
        if (request.profile) {
            printProfile(L, model, settings.rm, scene.kT());
            return 0;
        }
        // Explicit dmd.levels override dV and the design: the header names them, not the
        // uniform defaults they replace.
        if (!section.levels.empty())
            std::printf("# %s: levels explicit (%zu in dmd.levels), values %s, model %s; kT = "
                        "%.6g kJ/mol, r_m = %.6g A\n",
                        scene.name.c_str(), section.levels.size(),
                        section.values.empty() ? "midpoint" : "explicit (dmd.values)",
                        section.model.c_str(), scene.kT(), settings.rm);
        else
            std::printf("# %s: levels %s, values %s, n %d, dV %g kT, model %s; kT = %.6g kJ/mol, "
                        "r_m = %.6g A\n",
                        scene.name.c_str(), section.terraces.levels.c_str(),
                        section.terraces.values.c_str(), section.terraces.n, section.dV,
                        section.model.c_str(), scene.kT(), settings.rm);
        for (const std::string& w : scene.warnings)
            std::printf("# warning: %s\n", w.c_str());
        std::printf("terrace,lower_kJ_per_mol,upper_kJ_per_mol,value_kJ_per_mol\n");
        // Uniform levels are unbounded: print the well and the wall up to 50 kT.
        const int lo = L.isUniform()
                           ? static_cast<int>(std::floor(model.minimumEnergy() / L.step()))
                           : L.lowestTerrace();
        const int hi = L.isUniform() ? static_cast<int>(std::ceil(50.0 * scene.kT() / L.step()))
                                     : L.highestTerrace();
        for (int n = lo; n <= hi; ++n)
            std::printf("%d,%.9g,%.9g,%.9g\n", n, L.lower(n), L.upper(n), L.energy(n));
        return 0;
    });
}

std::string dmdRefusal(const Scene& scene) {
    try {
        withBodyAndPotential(scene, [&]<BodyKind K, PairPotential P>(const P& bare) {
            const auto model = sceneModel(scene, bare, true);
            dmd::readDmdSettings(dmd::readDmdSection(scene.dmd), model, scene.kT(),
                                 scene.boxLength());
            return 0;
        });
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

} // namespace terrace::cli
