// Every input kept for the fuzzers, the seeds and the findings, fed to the same entries the
// fuzzers call: a finding fixed stays fixed, in every build (fuzz/targets.hpp).
#include "fuzz/targets.hpp"
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <string>
#include <vector>

namespace {

using Entry = void (*)(std::string_view);

void replay(const std::string& target, Entry entry) {
    const std::filesystem::path root = TERRACE_SOURCE_DIR "/fuzz";
    std::vector<std::filesystem::path> files;
    for (const char* kind : {"corpus", "regressions"}) {
        const auto dir = root / kind / target;
        if (!std::filesystem::is_directory(dir)) continue;
        for (const auto& e : std::filesystem::directory_iterator(dir))
            if (e.is_regular_file()) files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    ASSERT_FALSE(files.empty()) << "no seed inputs for " << target;
    for (const auto& file : files) {
        std::ifstream in(file, std::ios::binary);
        const std::string bytes{std::istreambuf_iterator<char>(in), {}};
        ASSERT_TRUE(in.good() || in.eof()) << file;
        SCOPED_TRACE(file.string());
        try {
            entry(bytes);
        } catch (const std::exception& e) {
            ADD_FAILURE() << file << ": " << e.what();
        }
    }
}

} // namespace

TEST(FuzzRegressions, Scene) {
    replay("scene", terrace::fuzz::sceneInput);
}
TEST(FuzzRegressions, Sweep) {
    replay("sweep", terrace::fuzz::sweepInput);
}
TEST(FuzzRegressions, Restart) {
    replay("restart", terrace::fuzz::restartInput);
}
TEST(FuzzRegressions, Trajectory) {
    replay("trajectory", terrace::fuzz::trajectoryInput);
}
TEST(FuzzRegressions, Csv) {
    replay("csv", terrace::fuzz::csvInput);
}
