// Scene files and --set overrides: loadScene, then the engines' sections as a run resolves them.
// A scene that reads must read again from the resolved form a run records (scene.json).
#include "core/scene.hpp"
#include "cli/scene_check.hpp"
#include "core/output_file.hpp"
#include "fuzz/support.hpp"
#include "fuzz/targets.hpp"
#include <stdexcept>

namespace terrace::fuzz {

void sceneInput(std::string_view bytes) {
    const auto sets = takeSetLines(bytes);
    const auto path = scratchDirectory() / "scene.json";
    writeFile(path, bytes);
    Scene scene;
    try {
        scene = loadScene(path.string(), sets);
        cli::resolveEngineSections(scene, path.string());
    } catch (const SceneError&) {
        return;
    }
    (void)sceneWarnings(scene);
    Scene again = sceneFromJson(toJson(scene), "<resolved>");
    cli::resolveEngineSections(again, "<resolved>");
    if (toJson(again) != toJson(scene))
        throw std::logic_error("fuzz: the resolved scene does not read back the same");
}

} // namespace terrace::fuzz

#ifdef TERRACE_LIBFUZZER
extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, unsigned long size) {
    terrace::fuzz::sceneInput({reinterpret_cast<const char*>(data), size});
    return 0;
}
#endif
