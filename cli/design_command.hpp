#pragma once
// `terrace design`: the terraces a scene's DMD would run on, without running it. Prints the
// levels and terrace energies (dmd/terrace_design.hpp), or with --profile the potential along the
// design's reference alignment beside its terraced value, as CSV for any plotting tool.
#include "core/scene.hpp"
#include <string>
#include <vector>

namespace terrace::cli {

struct DesignRequest {
    std::string scenePath; // empty: the built-in default scene
    std::vector<std::string> overrides;
    bool profile = false;
};

/// Writes the design's table (or profile) to standard output; returns the exit status.
int printDesign(const DesignRequest& request);

/// Why DMD cannot run `scene` (its terraces: a level on the minimum, too many terraces, a box
/// narrower than 2 r_m), or "" when it can: what the engine would refuse, found without one.
std::string dmdRefusal(const Scene& scene);

} // namespace terrace::cli
