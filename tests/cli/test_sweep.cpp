// Sweep plans and tables (cli/sweep_plan.hpp, cli/sweep_table.hpp): the runs a sweep file names,
// in order and with their directory names; the one-line errors of bad sweep files; what a run
// directory found from before is taken for; the rows of sweep.csv.
#include "cli/sweep_plan.hpp"
#include "cli/sweep_table.hpp"
#include "core/output_file.hpp"
#include <filesystem>
#include <gtest/gtest.h>
#include <unistd.h>

namespace test_sweep {

using namespace terrace;
using namespace terrace::cli;
using nlohmann::json;

namespace {

SweepPlan plan(const std::string& text, const std::vector<std::string>& sets = {}) {
    return sweepFromJson(text, "s.json", ".", sets);
}

std::vector<std::string> names(const SweepPlan& p) {
    std::vector<std::string> n;
    for (const auto& r : p.runs)
        n.push_back(r.name);
    return n;
}

/// The error a bad sweep gives: one line, naming what it must.
std::string sweepError(const std::string& text) {
    try {
        plan(text);
    } catch (const SceneError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        return what;
    }
    ADD_FAILURE() << "no error for " << text;
    return "";
}

struct TempDir {
    std::filesystem::path path;
    TempDir() {
        char name[] = "/tmp/terrace-sweep-XXXXXX";
        path = mkdtemp(name);
    }
    ~TempDir() { std::filesystem::remove_all(path); }
};

} // namespace

TEST(SweepPlan, ProductOfAxesFirstSlowestSeedsInnermost) {
    const auto p = plan(R"({"axes": [{"state.density": [0.1, 0.3]}, {"engine": ["dmd", "smd"]}],
                            "seeds": [1, 2]})");
    const std::vector<std::string> expected = {
        "density-0.1_engine-dmd_seed-1", "density-0.1_engine-dmd_seed-2",
        "density-0.1_engine-smd_seed-1", "density-0.1_engine-smd_seed-2",
        "density-0.3_engine-dmd_seed-1", "density-0.3_engine-dmd_seed-2",
        "density-0.3_engine-smd_seed-1", "density-0.3_engine-smd_seed-2"};
    EXPECT_EQ(names(p), expected);
    EXPECT_EQ(p.axisKeys, (std::vector<std::string>{"state.density", "engine", "seed"}));
    // Each run's scene is the base scene with its overrides, resolved.
    EXPECT_DOUBLE_EQ(p.runs[5].scene.state.density, 0.3);
    EXPECT_EQ(p.runs[5].scene.engine, "dmd");
    EXPECT_EQ(p.runs[5].scene.seed, 2u);
    EXPECT_EQ(p.runs[7].scene.engine, "smd");
}

TEST(SweepPlan, ZippedKeysCasesLabelsAndCommonSets) {
    const auto p = plan(R"({"set": {"state.n": 64},
        "axes": [{"state.density": [0.1, 0.5], "state.temperature": [10, 1.4]},
                 {"cases": [{"engine": "dmd", "dmd.dV": 0.5}, {"engine": "smd", "smd.dt_fs": 1.8}]},
                 {"dmd.terraces": [{"levels": "optimal"}, {"levels": "energy", "values": "virial"}],
                  "labels": ["optimal", "virial"]}]})",
                        {"run.time_ps=0.9"});
    ASSERT_EQ(p.runs.size(), 8u);
    EXPECT_EQ(p.runs[0].name, "density-0.1_temperature-10_engine-dmd_dV-0.5_optimal");
    EXPECT_EQ(p.runs[7].name, "density-0.5_temperature-1.4_engine-smd_dt_fs-1.8_virial");
    for (const auto& r : p.runs) {
        EXPECT_EQ(r.scene.state.n, 64);
        EXPECT_DOUBLE_EQ(r.scene.run.time_ps, 0.9);
    }
    EXPECT_DOUBLE_EQ(p.runs[7].scene.state.temperature, 1.4);
    EXPECT_DOUBLE_EQ(p.runs[7].scene.smd["dt_fs"].get<double>(), 1.8);
    // A --set wins over the file's "set" (tradeoff's frames every sample give way to a user's),
    // and an axis over both.
    const auto q = plan(R"({"set": {"analysis.rdf_every": 1, "state.n": 64},
        "axes": [{"state.n": [27]}]})",
                        {"analysis.rdf_every=5", "state.n=125"});
    EXPECT_EQ(q.runs.at(0).scene.analysis.rdf_every, 5);
    EXPECT_EQ(q.runs.at(0).scene.state.n, 27);
    // The common overrides are not columns; every key an axis sets is.
    EXPECT_EQ(p.axisKeys, (std::vector<std::string>{"state.density", "state.temperature", "engine",
                                                    "dmd.dV", "smd.dt_fs", "dmd.terraces"}));
}

