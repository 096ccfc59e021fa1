#pragma once
// Keys the running engine does not read. Every scene holds both engines' sections (dmd, smd), so
// that one file serves either engine, and only the running engine reads its own; a scene file's
// sections are therefore never judged. A key that the command line sets in the other engine's
// section (--set smd.dt_fs=0.7 on a DMD run), or that a sweep's axis sets for a run of the other
// engine, has no effect on that run and is almost always a slip: it is a warning naming the
// engine, or an error under --strict. A sweep's common keys ("set", --set) serve all its runs, so
// they are judged against the engines the sweep runs at all (cli/sweep_plan.hpp).
#include <string>
#include <vector>

namespace terrace::cli {

/// The engine whose section holds `dottedKey` ("dmd" for dmd.dV, dmd or dmd.terraces.n; "smd"
/// likewise), or "" for a key both engines read.
std::string engineOfKey(const std::string& dottedKey);

/// The key of a "key=value" override (the whole text when it has no '=').
std::string overrideKey(const std::string& assignment);

/// One line on `what` ("--set smd.dt_fs=0.7"), a key of `keyEngine`'s section, which `reader` (a
/// clause: "the run's engine, dmd,") does not read.
std::string ignoredKeyNote(const std::string& what, const std::string& keyEngine,
                           const std::string& reader);
/// The note as a warning, and as a refusal under --strict.
std::string asWarning(const std::string& note);
std::string asRefusal(const std::string& note);

/// The overrides among `overrides` ("key=value") whose keys `engine` does not read, as warnings
/// (ignoredKeyNote, for `reader`) in their order; under `strict` the first is thrown instead, as
/// a SceneError.
std::vector<std::string> judgeOverrides(const std::vector<std::string>& overrides,
                                        const std::string& engine, const std::string& reader,
                                        bool strict);

} // namespace terrace::cli
