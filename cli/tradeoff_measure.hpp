#pragma once
// The numbers `terrace tradeoff` takes from each finished run, and a setting's bias on each
// observable from its replicas against the reference's (cli/tradeoff_plan.hpp for the
// observables). Pure functions of what the runs left on disk.
#include "analysis/tradeoff_stats.hpp"
#include "cli/tradeoff_plan.hpp"
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace terrace::cli {

/// How an observable was estimated: on the engine's own dynamics variables (DMD: terraced V,
/// impulse virial, g_d; SMD: the continuous ones, its own) or by the configurational estimators
/// (continuous U, W and g_c on the same configurations).
enum class Estimator { Own, Configurational };
const char* estimatorName(Estimator e, const std::string& engine);

/// One run's observables.
struct ReplicaResult {
    bool ok = false;
    std::string failure;                 // why not ok: the run's error, or energy not conserved
    bool beyondStability = false;        // the failure is SMD's stability limit (not a crash)
    double cpuPerPs = 0.0;               // production CPU s per simulated ps
    double cpuSeconds = 0.0;             // the whole run's (process_cpu_seconds)
    std::map<std::string, double> value; // "u", "u_conf", "p", "p_conf", "d", "tau_v", …
                                         // (g_peak: set by setPeakHeights)
    std::map<std::string, analysis::Estimate> withError; // those with the run's block error
    std::vector<double> g, gConf; // g(r) on the run's bins (gConf empty for SMD)
};

/// Reads DIR's summary.json and CSVs; `bodies`, ε (kJ/mol) for u; `rotating` whether tau_o
/// applies. A run that failed, or whose energy wandered (the SMD stability limit), is not ok.
ReplicaResult readReplica(const std::filesystem::path& dir, int bodies, double epsilon);

/// Where g_peak is read: the bins of g(r)'s highest peak, inclusive. Bins are uniform from r = 0
/// (bin k's centre at (k + ½)Δr), as analysis writes rdf.csv.
struct PeakWindow {
    std::size_t first = 0, last = 0;
};

/// The window of the mean of `curves` (each a g(r) on the same bins): around its highest bin
/// k*, the bins where g − 1 is at least half of g(k*) − 1, the peak's full width at half its
/// height above the ideal gas's (k* and its neighbours where g(k*) ≤ 1). nullopt without a
/// curve.
///
/// Why a window placed on the mean of every run, not each run's own peak: per run, g(r) of a
/// dilute state is a weak bump under bin noise (at ρ* 0.01, T* 10, N 512, 9 ps: 0.06 under ±0.12
/// per bin), so a run's highest bin is the largest of its noise, not the peak (1.31 where the
/// bump's top is 1.06), and it scattered 0.07 per run. A window makes g_peak a linear
/// functional of g(r), so the replicas' mean is unbiased, and its width averages the bins'
/// noise (0.031–0.036 per run on the same runs). Placed on the mean of all of the tradeoff's runs
/// (hundreds to thousands), the window's own noise is far below any one setting's, so it does
/// not favour the runs it is then read on.
std::optional<PeakWindow> peakWindow(const std::vector<const std::vector<double>*>& curves);

/// The mean of g over the window (NaN where g does not reach it).
double windowMean(const std::vector<double>& g, PeakWindow w);
/// Each ok replica's "g_peak" (and "g_peak_conf" where it has g_continuous): windowMean of its
/// curves over the window peakWindow places on every one of their own curves.
void setPeakHeights(const std::vector<std::vector<ReplicaResult>*>& sets);

/// ∫ c dt by the trapezoid rule over the samples (t in ps), up to c's first zero.
double integral(const std::vector<double>& t, const std::vector<double>& c);

/// A bias and what it was judged against: tolerance in the observable's units (for g: the RMS,
/// its decision taken on the square, the noise of both curves taken out).
struct ObservableBias {
    Observable observable = Observable::U;
    Estimator estimator = Estimator::Own;
    analysis::Estimate candidate, reference, bias; // bias: for g the RMS (sign: of its square)
    double tolerance = 0.0;
    analysis::Decision decision = analysis::Decision::Unresolved;
};

/// Per observable: the candidate's replicas against the reference's, decided at z
/// (analysis::decideBias). Where every replica carries its block error, each side's mean takes
/// the error its blocks give unless the replicas' scatter contradicts it
/// (analysis::pooledReplicaEstimate); otherwise the replica scatter alone. A relative tolerance
/// is a fraction of max(|reference mean|, scaleFloor). Empty when either side lacks two ok
/// replicas with the value.
std::optional<ObservableBias> scalarBias(Observable o, Estimator e,
                                         const std::vector<ReplicaResult>& candidate,
                                         const std::vector<ReplicaResult>& reference,
                                         analysis::Tolerance tolerance, double scaleFloor,
                                         double z);
std::optional<ObservableBias> curveBias(Estimator e, const std::vector<ReplicaResult>& candidate,
                                        const std::vector<ReplicaResult>& reference,
                                        double tolerance, double z);

/// The key of observable o under estimator e in ReplicaResult::value ("u", "u_conf", …).
std::string valueKey(Observable o, Estimator e);

/// The mean over bins of (ā − b̄)² − se²(ā) − se²(b̄) over the replicas' curves a and b (the
/// expected square of the noise taken out, so that it estimates the squared RMS of the true
/// difference), with its standard error from the same Gaussian bins treated as independent:
/// Var = Σ (4Δ²σ² + 2σ⁴)/M², σ² = se²(ā) + se²(b̄), Δ² by its unbiased estimate d² − σ².
/// Neighbouring bins of g(r) share frames, so the error is a guide rather than exact. dof: the
/// fewer replicas − 1.
analysis::Estimate squaredCurveDeviation(const std::vector<std::vector<double>>& a,
                                         const std::vector<std::vector<double>>& b);

} // namespace terrace::cli
