#pragma once
// What `terrace tradeoff` measures and where: the observables with their tolerances, the
// reference, and the ladders of candidate settings of each engine (cli/tradeoff_command.hpp for
// the loop that runs them).
//
// Observables, each a number per run (the replicas' mean is the estimate):
//   u       ⟨U⟩/(Nε), the potential energy per body in the potential's ε
//   p       P* = Pσ³/ε
//   d       D by Einstein from the MSD, Å²/ps
//   g       the RMS over r ≤ rdf_max of g(r) against the reference's (a curve: estimated from
//           the replicas' mean curves, the noise of both taken out; cli/tradeoff_measure.hpp)
//   g_peak  g(r)'s mean over its highest peak down to half its height above 1 (the window
//           placed on the mean g(r) of every run: cli/tradeoff_measure.hpp, peakWindow)
//   tau_v   ∫ VACF dt up to its first zero, ps (the velocity relaxation time)
//   tau_o   ∫ ⟨s(0)·s(t)⟩ dt up to its first zero, ps (bodies that rotate only)
// DMD gives u, p and g two ways: on its terraced observables (V, the impulse virial, g_d) and by
// the configurational estimators on the same configurations (core/continuous_sums.hpp); the
// tradeoff uses, for each, the one with the smaller measured bias and says which.
//
// Ladders, most accurate first: DMD over ΔV/kT (smallest first) with the paper's uniform terraces
// and the optimal design; SMD over dt for each splitting, dt = sample_fs/k for whole k (so every
// step lands on the sampling and thermostat grids) from the scene's smd.dt_fs up to 10 times it,
// cut at the first dt whose runs fail or stop conserving energy (the stability limit).
// Reference: SMD yoshida4 at half the scene's smd.dt_fs (its own dt⁴ error is checked by the
// yoshida4 rung at the scene's dt, whose bias bounds the reference's by 1/2⁴ of it).
#include "analysis/tradeoff_stats.hpp"
#include "cli/sweep_plan.hpp"
#include "core/scene.hpp"
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace terrace::cli {

enum class Observable { U, P, D, G, GPeak, TauV, TauO };
inline constexpr std::array<Observable, 7> allObservables{
    Observable::U,     Observable::P,    Observable::D,   Observable::G,
    Observable::GPeak, Observable::TauV, Observable::TauO};

const char* observableName(Observable o);
/// What the observable is, with its unit, for tables and plots.
const char* observableMeaning(Observable o);

/// The default tolerances, on the systematic error against the continuous model (see
/// defaultTolerance's definition for each one's reason).
analysis::Tolerance defaultTolerance(Observable o);

/// The least magnitude a relative tolerance of o is a fraction of (the reference's |mean| where
/// it is above): for P the ideal-gas pressure ρ*T*, since P of a liquid crosses zero; for U the
/// thermal energy per body T*, since U of a gas tends to zero (dilute rods at T* 10 have u =
/// −0.03, where 2 % of |u| asked U to 6e-5 kT); none for the others. Reduced units.
double relativeScaleFloor(Observable o, double density, double temperature);

struct TradeoffOptions {
    std::filesystem::path scenePath; // empty: the built-in default scene
    std::vector<std::string> sets;   // --set, for every run
    std::vector<std::pair<Observable, analysis::Tolerance>> tolerances; // --tolerance
    std::vector<Observable> observables; // measured (default all that apply)
    std::filesystem::path out;
    int jobs = 1;
    int biasN = 0;        // bodies of the bias runs; 0: the scene's
    int maxReplicas = 32; // per setting
    int costPairs = 5;    // alternated cost runs of each chosen engine
    double budgetCpuHours = 8.0;
    double alpha = 0.0455; // two-sided level of each decision (z = 2 at one look)
    std::vector<double> dVs{1.0, 0.5, 0.25, 0.125};                    // ΔV/kT of the DMD ladders
    std::vector<std::string> designs{"uniform", "optimal"};            // DMD ladders
    std::vector<std::string> schemes{"verlet", "omelyan", "yoshida4"}; // SMD ladders
    bool quiet = false;
    // Resolve both engines' cheapest settings even when one engine's is already cheaper than any
    // setting of the other could be (cli/tradeoff_dominance.hpp); without it the tradeoff stops
    // there and its ratio is a lower bound.
    bool frontier = false;
};

/// The items of a comma-separated option value ("a,b,c"; an empty item stays, to be refused).
std::vector<std::string> commaList(const std::string& list);

/// Whether dt = sample_fs/k puts a whole number of steps in the scene's sample and thermostat
/// intervals (SMD moves in whole steps; terrace run refuses any other dt).
bool stepsFitGrid(const Scene& scene, int k);

/// "u,p,g" as observables; throws SceneError naming an unknown one.
std::vector<Observable> parseObservables(const std::string& list);

/// "u=0.5%" (relative) or "p=0.01" (absolute); throws SceneError naming the problem.
std::pair<Observable, analysis::Tolerance> parseTolerance(const std::string& text);

/// One candidate setting (or the reference): the engine, its ladder and its place on it.
struct Setting {
    std::string engine;              // dmd | smd
    std::string ladder;              // dmd-uniform, dmd-optimal, smd-verlet, …, reference
    double x = 0.0;                  // ΔV/kT, or dt in fs
    std::vector<Override> overrides; // what makes the scene this setting
    bool interpolated = false;       // placed by the law fit, not on the ladder
    std::string label() const;       // directory-safe, e.g. dmd-uniform-dV0.25
};

/// The reference and every ladder's rungs for `scene` (most accurate first within each ladder).
struct TradeoffLadders {
    Setting reference;
    std::vector<std::vector<Setting>> ladders;
};
TradeoffLadders tradeoffLadders(const Scene& scene, const TradeoffOptions& options);

/// The DMD setting at ΔV/kT = x on `ladder` (dmd-uniform or dmd-optimal).
Setting dmdSetting(const std::string& ladder, double x);
/// The SMD setting of `scheme` at dt = x fs.
Setting smdSetting(const std::string& scheme, double dtFs);

/// The bias law's exponent where theory fixes it: dt² for the second-order splittings, dt⁴ for
/// yoshida4; DMD's is fitted.
std::optional<double> knownOrder(const Setting& s);

/// One observable's biases along a ladder (one per x) and its tolerance.
struct LadderBiases {
    std::vector<analysis::Estimate> bias;
    double tolerance = 0.0;
};

/// The x (ΔV/kT or dt in fs) at which the first of the power laws fitted to each observable's
/// biases along x reaches its tolerance, with the law's exponent fixed where theory fixes it;
/// +inf when no law is fitted or none reaches its tolerance.
double lawCrossing(const std::vector<double>& x, const std::vector<LadderBiases>& observables,
                   std::optional<double> order);

/// How far below its most accurate rung a ladder is extended by its law: a sixteenth of it.
constexpr double extrapolationReach = 1.0 / 16.0;
/// The extended setting sits this far inside the law's crossing, so that its own runs, which
/// decide, are not left at the edge of the tolerance by the law's error.
constexpr double extrapolationMargin = 0.8;

/// Where a ladder whose every rung lies outside its tolerance is extended: the law's crossing
/// (lawCrossing) by the margin, when that lies below the most accurate rung `front` and within
/// reach of it; nullopt otherwise (the law does not cross below front, or crosses out of reach).
std::optional<double> extensionBelow(double front, double crossing);

} // namespace terrace::cli
