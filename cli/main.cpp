// terrace: event-driven (DMD) and standard (SMD) rigid-body dynamics on one scene, side by side.
// The commands (run, analyse, compare, design, sweep, tradeoff, export) and their options are
// described in cli/help_text.cpp, which `terrace --help` and `terrace COMMAND --help` print.
#include "analysis/compare.hpp"
#include "cli/analyse_command.hpp"
#include "cli/design_command.hpp"
#include "cli/engine_keys.hpp"
#include "cli/export_command.hpp"
#include "cli/help_text.hpp"
#include "cli/output_dir.hpp"
#include "cli/run_command.hpp"
#include "cli/run_driver.hpp"
#include "cli/run_process.hpp"
#include "cli/summary_line.hpp"
#include "cli/sweep_mpi.hpp"
#include "cli/tradeoff_command.hpp"
#include "core/huge_pages.hpp"
#include "core/measure.hpp"
#include "core/scene_json.hpp"
#include "core/suggest.hpp"
#include "core/xyz.hpp"
#include <algorithm>
#include <boost/program_options.hpp>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace po = boost::program_options;
using namespace terrace;

namespace {

void printRunSummary(const Scene& scene, const nlohmann::json& s,
                     const std::filesystem::path& out) {
    std::fputs(cli::runSummaryText(scene.name, s, out).c_str(), stdout);
}

/// `terrace COMMAND --help`.
int printHelp(const std::string& command) {
    std::fputs(cli::commandHelp(command).c_str(), stdout);
    return 0;
}

/// Parses `args` by `opts` and `pos`; an unknown option is refused naming the nearest known one.
po::variables_map parseOptions(const std::vector<std::string>& args,
                               const po::options_description& opts,
                               const po::positional_options_description& pos) {
    po::variables_map vm;
    try {
        po::store(po::command_line_parser(args).options(opts).positional(pos).run(), vm);
    } catch (const po::unknown_option& e) {
        std::vector<std::string> known;
        for (const auto& o : opts.options())
            if (!o->long_name().empty()) known.push_back("--" + o->long_name());
        const std::string near = nearestName(e.get_option_name(), known);
        throw po::error("unrecognised option '" + e.get_option_name() + "'" +
                        (near.empty() ? "" : "; did you mean " + near + "?"));
    }
    po::notify(vm);
    return vm;
}

/// The options of a command on a scene: [SCENE] [--set key.path=value]... [--help], and its own.
po::variables_map parseSceneCommand(const std::vector<std::string>& args,
                                    po::options_description& opts) {
    opts.add_options()("set", po::value<std::vector<std::string>>()->composing(), "key.path=value")(
        "help,h", "this help")("scene", po::value<std::string>(), "scene file");
    // Boost would take the next option as --set's value and then count the words after it as
    // extra scene files: name the --set that lacks its value instead.
    for (std::size_t i = 0; i < args.size(); ++i)
        if (args[i] == "--set" && (i + 1 == args.size() || args[i + 1].starts_with("-")))
            throw po::error("--set needs a key.path=value after it, got " +
                            (i + 1 == args.size() ? std::string("nothing")
                                                  : "the option '" + args[i + 1] + "'"));
    po::positional_options_description pos;
    pos.add("scene", 1);
    try {
        return parseOptions(args, opts, pos);
    } catch (const po::too_many_positional_options_error&) {
        throw po::error("takes one scene file; the words after the first one that are not options "
                        "or their values are more files");
    }
}

/// `ofSweep`: this run is one of a sweep's (cli::stopWithSweep), whose keys the sweep judged
/// (cli/sweep_plan.hpp): the sweep knows which of them are common to runs of both engines, the
/// run does not.
int runMain(const std::vector<std::string>& args, bool ofSweep) {
    po::options_description opts("run options");
    opts.add_options()("out", po::value<std::string>(), "output directory")(
        "overwrite", "replace the results of an earlier run in the output directory")(
        "continue", po::value<std::string>(), "continue the run in DIR from its restart file")(
        "quiet", "no progress output")("strict", "refuse --set keys the engine does not read");
    const auto vm = parseSceneCommand(args, opts);
    if (vm.count("help")) return printHelp("run");
    const bool quiet = vm.count("quiet") > 0;
    cli::RunTarget target; // before the scene: its checks may build the engine's terraces
    if (vm.count("continue")) {
        if (vm.count("scene") || vm.count("set") || vm.count("out") || vm.count("overwrite"))
            throw po::error("--continue DIR takes no scene, --set, --out or --overwrite: the run "
                            "goes on with the scene and directory it was started with");
        const std::filesystem::path dir = vm["continue"].as<std::string>();
        Scene scene;
        const auto outcome = cli::continueRun(dir, quiet, scene);
        printRunSummary(scene, outcome.summary, dir);
        return outcome.exitStatus;
    }
    cli::RunRequest req;
    if (vm.count("scene")) req.scenePath = vm["scene"].as<std::string>();
    if (vm.count("set")) req.overrides = vm["set"].as<std::vector<std::string>>();
    req.quiet = quiet;
    Scene scene = cli::resolveScene(req);
    if (!ofSweep) // the run shows its warnings as it starts, and records them
        for (std::string& w :
             cli::judgeOverrides(req.overrides, scene.engine,
                                 "the run's engine, " + scene.engine + ",", vm.count("strict") > 0))
            scene.warnings.push_back(std::move(w));
    target.dir = vm.count("out") ? std::filesystem::path(vm["out"].as<std::string>())
                                 : cli::defaultOutput(scene, req.overrides);
    target.mode = vm.count("overwrite") ? cli::OutputMode::Overwrite : cli::OutputMode::Fresh;
    target.quiet = quiet;
    const auto outcome = cli::runScene(scene, target);
    printRunSummary(scene, outcome.summary, target.dir);
    return outcome.exitStatus;
}

int analyseMain(const std::vector<std::string>& args) {
    if (std::find(args.begin(), args.end(), "--help") != args.end() ||
        std::find(args.begin(), args.end(), "-h") != args.end())
        return printHelp("analyse");
    if (args.size() != 1) throw po::error("analyse takes exactly one directory");
    return cli::analyseRun(args[0]);
}

int designMain(const std::vector<std::string>& args) {
    po::options_description opts("design options");
    opts.add_options()("profile", "U and its terraced value along r")(
        "strict", "refuse --set keys of the smd section");
    const auto vm = parseSceneCommand(args, opts);
    if (vm.count("help")) return printHelp("design");
    cli::DesignRequest req;
    if (vm.count("scene")) req.scenePath = vm["scene"].as<std::string>();
    if (vm.count("set")) req.overrides = vm["set"].as<std::vector<std::string>>();
    for (const std::string& w :
         cli::judgeOverrides(req.overrides, "dmd", "terrace design, which shows DMD's terraces,",
                             vm.count("strict") > 0))
        std::fprintf(stderr, "terrace: warning: %s\n", w.c_str());
    req.profile = vm.count("profile") > 0;
    return cli::printDesign(req);
}

int sweepMain(const std::vector<std::string>& args) {
    po::options_description opts("sweep options");
    opts.add_options()("out", po::value<std::string>(), "output directory")(
        "jobs,j", po::value<int>()->default_value(1), "runs at once in this process")(
        "retry-failed", "run again the runs whose failure is recorded")(
        "quiet", "no progress output")("sweep", po::value<std::string>(), "sweep file")(
        "set", po::value<std::vector<std::string>>()->composing(), "key.path=value")(
        "strict", "refuse keys the runs' engines do not read")("help,h", "this help");
    po::positional_options_description pos;
    pos.add("sweep", 1);
    const auto vm = parseOptions(args, opts, pos);
    if (vm.count("help")) return printHelp("sweep");
    if (!vm.count("sweep")) throw po::error("sweep takes a sweep file (SWEEP.json)");
    const std::filesystem::path file = vm["sweep"].as<std::string>();
    const auto sets =
        vm.count("set") ? vm["set"].as<std::vector<std::string>>() : std::vector<std::string>{};
    cli::SweepOptions options;
    options.out = vm.count("out")
                      ? std::filesystem::path(vm["out"].as<std::string>())
                      : std::filesystem::path("out") /
                            cli::nameWithOverrides(cli::sanitisedName(file.stem().string()), sets);
    options.jobs = vm["jobs"].as<int>();
    options.quiet = vm.count("quiet") > 0;
    options.retryFailed = vm.count("retry-failed") > 0;
    options.strict = vm.count("strict") > 0;
    if (options.jobs < 0 || (options.jobs == 0 && !cli::launchedByMpi()))
        throw po::error("-j must be at least 1 (0 only under mpirun: rank 0 then only hands out)");
    if (cli::launchedByMpi()) return cli::mpiSweep(file, sets, options);
    cli::SweepPlan plan;
    try {
        plan = cli::loadSweep(file, sets);
        if (options.strict) cli::refuseIgnoredKeys(plan);
        for (const std::string& note : plan.ignoredKeys)
            std::fprintf(stderr, "terrace: warning: %s\n", cli::asWarning(note).c_str());
    } catch (const SceneError& e) { // a bad sweep file: nothing has run
        std::fprintf(stderr, "terrace: %s\n", e.what());
        return 2;
    }
    try {
        return cli::runSweep(plan, options);
    } catch (const std::exception& e) { // the sweep itself, not a run: another sweep holds DIR,
        std::fprintf(stderr, "terrace: %s\n", e.what()); // the table cannot be written, ...
        return 3;
    }
}

int tradeoffMain(const std::vector<std::string>& args) {
    po::options_description opts("tradeoff options");
    opts.add_options()("out", po::value<std::string>(), "output directory")(
        "jobs,j", po::value<int>()->default_value(1), "runs at once")(
        "tolerance", po::value<std::vector<std::string>>()->composing(),
        "OBS=VALUE[%]")("bias-n", po::value<int>()->default_value(0), "bodies of the bias runs")(
        "max-replicas", po::value<int>()->default_value(32), "replicas per setting at most")(
        "cost-pairs", po::value<int>()->default_value(5), "alternated cost runs per engine")(
        "budget-cpu-hours", po::value<double>()->default_value(8.0), "CPU budget")(
        "dV", po::value<std::string>()->default_value("1,0.5,0.25,0.125"), "DMD ladder, kT")(
        "designs", po::value<std::string>()->default_value("uniform,optimal"), "DMD ladders")(
        "schemes", po::value<std::string>()->default_value("verlet,omelyan,yoshida4"),
        "SMD ladders")("observables", po::value<std::string>(), "u,p,d,g,g_peak,tau_v,tau_o")(
        "frontier", "resolve both engines' cheapest settings")("quiet", "no progress output")(
        "scene", po::value<std::string>(),
        "scene file")("set", po::value<std::vector<std::string>>()->composing(),
                      "key.path=value")("help,h", "this help");
    po::positional_options_description pos;
    pos.add("scene", 1);
    const auto vm = parseOptions(args, opts, pos);
    if (vm.count("help")) return printHelp("tradeoff");
    if (cli::launchedByMpi())
        throw po::error("tradeoff hands out its runs locally (-j N) and does not run under an MPI "
                        "launcher: every rank would run the whole tradeoff");
    cli::TradeoffOptions o;
    if (vm.count("scene")) o.scenePath = vm["scene"].as<std::string>();
    if (vm.count("set")) o.sets = vm["set"].as<std::vector<std::string>>();
    o.jobs = vm["jobs"].as<int>();
    o.biasN = vm["bias-n"].as<int>();
    o.maxReplicas = vm["max-replicas"].as<int>();
    o.costPairs = vm["cost-pairs"].as<int>();
    o.budgetCpuHours = vm["budget-cpu-hours"].as<double>();
    o.quiet = vm.count("quiet") > 0;
    o.frontier = vm.count("frontier") > 0;
    if (o.jobs < 1) throw po::error("-j must be at least 1");
    if (o.biasN < 0 || o.biasN == 1) throw po::error("--bias-n must be 0 (the scene's) or >= 2");
    if (o.maxReplicas < 2) throw po::error("--max-replicas must be at least 2");
    if (o.costPairs < 1) throw po::error("--cost-pairs must be at least 1");
    if (!(o.budgetCpuHours > 0.0)) throw po::error("--budget-cpu-hours must be > 0");
    o.dVs.clear();
    for (const std::string& item : cli::commaList(vm["dV"].as<std::string>())) {
        std::size_t used = 0;
        double x = 0.0;
        try {
            x = std::stod(item, &used);
        } catch (const std::exception&) {
        }
        if (used == 0 || used != item.size() || !(x > 0.0) || !std::isfinite(x))
            throw po::error("--dV takes a comma-separated list of positive numbers (kT), got '" +
                            item + "'");
        o.dVs.push_back(x);
    }
    if (o.dVs.size() < 2) throw po::error("--dV needs at least two values for a ladder");
    const auto split = [](const std::string& list, const std::vector<std::string>& valid,
                          const char* option) {
        const std::vector<std::string> items = cli::commaList(list);
        for (const std::string& item : items)
            if (std::find(valid.begin(), valid.end(), item) == valid.end())
                throw po::error(std::string(option) + ": '" + item + "' is none of the choices");
        return items;
    };
    o.designs = split(vm["designs"].as<std::string>(), {"uniform", "optimal"}, "--designs");
    o.schemes =
        split(vm["schemes"].as<std::string>(), {"verlet", "omelyan", "yoshida4"}, "--schemes");
    try {
        if (vm.count("observables"))
            o.observables = cli::parseObservables(vm["observables"].as<std::string>());
        if (vm.count("tolerance"))
            for (const auto& text : vm["tolerance"].as<std::vector<std::string>>())
                o.tolerances.push_back(cli::parseTolerance(text));
        const Scene scene = o.scenePath.empty()
                                ? sceneFromJson(nlohmann::json::object(), "<built-in>", o.sets)
                                : loadScene(o.scenePath.string(), o.sets);
        o.out =
            vm.count("out")
                ? std::filesystem::path(vm["out"].as<std::string>())
                : std::filesystem::path("out") /
                      cli::nameWithOverrides(cli::sanitisedName("tradeoff-" + scene.name), o.sets);
    } catch (const SceneError& e) {
        std::fprintf(stderr, "terrace: %s\n", e.what());
        return 2;
    }
    return cli::runTradeoff(o);
}

int exportMain(const std::vector<std::string>& args) {
    po::options_description opts("export options");
    opts.add_options()("format", po::value<std::string>(),
                       "lammps")("dir", po::value<std::string>(), "output directory");
    // The scene is the second word here: parseSceneCommand's positional list would take the
    // format for it.
    opts.add_options()("set", po::value<std::vector<std::string>>()->composing(), "key.path=value")(
        "help,h", "this help")("scene", po::value<std::string>(), "scene file");
    for (std::size_t i = 0; i < args.size(); ++i) // as parseSceneCommand's
        if (args[i] == "--set" && (i + 1 == args.size() || args[i + 1].starts_with("-")))
            throw po::error("--set needs a key.path=value after it, got " +
                            (i + 1 == args.size() ? std::string("nothing")
                                                  : "the option '" + args[i + 1] + "'"));
    po::positional_options_description pos;
    pos.add("format", 1).add("scene", 1).add("dir", 1);
    po::variables_map vm;
    try {
        vm = parseOptions(args, opts, pos);
    } catch (const po::too_many_positional_options_error&) {
        throw po::error("takes a format, a scene file and a directory, no more");
    }
    if (vm.count("help")) return printHelp("export");
    if (!vm.count("format") || !vm.count("scene") || !vm.count("dir"))
        throw po::error("takes a format, a scene file and a directory: terrace export lammps "
                        "SCENE.json DIR");
    cli::ExportRequest req;
    req.format = vm["format"].as<std::string>();
    if (req.format != "lammps")
        throw po::error("no format '" + req.format + "' (the one there is: lammps)");
    req.scenePath = vm["scene"].as<std::string>();
    req.dir = vm["dir"].as<std::string>();
    if (vm.count("set")) req.overrides = vm["set"].as<std::vector<std::string>>();
    return cli::exportScene(req);
}

int compareMain(const std::vector<std::string>& args) {
    po::options_description opts("compare options");
    opts.add_options()("tol-sigma", po::value<double>()->default_value(3.0), "tolerance in sigma")(
        "column", po::value<std::string>()->default_value(""), "value column")(
        "files", po::value<std::vector<std::string>>(), "A.csv B.csv")("help,h", "this help");
    po::positional_options_description pos;
    pos.add("files", 2);
    const auto vm = parseOptions(args, opts, pos);
    if (vm.count("help")) return printHelp("compare");
    if (!vm.count("files") || vm["files"].as<std::vector<std::string>>().size() != 2)
        throw po::error("compare takes two CSV files");
    const auto files = vm["files"].as<std::vector<std::string>>();
    const double tolSigma = vm["tol-sigma"].as<double>();
    if (!(std::isfinite(tolSigma) && tolSigma > 0.0))
        throw po::error("--tol-sigma must be a finite number > 0 (a tolerance in standard "
                        "deviations, e.g. 3), got " +
                        showNumber(tolSigma));
    const auto c =
        analysis::compareCsv(files[0], files[1], tolSigma, vm["column"].as<std::string>());
    std::printf("%s\n", c.verdict.c_str());
    return c.agree ? 0 : 1;
}

} // namespace

