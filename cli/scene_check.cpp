#include "cli/scene_check.hpp"
#include "dmd/section.hpp"
#include "smd/parameters.hpp"

namespace terrace::cli {

void resolveEngineSections(Scene& scene, const std::string& origin) {
    dmd::resolveDmdSection(scene, origin);
    smd::resolveSmdSection(scene, origin);
}

} // namespace terrace::cli
