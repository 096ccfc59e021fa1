// Trajectories as terrace analyse reads them: both passes over trajectory.xyz and the analysis
// they feed, the CSVs written into the scratch directory.
#include "cli/analyse_command.hpp"
#include "core/output_file.hpp"
#include "core/xyz.hpp"
#include "fuzz/support.hpp"
#include "fuzz/targets.hpp"
#include <cstdio>
#include <stdexcept>

namespace terrace::fuzz {

void trajectoryInput(std::string_view bytes) {
    const auto dir = scratchDirectory() / "analyse";
    std::filesystem::create_directories(dir);
    writeFile(dir / "trajectory.xyz", bytes);
    try {
        cli::analyseRun(dir);
    } catch (const TrajectoryError&) {
    } catch (const std::invalid_argument&) { // the analysis refusing what the frames say
    }
}

} // namespace terrace::fuzz

#ifdef TERRACE_LIBFUZZER
extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, unsigned long size) {
    // analyseRun's summary on stdout, once an input, would drown the fuzzer's own.
    static const bool quiet = std::freopen("/dev/null", "w", stdout) != nullptr;
    (void)quiet;
    terrace::fuzz::trajectoryInput({reinterpret_cast<const char*>(data), size});
    return 0;
}
#endif
