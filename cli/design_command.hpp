#pragma once
// `terrace design`: the terraces a scene's DMD would run on, without running it. Prints the
// levels and terrace energies (dmd/terrace_design.hpp), or with --profile the potential along the
// design's reference alignment beside its terraced value, as CSV for any plotting tool.
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

} // namespace terrace::cli
