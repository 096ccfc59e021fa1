// paper_tools: the numeric steps of the paper's figures and tables that a shell script cannot do
// (Makefile.paper calls it; experiments/README.md lists the subcommands).
//   potential-map OUT.csv                 fig1 data (potential_map.hpp)
//   search-trace DIR [dV_kT]              fig2 data (search_trace.hpp)
//   mean OUT.csv IN.csv IN.csv...         replica mean and standard error (replicas.hpp)
//   error REF.csv CURVE.csv COLUMN [XMAX] RMS difference and its noise floor (replicas.hpp)
//   summary-header                        header of summary rows
//   summary LABEL DIR...                  one table row over replica runs (summaries.hpp)
//   get FILE.json KEY...                  values of dotted keys, comma separated
//   stats X...                            replica mean and standard error (convergence.hpp)
//   replica-stats KEY SCALE DIR...        the same of a summary key over replica runs, SCALE
//                                         total | per-body | abs-per-nkt (summaries.hpp)
//   configurational DIR                   the continuous model's U and P on DIR's trajectory
//                                         (configurational.hpp), as JSON
//   order IN.csv OUT.csv                  orders of convergence of a table (convergence.hpp)
//   equal-accuracy FRONTS.csv SET         equal-accuracy efficiency of each DMD design against
//                                         SMD at SET's errors (equal_accuracy.hpp)
#include "analysis/csv.hpp"
#include "experiments/tools/configurational.hpp"
#include "experiments/tools/convergence.hpp"
#include "experiments/tools/equal_accuracy.hpp"
#include "experiments/tools/potential_map.hpp"
#include "experiments/tools/replicas.hpp"
#include "experiments/tools/search_trace.hpp"
#include "experiments/tools/summaries.hpp"
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

namespace {

int usage() {
    std::cerr << "usage: paper_tools potential-map OUT.csv\n"
                 "       paper_tools search-trace DIR [dV_kT]\n"
                 "       paper_tools mean OUT.csv IN.csv IN.csv...\n"
                 "       paper_tools error REF.csv CURVE.csv COLUMN [XMAX]\n"
                 "       paper_tools summary-header\n"
                 "       paper_tools summary LABEL DIR...\n"
                 "       paper_tools get FILE.json KEY...\n"
                 "       paper_tools stats X...\n"
                 "       paper_tools replica-stats KEY total|per-body|abs-per-nkt DIR...\n"
                 "       paper_tools configurational DIR\n"
                 "       paper_tools order IN.csv OUT.csv\n"
                 "       paper_tools equal-accuracy FRONTS.csv SET\n";
    return 2;
}

int run(const std::vector<std::string>& a) {
    using namespace terrace;
    const std::string& cmd = a[0];
    if (cmd == "potential-map" && a.size() == 2) {
        experiments::writePotentialMap(a[1]);
    } else if (cmd == "search-trace" && (a.size() == 2 || a.size() == 3)) {
        experiments::writeSearchTrace(a[1], a.size() == 3 ? std::stod(a[2]) : 0.5);
    } else if (cmd == "mean" && a.size() >= 4) {
        std::vector<analysis::CsvTable> replicas;
        for (std::size_t k = 2; k < a.size(); ++k)
            replicas.push_back(analysis::readCsv(a[k]));
        analysis::writeCsv(a[1], experiments::replicaMean(replicas));
    } else if (cmd == "error" && (a.size() == 4 || a.size() == 5)) {
        const auto ref = analysis::readCsv(a[1]), curve = analysis::readCsv(a[2]);
        const double xMax = a.size() == 5 ? std::stod(a[4]) : 0.0;
        std::printf("%.6g %.6g\n", experiments::rmsDifference(ref, curve, a[3], xMax),
                    experiments::rmsNoise(ref, curve, a[3], xMax));
    } else if (cmd == "summary-header" && a.size() == 1) {
        std::cout << experiments::summaryHeader() << '\n';
    } else if (cmd == "summary" && a.size() >= 3) {
        std::cout << experiments::summaryRow(a[1], {a.begin() + 2, a.end()}) << '\n';
    } else if (cmd == "get" && a.size() >= 3) {
        std::cout << experiments::jsonValues(a[1], {a.begin() + 2, a.end()}) << '\n';
    } else if (cmd == "stats" && a.size() >= 2) {
        std::vector<double> x;
        for (std::size_t k = 1; k < a.size(); ++k)
            x.push_back(std::stod(a[k]));
        const auto m = experiments::replicaStatistics(x);
        std::printf("%.10g %.6g\n", m.mean, m.error);
    } else if (cmd == "replica-stats" && a.size() >= 4) {
        // One process for a set's replicas: the scripts' loops over them spent more time
        // starting programs than reading summaries.
        const auto scale = experiments::summaryScale(a[2]);
        std::vector<double> x;
        for (std::size_t k = 3; k < a.size(); ++k)
            x.push_back(experiments::replicaValue(a[k], a[1], scale));
        const auto m = experiments::replicaStatistics(x);
        std::printf("%.10g %.6g\n", m.mean, m.error);
    } else if (cmd == "configurational" && a.size() == 2) {
        const auto c = experiments::configurational(a[1]);
        std::printf("{\"frames\": %d, \"potential_energy_per_body\": %.12g, "
                    "\"pressure_reduced\": %.12g}\n",
                    c.frames, c.potentialPerBody, c.pressureReduced);
    } else if (cmd == "order" && a.size() == 3) {
        std::cout << "quantity,order,order_err,log_prefactor,chi2_per_dof,points\n";
        for (const auto& row : experiments::fitOrders(analysis::readCsv(a[1]), a[2]))
            std::cout << row << '\n';
    } else if (cmd == "equal-accuracy" && a.size() == 3) {
        std::cout << "design,quantity,target,target_error,resolved,smd_cost,design_cost,efficiency,"
                     "bound,smd_via\n";
        for (const auto& row : experiments::equalAccuracy(a[1], a[2]))
            std::cout << row << '\n';
    } else {
        return usage();
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 2) return usage();
    try {
        return run(std::vector<std::string>(argv + 1, argv + argc));
    } catch (const std::exception& e) {
        std::cerr << "paper_tools " << argv[1] << ": " << e.what() << '\n';
        return 1;
    }
}
