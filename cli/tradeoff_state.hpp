#pragma once
// The state of one `terrace tradeoff` search (cli/tradeoff_command.hpp): the reference and the
// candidates' ladders, each setting with the replicas asked for, what they measured and what was
// decided of it. The runs behind it are made and read by cli/tradeoff_runs.hpp, the search's
// steps are cli/tradeoff_search.hpp, its record cli/tradeoff_report.hpp, and the verdict drawn
// from it cli/tradeoff_choice.hpp, cli/tradeoff_cost.hpp and cli/tradeoff_verdict.hpp.
#include "analysis/tradeoff_stats.hpp"
#include "cli/tradeoff_measure.hpp"
#include "cli/tradeoff_plan.hpp"
#include "core/scene.hpp"
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace terrace::cli {

/// A decision as tradeoff.json and tradeoff.csv write it.
inline const char* decisionName(analysis::Decision d) {
    using analysis::Decision;
    return d == Decision::Within ? "within" : d == Decision::Outside ? "outside" : "unresolved";
}

/// A setting with its replicas and what they say.
struct Rung {
    Setting setting;
    int target = 0; // replicas asked for
    std::vector<ReplicaResult> replicas;
    std::vector<ObservableBias> biases;
    std::vector<ObservableBias> alternatives; // DMD: the estimator not chosen, for comparison
    analysis::Decision decision = analysis::Decision::Unresolved;
    std::string failure;          // the stability limit, or why a rung cannot be judged
    bool beyondStability = false; // a replica met SMD's stability limit (failure says how)

    int ok() const {
        return int(std::count_if(replicas.begin(), replicas.end(),
                                 [](const ReplicaResult& r) { return r.ok; }));
    }
    double cost() const { // mean production CPU s per ps of the ok replicas
        double sum = 0.0;
        int n = 0;
        for (const auto& r : replicas)
            if (r.ok && std::isfinite(r.cpuPerPs)) sum += r.cpuPerPs, ++n;
        return n ? sum / n : std::numeric_limits<double>::quiet_NaN();
    }
};

/// The directory name of a setting's k-th replica under OUT/runs.
inline std::string replicaName(const Setting& s, int k) {
    return s.label() + "_r" + std::to_string(k);
}

/// Whether DMD has a configurational estimator of `o` beside its own (docs/TRADEOFF.md).
inline bool hasConfigurational(Observable o) {
    return o == Observable::U || o == Observable::P || o == Observable::G || o == Observable::GPeak;
}

/// One search: what it was asked (options, scene, observables and tolerances), the reference and
/// the ladders with what their runs measured, DMD's estimator per observable, the replica counts
/// it may look at (schedule) and at what z, the CPU its runs spent, and the notes for the report.
struct Tradeoff {
    TradeoffOptions options;
    Scene scene;         // the user's, at its N: the cost runs
    int biasBodies = 0;  // bodies of the bias runs
    std::string biasSet; // the --set that gives the bias runs their N ("": the scene's)
    std::vector<Observable> observables;
    std::map<Observable, analysis::Tolerance> tolerance;
    Rung reference;
    std::vector<std::vector<Rung>> ladders;
    std::map<Observable, Estimator> dmdEstimator;
    std::vector<int> schedule;
    double z = 2.0;
    double cpuSpent = 0.0;
    std::vector<std::string> notes;
    std::set<std::string> interpolatedLadders;

    std::filesystem::path runs() const { return options.out / "runs"; }

    /// The least magnitude a relative tolerance of o is a fraction of (relativeScaleFloor).
    double scaleFloor(Observable o) const {
        return relativeScaleFloor(o, scene.state.density, scene.state.temperature);
    }
};

} // namespace terrace::cli