/// What reaches standard output is part of the result: a write that failed there is an error too.
int checkedStdout(int status) {
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
        std::fprintf(stderr, "terrace: cannot write to standard output: %s\n",
                     std::strerror(errno));
        return status == 0 ? 1 : status;
    }
    return status;
}

int main(int argc, char** argv) {
#if defined(__GLIBC__)
    // Blocks of 1 MiB and more are mapped apart, and so return to the system when freed. glibc's
    // own threshold rises to 32 MiB once such a block is freed (a restart point drops the
    // engine), after which the rebuilt engine's arrays come from the heap, where what is freed
    // around them stays resident: DMD at 262 144 bodies with restart points peaked at 1.17 KB
    // per body so, 1.003 with the threshold held (0.98 without restart points).
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
#endif
    const bool ofSweep = terrace::cli::stopWithSweep();
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "--help" || args[0] == "-h" ||
        (args[0] == "help" && args.size() == 1)) {
        std::fputs(cli::generalHelp().c_str(), args.empty() ? stderr : stdout);
        return args.empty() ? 2 : 0;
    }
    if (args[0] == "help") { // terrace help COMMAND
        const std::string help = cli::commandHelp(args[1]);
        if (help.empty()) {
            std::fprintf(stderr,
                         "terrace: help: no command '%s' (the commands: run, analyse, "
                         "compare, design, sweep, tradeoff, export)\n",
                         args[1].c_str());
            return 2;
        }
        return checkedStdout(printHelp(args[1]));
    }
    const std::string command = args[0];
    args.erase(args.begin());
    try {
        hugePagesWanted(); // a misspelt TERRACE_HUGE_PAGES is an error before anything runs
        measureSwitches(); // and so is a misspelt TERRACE_MEASURE
        if (command == "run") return checkedStdout(runMain(args, ofSweep));
        if (command == "analyse" || command == "analyze") return checkedStdout(analyseMain(args));
        if (command == "compare") return checkedStdout(compareMain(args));
        if (command == "design") return checkedStdout(designMain(args));
        if (command == "sweep") return checkedStdout(sweepMain(args));
        if (command == "tradeoff") return checkedStdout(tradeoffMain(args));
        if (command == "export") return checkedStdout(exportMain(args));
        const std::string near = nearestName(command, cli::commandNames());
        std::fprintf(stderr, "terrace: unknown command '%s'%s (try terrace --help)\n",
                     command.c_str(), near.empty() ? "" : ("; did you mean " + near + "?").c_str());
        return 2;
    } catch (const po::error& e) {
        std::fprintf(stderr, "terrace %s: %s (try terrace %s --help)\n", command.c_str(), e.what(),
                     command.c_str());
        return 2;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "terrace: out of memory (the system refused an allocation)\n");
        return 1;
    } catch (const std::filesystem::filesystem_error& e) {
        // The library's text repeats the operation in its own words; name the path and cause.
        std::fprintf(stderr, "terrace: cannot access %s: %s\n", e.path1().c_str(),
                     e.code().message().c_str());
        return 1;
    } catch (const nlohmann::json::exception& e) {
        // Files are read and checked where they are named; this is a fault of terrace's own.
        std::fprintf(stderr, "terrace: internal error (JSON): %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "terrace: %s\n", e.what());
        return 1;
    }
}
