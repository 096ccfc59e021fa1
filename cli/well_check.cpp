#include "cli/well_check.hpp"
#include "cli/dispatch.hpp"
#include "dmd/settings.hpp"
#include "dmd/well_coverage.hpp"
#include <sstream>

namespace terrace::cli {

void warnOfSwallowedWells(Scene& scene) {
    if (scene.engine != "dmd" || !(scene.kT() > 0.0)) return;
    dmd::WellCoverage c;
    try {
        c = withBodyAndPotential(scene, [&]<class K, class P>(const P& bare) {
            const auto model = sceneModel(scene, bare, true);
            const auto settings = dmd::readDmdSettings(scene.dmd, model, scene.kT(),
                                                       std::numeric_limits<double>::infinity());
            return dmd::wellCoverage(model, settings.levels, significantWellInKT * scene.kT(),
                                     20.0 * scene.kT());
        });
    } catch (const std::exception&) {
        return;
    }
    if (c.swallowed == 0) return;
    const dmd::DmdSection d = dmd::readDmdSection(scene.dmd);
    const double kT = scene.kT();
    std::ostringstream o;
    o.precision(3);
    o << "dmd: terrace 0 (V = 0) holds the whole well of " << c.swallowed << " of the "
      << c.withWell << " pair orientations sampled whose well is deeper than "
      << significantWellInKT << " kT (the deepest of them " << c.deepestSwallowed / kT
      << " kT): pairs so turned feel no attraction, and DMD samples another fluid; ";
    if (d.levels.empty() && d.terraces.levels == "energy" && d.terraces.n == 0)
        o << "dmd.dV < " << 2.0 * -c.deepestSwallowed / kT
          << " kT resolves the deepest, dmd.dV <= " << 2.0 * significantWellInKT
          << " kT every one deeper than " << significantWellInKT << " kT";
    else
        o << "more levels in the well (a smaller dmd.dV or a larger dmd.terraces.n) resolve them";
    scene.warnings.push_back(o.str());
}

} // namespace terrace::cli