TEST(SweepPlan, KeysSharingALastComponentKeepTheirWholeName) {
    const auto p = plan(R"({"axes": [{"smd.skin": [0.3]}, {"dmd.horizon_fs": [4]},
                                     {"cases": [{"smd.dt_fs": 1}, {"dmd.dV": 1}]}]})");
    EXPECT_EQ(names(p), (std::vector<std::string>{"skin-0.3_horizon_fs-4_dt_fs-1",
                                                  "skin-0.3_horizon_fs-4_dV-1"}));
    const auto q = plan(R"({"axes": [{"body.kind": ["linear"]}, {"potential.kind": ["rod-lj"]}]})");
    EXPECT_EQ(names(q), (std::vector<std::string>{"body.kind-linear_potential.kind-rod-lj"}));
}

TEST(SweepPlan, NoAxesIsOneRunOfTheBaseScene) {
    const auto p = plan(R"({})");
    ASSERT_EQ(p.runs.size(), 1u);
    EXPECT_EQ(p.runs[0].name, "run");
    EXPECT_TRUE(p.runs[0].overrides.empty());
}

TEST(SweepPlan, OverrideArgumentsAreJsonAsTerraceRunTakesThem) {
    EXPECT_EQ(overrideArgument({"engine", "smd"}), R"(engine="smd")");
    EXPECT_EQ(overrideArgument({"dmd.dV", 0.25}), "dmd.dV=0.25");
    EXPECT_EQ(valueText(json("smd")), "smd");
    EXPECT_EQ(valueText(json::parse(R"({"levels":"optimal"})")), R"({"levels":"optimal"})");
}

