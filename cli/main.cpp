// terrace: event-driven (DMD) and standard (SMD) rigid-body dynamics on one scene, side by side.
//   terrace run [SCENE] [--set key.path=value]... [--out DIR] [--quiet]
//   terrace analyse DIR
//   terrace compare A.csv B.csv [--tol-sigma X] [--column NAME]
#include "analysis/compare.hpp"
#include "analysis/correlations.hpp"
#include "cli/run_command.hpp"
#include "core/xyz.hpp"
#include <boost/program_options.hpp>
#include <cstdio>
#include <iostream>

namespace po = boost::program_options;
using namespace terrace;

namespace {

const char* usage = R"(terrace — event-driven dynamics of rigid bodies on terraced potentials (DMD)
and standard rigid-body MD on the continuous potential (SMD), compared on one scene.

Usage:
  terrace run [SCENE.json] [--set key.path=value]... [--out DIR] [--quiet]
      Run a scene (default: the built-in dense rods, N 512, rho* 0.5, T* 1.4).
      --set overrides any scene key by its dotted path, e.g. --set engine=smd
      --set dmd.dV=0.5 --set run.time_ps=5. Writes DIR/summary.json, scene.json,
      initial.xyz, rdf.csv, vacf.csv, oacf.csv, msd.csv and, if asked for,
      trajectory.xyz (default DIR: out/<scene name>-<engine>).
  terrace analyse DIR
      Recompute the correlation CSVs of DIR from DIR/trajectory.xyz.
  terrace compare A.csv B.csv [--tol-sigma X] [--column NAME]
      Regression check of two correlation curves; exit status 1 when they disagree.
  terrace --help

Units: lengths in Angstrom, masses g/mol, energies kJ/mol, times fs/ps on input and output.
)";

int runMain(const std::vector<std::string>& args) {
    po::options_description opts("run options");
    opts.add_options()("set", po::value<std::vector<std::string>>()->composing(),
                       "key.path=value")("out", po::value<std::string>(), "output directory")(
        "quiet", "no progress output")("scene", po::value<std::string>(), "scene file");
    po::positional_options_description pos;
    pos.add("scene", 1);
    po::variables_map vm;
    po::store(po::command_line_parser(args).options(opts).positional(pos).run(), vm);
    po::notify(vm);
    cli::RunRequest req;
    if (vm.count("scene")) req.scenePath = vm["scene"].as<std::string>();
    if (vm.count("set")) req.overrides = vm["set"].as<std::vector<std::string>>();
    req.quiet = vm.count("quiet") > 0;
    const Scene scene = cli::resolveScene(req);
    const std::filesystem::path out =
        vm.count("out") ? std::filesystem::path(vm["out"].as<std::string>())
                        : std::filesystem::path("out") / (scene.name + "-" + scene.engine);
    const auto s = cli::runScene(scene, out, req.quiet);
    std::printf("%s: %s, N = %d, %.3f ps simulated in %.2f CPU s (%.3f CPU s/ps)\n",
                scene.name.c_str(), scene.engine.c_str(), s["n_bodies"].get<int>(),
                s["simulated_ps"].get<double>(), s["cpu_seconds"].get<double>(),
                s["cpu_seconds_per_ps"].get<double>());
    std::printf("  T = %.1f K (target %.1f K), <U> = %.4f kJ/mol, energy rel. fluctuation %.3g, "
                "drift %.3g kJ/mol/ps\n",
                s["temperature_K"].get<double>(), s["temperature_target_K"].get<double>(),
                s["potential_energy_mean"].get<double>(), s["energy"]["rel_fluct"].get<double>(),
                s["energy"]["drift_per_ps"].get<double>());
    if (s.contains("collisions_per_ps"))
        std::printf("  %.4g collisions/ps, %.4g events per CPU s\n",
                    s["collisions_per_ps"].get<double>(), s.value("events_per_cpu_second", 0.0));
    std::printf("  output in %s/\n", out.c_str());
    return s.value("interrupted", false) ? 130 : 0;
}

int analyseMain(const std::vector<std::string>& args) {
    if (args.size() != 1) throw po::error("analyse takes exactly one directory");
    const std::filesystem::path dir = args[0];
    const auto frames = readTrajectory((dir / "trajectory.xyz").string());
    if (frames.size() < 4)
        throw TrajectoryError((dir / "trajectory.xyz").string() +
                              ": fewer than 4 frames, too few to correlate");
    const auto summary = analysis::writeCorrelations(frames, dir);
    std::printf("%zu frames analysed; wrote the correlation CSVs in %s/\n", frames.size(),
                dir.c_str());
    std::printf("%s\n", summary.dump().c_str());
    return 0;
}

int compareMain(const std::vector<std::string>& args) {
    po::options_description opts("compare options");
    opts.add_options()("tol-sigma", po::value<double>()->default_value(3.0), "tolerance in sigma")(
        "column", po::value<std::string>()->default_value(""),
        "value column")("files", po::value<std::vector<std::string>>(), "A.csv B.csv");
    po::positional_options_description pos;
    pos.add("files", 2);
    po::variables_map vm;
    po::store(po::command_line_parser(args).options(opts).positional(pos).run(), vm);
    po::notify(vm);
    if (!vm.count("files") || vm["files"].as<std::vector<std::string>>().size() != 2)
        throw po::error("compare takes two CSV files");
    const auto files = vm["files"].as<std::vector<std::string>>();
    const auto c = analysis::compareCsv(files[0], files[1], vm["tol-sigma"].as<double>(),
                                        vm["column"].as<std::string>());
    std::printf("%s\n", c.verdict.c_str());
    return c.agree ? 0 : 1;
}

} // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        std::fputs(usage, args.empty() ? stderr : stdout);
        return args.empty() ? 2 : 0;
    }
    const std::string command = args[0];
    args.erase(args.begin());
    try {
        if (command == "run") return runMain(args);
        if (command == "analyse" || command == "analyze") return analyseMain(args);
        if (command == "compare") return compareMain(args);
        std::fprintf(stderr, "terrace: unknown command '%s' (try terrace --help)\n",
                     command.c_str());
        return 2;
    } catch (const po::error& e) {
        std::fprintf(stderr, "terrace %s: %s (try terrace --help)\n", command.c_str(), e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "terrace: %s\n", e.what());
        return 1;
    }
}
