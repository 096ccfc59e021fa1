#include "cli/scene_check.hpp"
#include "core/scene_units.hpp"
#include "dmd/section.hpp"
#include "smd/parameters.hpp"

namespace terrace::cli {

void resolveEngineSections(Scene& scene, const std::string& origin) {
    try {
        dmd::resolveDmdSection(scene, origin);
        smd::resolveSmdSection(scene, origin);
    } catch (const SceneError& e) { // under lj, its numbers are the converted ones: say so
        const UnitSystem u = unitSystem(scene);
        if (!u.reduced()) throw;
        throw SceneError(std::string(e.what()) + reducedNote(u));
    }
}

} // namespace terrace::cli