TEST(SweepPlan, BadSweepFilesFailInOneLineNamingTheProblem) {
    EXPECT_NE(sweepError("{ not json").find("not valid JSON"), std::string::npos);
    EXPECT_NE(sweepError(R"({"axis": []})").find("axis: unknown key; did you mean axes?"),
              std::string::npos);
    EXPECT_NE(sweepError(R"({"axes": [{"dmd.dV": [1, 2], "smd.dt_fs": [1]}]})")
                  .find("axes[0].smd.dt_fs: zipped keys need lists of one length"),
              std::string::npos);
    EXPECT_NE(sweepError(R"({"axes": [{"dmd.dV": []}]})").find("non-empty list"),
              std::string::npos);
    EXPECT_NE(sweepError(R"({"seeds": [1.5]})").find("seeds: must be integers"), std::string::npos);
    EXPECT_NE(sweepError(R"({"axes": [{"dmd.dV": [1, 1]}]})").find("both named 'dV-1'"),
              std::string::npos);
    EXPECT_NE(
        sweepError(R"({"axes": [{"dmd.dV": [1, 2], "labels": ["a"]}]})").find("axes[0].labels"),
        std::string::npos);
    EXPECT_NE(sweepError(R"({"axes": [{"cases": [{"engine": "dmd"}], "dmd.dV": [1]}]})")
                  .find("takes no other key"),
              std::string::npos);
    // A scene key that does not exist, or a value the scene refuses, names the run and the key.
    const auto unknown = sweepError(R"({"axes": [{"dmd.dv": [1]}]})");
    EXPECT_NE(unknown.find("run dv-1"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("dmd.dv: unknown key"), std::string::npos) << unknown;
    const auto refused = sweepError(R"({"axes": [{"smd.dt_fs": [1.8, 0]}]})");
    EXPECT_NE(refused.find("run dt_fs-0"), std::string::npos) << refused;
    EXPECT_NE(refused.find("smd.dt_fs"), std::string::npos) << refused;
    EXPECT_THROW(loadSweep("/nonexistent/sweep.json", {}), SceneError);
}

// A key repeated in a sweep file is refused, named by its path, as a scene's are: last-wins would
// run another sweep than the one the file seems to ask for.
TEST(SweepPlan, ARepeatedKeyIsRefusedNamingIt) {
    EXPECT_EQ(sweepError(R"({"seeds": [1], "seeds": [2]})"), "s.json: seeds: duplicate key");
    EXPECT_EQ(sweepError(R"({"set": {"run.time_ps": 1, "run.time_ps": 2}})"),
              "s.json: set.run.time_ps: duplicate key");
    EXPECT_EQ(sweepError(R"({"axes": [{"dmd.dV": [1], "dmd.dV": [2]}]})"),
              "s.json: axes[0].dmd.dV: duplicate key");
    EXPECT_EQ(sweepError(R"({"axes": [{"cases": [{"seed": 1, "seed": 2}]}]})"),
              "s.json: axes[0].cases[0].seed: duplicate key");
    // The same key in two objects is no repetition.
    EXPECT_EQ(plan(R"({"axes": [{"cases": [{"seed": 1}, {"seed": 2}]}]})").runs.size(), 2u);
}

// Keys of one engine's section set for runs of the other (cli/engine_keys.hpp): the ladders of
// two engines as cases, and common keys of both engines for a sweep running both, are meant; an
// axis that sets smd.dt_fs for DMD runs, or a common key of an engine no run has, is not.
TEST(SweepPlan, KeysTheRunsEnginesDoNotReadAreNoted) {
    const char* ladders = R"({"axes": [{"cases": [{"engine": "dmd", "dmd.dV": 0.5},
                                                 {"engine": "smd", "smd.dt_fs": 1.8}]}]})";
    EXPECT_TRUE(plan(ladders).ignoredKeys.empty());
    EXPECT_TRUE(plan(ladders, {"smd.skin=0.4", "dmd.horizon_fs=2"}).ignoredKeys.empty());
    EXPECT_TRUE(plan(R"({"set": {"smd.skin": 0.4}, "axes": [{"engine": ["dmd", "smd"]}]})")
                    .ignoredKeys.empty());
    // An SMD key zipped with one both engines read serves the SMD runs (bench.json's skin).
    EXPECT_TRUE(plan(R"({"axes": [{"state.density": [0.1, 0.3], "smd.skin": [2.4, 0.3]},
                                  {"engine": ["dmd", "smd"]}]})")
                    .ignoredKeys.empty());
    // A case that sets the engine and a key of the other's section means it for that run.
    const auto contrary =
        plan(R"({"axes": [{"cases": [{"engine": "dmd", "smd.dt_fs": 0.9}, {"engine": "smd"}]}]})");
    ASSERT_EQ(contrary.ignoredKeys.size(), 1u);
    EXPECT_NE(contrary.ignoredKeys[0].find("axes set smd.dt_fs for 1 run of engine dmd (first: "
                                           "engine-dmd_dt_fs-0.9)"),
              std::string::npos)
        << contrary.ignoredKeys[0];

    // A product of an engine axis and an SMD axis: the DMD runs ignore smd.dt_fs.
    const auto product =
        plan(R"({"axes": [{"engine": ["dmd", "smd"]}, {"smd.dt_fs": [0.9, 1.8]}]})");
    ASSERT_EQ(product.ignoredKeys.size(), 1u);
    EXPECT_EQ(product.ignoredKeys[0],
              "s.json: axes set smd.dt_fs for 2 runs of engine dmd (first: engine-dmd_dt_fs-0.9): "
              "their engine, dmd, does not read the smd section, so the setting has no effect");

    // A common key of an engine no run has.
    const auto common = plan(R"({"axes": [{"dmd.dV": [0.5, 0.25]}]})", {"smd.dt_fs=0.7"});
    ASSERT_EQ(common.ignoredKeys.size(), 1u);
    EXPECT_EQ(common.ignoredKeys[0],
              "s.json: smd.dt_fs=0.7 (for every run): every run's engine, dmd, does not read the "
              "smd section, so the setting has no effect");
    try {
        refuseIgnoredKeys(common);
        ADD_FAILURE() << "--strict accepted a key no run reads";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()), common.ignoredKeys[0] + " (refused under --strict)");
    }
    EXPECT_NO_THROW(refuseIgnoredKeys(plan(ladders)));
}

