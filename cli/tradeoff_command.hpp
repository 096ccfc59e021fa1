#pragma once
// `terrace tradeoff SCENE`: does DMD pay for this scene at these tolerances? It measures, for
// each engine, the cheapest setting whose systematic error against the continuous model is
// resolved within tolerance on every observable, and the cost ratio of the two at the scene's N.
//
//   reference   SMD yoshida4 at half the scene's dt, 8 replicas to begin with (the fewer degrees
//               of freedom of the two sides set each decision's Student factor), doubled until
//               its standard error is below a third of every tolerance and below the
//               candidate's wherever a decision is open
//   candidates  the ladders of cli/tradeoff_plan.hpp, two replicas each to begin with
//   decisions   each rung's bias on each observable (cli/tradeoff_measure.hpp) is Within,
//               Outside or Unresolved at z = sequentialZ(α, looks) (analysis/tradeoff_stats.hpp);
//               a rung is Within when every observable is, Outside when one is (or its runs fail
//               or stop conserving energy: the stability limit). The unresolved rungs that could
//               still be a ladder's cheapest Within get more replicas, at the next count of the
//               fixed doubling schedule that the projection says could resolve them, until none
//               is left or the budget is spent (then the note says so)
//   law         where a ladder's cheapest Within rung has an Outside rung next to it, the bias
//               is fitted to c·x^p per observable (p fixed at 2 or 4 for the splittings) and the
//               setting where the first observable reaches its tolerance is placed between them
//               and decided with its own replicas
//   early stop  once one engine's cheapest Within rung costs less, at the bias runs' N, than the
//               other engine's cost floor (cli/tradeoff_dominance.hpp), the two are timed in the
//               cost window; resolved cheaper there, the question is answered: the loop stops
//               and the verdict's ratio, to the floor's rung, says "at least" (unless --frontier)
//   open rungs  a rung still Unresolved at the end and cheaper than its engine's chosen one may
//               be within: the chosen settings' ratio is then one end of the answer, and the
//               verdict says "at least" where the other end stays on the same side of 1, or
//               gives no verdict (cli/tradeoff_dominance.hpp, openRungVerdict)
//   cost        the two engines' chosen settings at the scene's N, alternated A B A B for
//               `costPairs` pairs, one run at a time; the ratio's median and its order-statistics
//               interval
//
// Every run goes through the sweep machinery into OUT/runs/<setting>_r<k> (so -j works, and a
// killed tradeoff given the same command continues: finished runs are kept). OUT gets
// tradeoff.json (every run, estimate and decision), tradeoff.csv (a row per setting and
// observable), tradeoff.png (bias against cost per observable, with the tolerance band; needs
// gnuplot) and the verdict on standard output.
//
// The parts: the search's state (cli/tradeoff_state.hpp), its runs on disk (tradeoff_runs), its
// steps (tradeoff_search), its record (tradeoff_report), the settings the verdict compares
// (tradeoff_choice), the cost windows (tradeoff_cost) and the verdict (tradeoff_verdict).
#include "cli/tradeoff_plan.hpp"

namespace terrace::cli {

/// Runs the tradeoff; exit status 0 with a verdict, 1 when no verdict could be reached (the note
/// says why), 128 + a signal when stopped by one (the same command goes on later).
int runTradeoff(const TradeoffOptions& options);

} // namespace terrace::cli
