#pragma once
// Self-describing results (STYLE.md item 11): every run records the resolved scene, the seed, the
// git revision and the compiler and flags that built the executable next to its output.
#include "core/scene.hpp"
#include <nlohmann/json.hpp>
#include <string>

namespace terrace::cli {

nlohmann::json provenance(const Scene& scene);

/// Prints progress lines to stderr, at most one every few seconds and only once a run has taken
/// longer than that, so short runs stay silent.
class ProgressReporter {
public:
    explicit ProgressReporter(bool quiet);
    void report(const char* phase, long done, long total, double time);

private:
    bool quiet_;
    double started_;
    double last_;
};

} // namespace terrace::cli
