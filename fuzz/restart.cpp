// Restart files as a continued run reads them before it rebuilds an engine: restart.bin's CBOR,
// its format and the scene it records (cli/run_command.cpp continueRun), and samples.bin records.
#include "cli/restart.hpp"
#include "cli/scene_check.hpp"
#include "core/output_file.hpp"
#include "core/scene.hpp"
#include "fuzz/support.hpp"
#include "fuzz/targets.hpp"

namespace terrace::fuzz {

void restartInput(std::string_view bytes) {
    if (bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0xff) {
        const int bodies = (bytes[1] & 7) + 1;
        const bool withOrientation = (bytes[1] & 8) != 0;
        std::vector<Snapshot> samples;
        std::vector<cli::SampleRecord> energies;
        try {
            cli::decodeSamples(std::string(bytes.substr(2)), bodies, withOrientation, 10.0, samples,
                               energies);
        } catch (const std::runtime_error&) { // not whole records (documented)
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
