#pragma once
// A scene made ready to run: the engines' sections, which the scene carries as given, read and
// checked by the modules that own them (dmd/section.hpp, smd/parameters.hpp) against the rest
// of the scene, and written back resolved, every key given, so that the scene recorded next to
// a run says everything it ran with. The run command, `terrace design` and the sweep planner
// all call this before any work, so that a bad key is a one-line error naming it, and a bad
// sweep fails before any of its runs starts.
#include "core/scene.hpp"
#include <string>

namespace terrace::cli {

/// Throws SceneError "<origin>: <key>: <problem>"; adds the sections' warnings to scene.warnings.
void resolveEngineSections(Scene& scene, const std::string& origin);

} // namespace terrace::cli