// Bytes that are not UTF-8, in the file or a --set of the command line: one line naming the byte
// and where it is, not "not valid JSON" nor the raw bytes echoed.
TEST(SweepPlan, TextThatIsNotUtf8IsRefusedNamingTheByte) {
    EXPECT_EQ(sweepError("{\"set\": {\"dmd.\xff\": 1}}"),
              "s.json: byte 0xff at line 1, column 15: not UTF-8 text: a sweep file is JSON, which "
              "is UTF-8");
    EXPECT_EQ(sweepError("{\"seeds\": [1],\n \"set\": {\"name\": \"caf\xe9\"}}"),
              "s.json: byte 0xe9 at line 2, column 22: not UTF-8 text: a sweep file is JSON, which "
              "is UTF-8");
    try {
        plan(R"({"seeds": [1]})", {"name=caf\xe9"});
        ADD_FAILURE() << "a --set that is not UTF-8 was taken";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "s.json: --set name=caf\\xe9: not UTF-8 text (byte 0xe9 at character 9): keys "
                  "and values are UTF-8");
    }
}

TEST(SweepTable, RowsInSweepOrderWithStatusNumbersAndQuotedCells) {
    const auto p = plan(R"({"axes": [{"dmd.terraces": [{"levels": "optimal", "n": 3}]},
                                     {"engine": ["dmd", "smd"]}]})");
    std::vector<SweepEntry> entries(2);
    entries[0].status = RunStatus::Ok;
    entries[0].summary = {{"n_bodies", 512},
                          {"simulated_ps", 9.0},
                          {"potential_energy_mean", -4000.5},
                          {"pressure", {{"mean_reduced", 0.25}, {"error_reduced", 0.01}}}};
    entries[0].wallSeconds = 2.5;
    entries[1].status = RunStatus::Failed;
    entries[1].message = "smd: the integration became unstable, \"dt\" too long";
    const std::string table = sweepTable(p, entries);
    std::istringstream in(table);
    std::string header, first, second, extra;
    std::getline(in, header), std::getline(in, first), std::getline(in, second);
    EXPECT_FALSE(std::getline(in, extra));
    EXPECT_EQ(header.rfind("run,dmd.terraces,engine,status,n_bodies,simulated_ps,", 0), 0u);
    EXPECT_NE(header.find(",cpu_seconds,cpu_seconds_per_ps,collisions_per_cpu_second,"
                          "all_events_per_cpu_second,wall_seconds,message"),
              std::string::npos)
        << "the costs come last, after the physics";
    EXPECT_EQ(
        first.rfind(
            R"(levels-optimal_n-3_engine-dmd,"{""levels"":""optimal"",""n"":3}",dmd,ok,512,9,)", 0),
        0u)
        << first;
    EXPECT_NE(first.find(",-4000.5,"), std::string::npos);
    EXPECT_NE(first.find(",0.25,0.01,"), std::string::npos);
    EXPECT_NE(first.find(",2.5,"), std::string::npos);
    EXPECT_NE(second.find(",smd,failed,nan,"), std::string::npos) << second;
    EXPECT_NE(second.find(R"("smd: the integration became unstable, ""dt"" too long")"),
              std::string::npos)
        << second;
}

TEST(SweepTable, CompleteSummaries) {
    const json done = {{"cpu_seconds", 1.0}, {"analysis", {{"rdf", "rdf.csv"}}}};
    EXPECT_TRUE(completeSummary(done));
    json interrupted = done;
    interrupted["interrupted"] = true;
    EXPECT_FALSE(completeSummary(interrupted));
    json failed = done;
    failed["error"] = "smd: unstable";
    EXPECT_FALSE(completeSummary(failed));
    json unfinished = done;
    unfinished["analysis"] = "not finished: the process ended during the analysis";
    EXPECT_FALSE(completeSummary(unfinished));
    EXPECT_FALSE(completeSummary(json(nullptr)));
}

