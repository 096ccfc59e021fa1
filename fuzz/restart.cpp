// Restart files as a continued run reads them before it rebuilds an engine: restart.bin's CBOR,
// its format and the scene it records (cli/run_command.cpp continueRun), and the analysis' and
// the sample statistics' states it carries (analysis/state_bytes.hpp).
#include "cli/restart.hpp"
#include "analysis/run_analysis.hpp"
#include "cli/sample_statistics.hpp"
#include "cli/scene_check.hpp"
#include "core/output_file.hpp"
#include "core/scene.hpp"
#include "fuzz/support.hpp"
#include "fuzz/targets.hpp"

namespace terrace::fuzz {

void restartInput(std::string_view bytes) {
    if (bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0xfe) {
        // The sample statistics' state, for a plan of 8 + (second byte & 15) samples, every third
        // a g(r) frame; the kind of virial by bit 4, a heat bath by bit 5.
        const long samples = 8 + (bytes[1] & 15);
        const bool heatBath = (bytes[1] & 32) != 0;
        cli::SampleStatistics stats(
            cli::SamplePlan{samples, (samples + 2) / 3,
                            (bytes[1] & 16) != 0 ? VirialKind::Impulse : VirialKind::Instantaneous,
                            1000.0, 100, 2.5, heatBath});
        const auto* state = reinterpret_cast<const std::uint8_t*>(bytes.data() + 2);
        try {
            stats.restore({state, bytes.size() - 2});
            nlohmann::json summary; // what a continued run then reports from it
            stats.summarise(summary, 3.0, 1.0);
            (void)stats.collisionRateError(0.01);
            if (heatBath && stats.count() > 0) { // what the heat bath's summary reads
                (void)stats.effectiveEnergy();
                (void)stats.bathEnergyRemoved();
                (void)stats.canonicalKinetic();
            }
        } catch (const std::invalid_argument&) { // a state that does not fit (documented)
        }
        return;
    }
    if (bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0xff) {
        analysis::StreamingOptions options;
        options.lagsPerLevel = 4;
        options.beta = (bytes[1] & 8) != 0 ? 1.0 : 0.0; // with a terracing profile
        analysis::RunAnalysis analysis((bytes[1] & 7) + 2, 10.0, 0.001, 8, options);
        const auto* state = reinterpret_cast<const std::uint8_t*>(bytes.data() + 2);
        try {
            analysis.restore({state, bytes.size() - 2});
        } catch (const std::invalid_argument&) { // a state that does not fit (documented)
        }
        return;
    }
    const auto dir = scratchDirectory() / "restart";
    std::filesystem::create_directories(dir);
    writeFile(dir / "restart.bin", bytes);
    try {
        const nlohmann::json restart = cli::readRestart(dir);
        try {
            nlohmann::json recorded = restart.at("scene");
            if (recorded.contains("dmd") && recorded["dmd"].value("queue", "") == "auto")
                recorded["dmd"]["queue"] = "tree";
            Scene scene = sceneFromJson(recorded, "restart.bin");
            cli::resolveEngineSections(scene, "restart.bin");
        } catch (const nlohmann::json::exception& e) {
            throw cli::damagedRestart(dir, e); // as continueRun does
        }
    } catch (const IoError&) {
    } catch (const SceneError&) {
    }
}

} // namespace terrace::fuzz

#ifdef TERRACE_LIBFUZZER
extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, unsigned long size) {
    terrace::fuzz::restartInput({reinterpret_cast<const char*>(data), size});
    return 0;
}
#endif
