#pragma once
// What the resource-check tests share: the dense-rods scene with overrides, a scratch directory of
// the process's own, and the process's peak resident memory.
#include "cli/run_command.hpp"
#include <filesystem>
#include <string>
#include <sys/resource.h>
#include <unistd.h>
#include <vector>

namespace terrace::resource_tests {

inline const std::string denseRods =
    std::string(TERRACE_SOURCE_DIR) + "/experiments/scenes/dense-rods.json";

inline Scene scene(std::vector<std::string> sets) {
    return cli::resolveScene({denseRods, std::move(sets), true});
}

inline std::filesystem::path scratch(const std::string& what) {
    return std::filesystem::temp_directory_path() /
           ("terrace-resources-" + what + "-" + std::to_string(::getpid()));
}

inline double peakRssBytes() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) * 1024.0; // KiB on Linux
}

} // namespace terrace::resource_tests
