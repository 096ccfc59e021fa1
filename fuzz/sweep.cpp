// Sweep files and the --set options of terrace sweep: the whole plan, every run's scene resolved.
#include "cli/sweep_plan.hpp"
#include "fuzz/support.hpp"
#include "fuzz/targets.hpp"

namespace terrace::fuzz {

void sweepInput(std::string_view bytes) {
    const auto sets = takeSetLines(bytes);
    try {
        (void)cli::sweepFromJson(std::string(bytes), "sweep.json",
                                 TERRACE_SOURCE_DIR "/experiments/sweeps", sets);
    } catch (const SceneError&) {
    }
}

} // namespace terrace::fuzz

#ifdef TERRACE_LIBFUZZER
extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, unsigned long size) {
    terrace::fuzz::sweepInput({reinterpret_cast<const char*>(data), size});
    return 0;
}
#endif
