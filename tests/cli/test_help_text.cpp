// terrace --help and terrace COMMAND --help (cli/help_text.hpp): every command has its own help,
// naming every option its parser takes (cli/main.cpp).
#include "cli/help_text.hpp"
#include <gtest/gtest.h>

namespace test_help_text {

using namespace terrace::cli;

TEST(HelpText, EveryCommandHasItsOwnHelp) {
    const std::vector<std::string> expected = {"run",   "analyse",  "compare", "design",
                                               "sweep", "tradeoff", "export"};
    EXPECT_EQ(commandNames(), expected);
    for (const std::string& c : commandNames()) {
        const std::string help = commandHelp(c);
        EXPECT_EQ(help.rfind("Usage:\n  terrace " + c, 0), 0u) << help;
        EXPECT_NE(help.find("--help"), std::string::npos) << c;
        EXPECT_NE(generalHelp().find("terrace " + c), std::string::npos) << c;
    }
    EXPECT_EQ(commandHelp("analyze"), commandHelp("analyse"));
    EXPECT_EQ(commandHelp("lammps"), "");
}

TEST(HelpText, EachCommandsOptionsAreListed) {
    const std::vector<std::pair<std::string, std::vector<std::string>>> options = {
        {"run", {"--set", "--out", "--overwrite", "--strict", "--continue", "--quiet"}},
        {"compare", {"--tol-sigma", "--column"}},
        {"design", {"--set", "--profile", "--strict"}},
        {"export", {"--set"}},
        {"sweep", {"--set", "--out", "-j", "--retry-failed", "--strict", "--quiet"}},
        {"tradeoff",
         {"--tolerance", "--set", "-j", "--out", "--bias-n", "--max-replicas", "--cost-pairs",
          "--budget-cpu-hours", "--dV", "--designs", "--schemes", "--observables", "--quiet"}}};
    for (const auto& [command, list] : options) {
        const std::string help = commandHelp(command);
        const std::string listed = help.substr(help.find("\nOptions:\n"));
        for (const std::string& o : list)
            EXPECT_NE(listed.find("\n  " + o + " "), std::string::npos) << command << " " << o;
    }
}

TEST(HelpText, RunNamesTheUnits) {
    const std::string help = commandHelp("run");
    for (const char* needle : {"units=lj", "T*, U/N in ε", "docs/UNITS.md", "run.time_ps"})
        EXPECT_NE(help.find(needle), std::string::npos) << needle;
}

TEST(HelpText, RunNamesTheHeatBath) {
    const std::string help = commandHelp("run");
    for (const char* needle : {"run.heat_bath", "andersen", "csvr", "NVE"})
        EXPECT_NE(help.find(needle), std::string::npos) << needle;
}

} // namespace test_help_text
