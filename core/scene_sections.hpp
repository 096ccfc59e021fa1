#pragma once
// The readers of the scene's own sections, one per section, each reading the keys it owns once
// and checking them against the sections read before it (sceneFromJson calls them in this
// order). The engines' sections, dmd and smd, are carried as given: dmd/section.hpp and
// smd/parameters.hpp read them.
#include "core/scene.hpp"
#include "core/scene_json.hpp"

namespace terrace::detail {

void readIdentity(const JsonSection& top, Scene& s);  // name, seed
void readBody(const JsonSection& body, Scene& s);     // body (sites wait for the potential)
void readPotential(const JsonSection& pot, Scene& s); // potential, and what it asks of the body
void readSites(const JsonSection& body, Scene& s);    // body.sites for potential.kind sites
void readSpecies(const JsonSection& top, Scene& s);   // species and potential.pairs (after both)
void checkInertia(const JsonSection& body, const Scene& s);
void readState(const JsonSection& state, Scene& s);
/// kT and thermal motion the time grid resolves; explicit bodies a double can carry.
void checkRepresentable(const JsonSection& top, const Scene& s);
void readRun(const JsonSection& run, Scene& s);
void readOutput(const JsonSection& output, Scene& s);
void readAnalysis(const JsonSection& analysis, Scene& s);

} // namespace terrace::detail
