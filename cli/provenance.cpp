#include "cli/provenance.hpp"
#include "cli/cpu_clock.hpp"
#include "cli/restart.hpp"
#include <chrono>
#include <cstdio>
#include <ctime>

#ifndef TERRACE_GIT_REVISION
#define TERRACE_GIT_REVISION "unknown"
#endif
#ifndef TERRACE_CXX_FLAGS
#define TERRACE_CXX_FLAGS "unknown"
#endif

namespace terrace::cli {

namespace {
double wallNow() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}
} // namespace

nlohmann::json provenance(const Scene& scene) {
    char stamp[32] = "";
    const std::time_t now = std::time(nullptr);
    std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    nlohmann::json resolved = toJson(scene);
    // An explicit start of many bodies is the run's scene.json's to hold, whole: here it is named
    // by its count and checksum, so that summary.json stays small (9.3 MB at N 32 000 otherwise).
    if (scene.state.particles.size() > provenanceParticlesInline) {
        auto& particles = resolved["state"]["particles"];
        char sum[24];
        std::snprintf(sum, sizeof sum, "%016llx",
                      static_cast<unsigned long long>(crc64(particles.dump())));
        particles = {{"count", scene.state.particles.size()},
                     {"crc64_of_json", sum},
                     {"file", "scene.json"}};
    }
    return {{"scene", resolved},
            {"seed", scene.seed},
            {"git_revision", TERRACE_GIT_REVISION},
            {"compiler", std::string("g++ ") + __VERSION__},
            {"flags", TERRACE_CXX_FLAGS},
            {"date_utc", stamp}};
}

ProgressReporter::ProgressReporter(bool quiet, double endTime, const UnitSystem& units)
    : quiet_(quiet), started_(wallNow()), last_(started_), endTime_(endTime), units_(units) {}

void ProgressReporter::report(const char* phase, long done, long total, double time) {
    constexpr double everySeconds = 5.0; // quiet for short runs, a heartbeat for long ones
    const double now = wallNow();
    if (phase_ != phase) phase_ = phase, phaseWall_ = now, phaseTime_ = time;
    if (quiet_ || (now - last_ < everySeconds && done != total) || now - started_ < everySeconds)
        return;
    last_ = now;
    char eta[64] = "";
    if (time > phaseTime_ && endTime_ > time)
        std::snprintf(eta, sizeof eta, ", about %.0f s left",
                      (now - phaseWall_) / (time - phaseTime_) * (endTime_ - time));
    std::fprintf(stderr, "terrace: %s %ld/%ld samples (%.0f%%), t = %.3f %s, %.0f s elapsed%s\n",
                 phase, done, total, total > 0 ? 100.0 * double(done) / double(total) : 100.0,
                 units_.time(time * 0.1), units_.timeUnit(), now - started_, eta);
}

} // namespace terrace::cli
