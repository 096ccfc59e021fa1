#pragma once
// What `terrace tradeoff` writes of its search (cli/tradeoff_state.hpp): tradeoff.json's record of
// every setting, estimate and decision, tradeoff.csv (a row per setting and observable),
// tradeoff.png (bias against cost per observable, with the tolerance band), and the words the
// verdict names settings and tolerances by.
#include "cli/tradeoff_state.hpp"
#include <nlohmann/json.hpp>
#include <string>

namespace terrace::cli {

/// One observable's bias on a setting of `engine` ("dmd" or "smd"), as tradeoff.json holds it.
nlohmann::json biasJson(const ObservableBias& b, const std::string& engine);

/// Everything measured so far: written after every round (with no verdict yet) and at the end.
nlohmann::json report(const Tradeoff& t);

/// The reference's own dt error, bounded through yoshida4 at twice its step, into out
/// ("reference_check"), with a note whether it is shown converged; nothing where that rung is
/// not on the ladders.
void reportReferenceCheck(Tradeoff& t, nlohmann::json& out);

/// A setting as the verdict names it ("DMD dV = 0.25 kT (optimal terraces; u configurational,
/// ...)", "SMD verlet dt = 1.8 fs").
std::string describe(const Setting& s, const Tradeoff& t);

/// The tolerances as the verdict states them ("u +-0.5 %, p +-2 %, ...").
std::string toleranceText(const Tradeoff& t);

/// tradeoff.csv: a row per setting and observable.
void writeTable(const Tradeoff& t);

/// tradeoff.dat, and from it (where gnuplot is) tradeoff.png: bias/tolerance against cost, one
/// panel per observable, the band |bias| <= tolerance shaded.
void writePlot(const Tradeoff& t);

} // namespace terrace::cli