TEST(SweepTable, WhatADirectoryFromBeforeIsTakenFor) {
    const TempDir tmp;
    const auto p = plan(R"({"axes": [{"engine": ["dmd"]}]})");
    const SweepRun& run = p.runs[0];
    const auto dir = tmp.path / run.name;
    SweepEntry found;
    // Nothing there: a fresh run.
    EXPECT_EQ(resumeAction(dir, run, false, found), RunAction::Fresh);
    std::filesystem::create_directories(dir);
    const json scene = toJson(run.scene);
    const json summary = {{"cpu_seconds", 1.0}, {"analysis", json::object()}};
    // The complete result of the same scene: not run again, its summary taken.
    writeFileAtomically(dir / "scene.json", scene.dump(2));
    writeFileAtomically(dir / "summary.json", summary.dump());
    EXPECT_EQ(resumeAction(dir, run, false, found), RunAction::Skip);
    EXPECT_EQ(found.status, RunStatus::Ok);
    EXPECT_TRUE(found.reused);
    // The same result for another scene: run afresh.
    json other = scene;
    other["state"]["density"] = 0.3;
    writeFileAtomically(dir / "scene.json", other.dump());
    EXPECT_EQ(resumeAction(dir, run, false, found), RunAction::Fresh);
    // An interrupted run of the same scene: continued from its restart file, else run again.
    writeFileAtomically(dir / "scene.json", scene.dump());
    writeFileAtomically(dir / "summary.json",
                        json{{"cpu_seconds", 1.0}, {"interrupted", true}}.dump());
    EXPECT_EQ(resumeAction(dir, run, false, found), RunAction::Fresh);
    writeFileAtomically(dir / "restart.bin", "x");
    EXPECT_EQ(resumeAction(dir, run, false, found), RunAction::Continue);
    // A recorded failure of the same scene stands unless retried; one of another scene does not.
    writeFileAtomically(dir / failedFileName, json{{"scene", scene}, {"error", "boom"}}.dump());
    EXPECT_EQ(resumeAction(dir, run, false, found), RunAction::Skip);
    EXPECT_EQ(found.status, RunStatus::Failed);
    EXPECT_EQ(found.message, "boom");
    EXPECT_EQ(resumeAction(dir, run, true, found), RunAction::Continue);
    writeFileAtomically(dir / failedFileName, json{{"scene", other}, {"error", "boom"}}.dump());
    EXPECT_EQ(resumeAction(dir, run, false, found), RunAction::Continue);
}

TEST(SweepTable, FinishedRunsAreClassifiedFromWhatTheyLeft) {
    const TempDir tmp;
    const auto p = plan(R"({"axes": [{"engine": ["dmd"]}]})");
    const SweepRun& run = p.runs[0];
    const auto dir = tmp.path / run.name;
    std::filesystem::create_directories(dir);
    // Refused before it wrote anything: the log's last line is the reason, recorded.
    writeFileAtomically(dir / "run.log", "terrace: run: too many samples\n\n");
    auto e = finishedEntry(dir, run, {false, 1});
    EXPECT_EQ(e.status, RunStatus::Failed);
    EXPECT_EQ(e.message, "run: too many samples");
    EXPECT_TRUE(std::filesystem::exists(dir / failedFileName));
    SweepEntry found;
    EXPECT_EQ(resumeAction(dir, run, false, found), RunAction::Skip);
    // A crash names its signal.
    e = finishedEntry(dir, run, {true, 11});
    EXPECT_EQ(e.status, RunStatus::Failed);
    EXPECT_NE(e.message.find("killed by signal 11"), std::string::npos);
    // Stopped by a signal, its summary says so: interrupted, not failed.
    writeFileAtomically(
        dir / "summary.json",
        json{{"cpu_seconds", 1.0}, {"interrupted", true}, {"interrupted_by", "SIGTERM"}}.dump());
    e = finishedEntry(dir, run, {false, 143});
    EXPECT_EQ(e.status, RunStatus::Interrupted);
    EXPECT_EQ(e.message, "interrupted by SIGTERM");
    // Finished.
    writeFileAtomically(dir / "summary.json",
                        json{{"cpu_seconds", 1.0}, {"analysis", json::object()}}.dump());
    e = finishedEntry(dir, run, {false, 0});
    EXPECT_EQ(e.status, RunStatus::Ok);
}

} // namespace test_sweep
