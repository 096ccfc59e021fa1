#pragma once
// Self-describing results (STYLE.md item 11): every run records the resolved scene, the seed, the
// git revision and the compiler and flags that built the executable next to its output.
#include "core/scene.hpp"
#include "core/unit_system.hpp"
#include <nlohmann/json.hpp>
#include <string>

namespace terrace::cli {

/// Explicit start bodies (state.particles) the provenance copies whole; beyond, it names them by
/// count, checksum and the file that holds them (the run's scene.json).
inline constexpr std::size_t provenanceParticlesInline = 64;

nlohmann::json provenance(const Scene& scene);

/// Prints progress lines to stderr, at most one every few seconds and only once a run has taken
/// longer than that, so short runs stay silent.
class ProgressReporter {
public:
    /// endTime: where the run ends, internal time units (equilibration and production); the
    /// time reached is shown in `units` (ps or τ).
    ProgressReporter(bool quiet, double endTime, const UnitSystem& units = UnitSystem::real());
    /// A line every few seconds: the phase, samples done, the time reached and the wall seconds
    /// left until endTime at the pace of the current phase, the analysis' time per sample included
    /// (during equilibration, which analyses nothing, the estimate is a little short).
    void report(const char* phase, long done, long total, double time);

private:
    bool quiet_;
    double started_;
    double last_;
    double endTime_;
    UnitSystem units_;
    std::string phase_;                        // the phase whose pace is measured
    double phaseWall_ = 0.0, phaseTime_ = 0.0; // wall seconds and run time where it began
};

} // namespace terrace::cli
