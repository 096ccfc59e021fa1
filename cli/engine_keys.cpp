#include "cli/engine_keys.hpp"
#include "core/scene.hpp"

namespace terrace::cli {

std::string engineOfKey(const std::string& dottedKey) {
    const std::string section = dottedKey.substr(0, dottedKey.find('.'));
    return section == "dmd" || section == "smd" ? section : "";
}

std::string overrideKey(const std::string& assignment) {
    return assignment.substr(0, assignment.find('='));
}

std::string ignoredKeyNote(const std::string& what, const std::string& keyEngine,
                           const std::string& reader) {
    return what + ": " + reader + " does not read the " + keyEngine +
           " section, so the setting has no effect";
}

std::string asWarning(const std::string& note) {
    return note + " (--strict refuses it)";
}

std::string asRefusal(const std::string& note) {
    return note + " (refused under --strict)";
}

std::vector<std::string> judgeOverrides(const std::vector<std::string>& overrides,
                                        const std::string& engine, const std::string& reader,
                                        bool strict) {
    std::vector<std::string> warnings;
    for (const std::string& o : overrides) {
        const std::string owner = engineOfKey(overrideKey(o));
        if (owner.empty() || owner == engine) continue;
        const std::string note = ignoredKeyNote("--set " + o, owner, reader);
        if (strict) throw SceneError(asRefusal(note));
        warnings.push_back(asWarning(note));
    }
    return warnings;
}

} // namespace terrace::cli
