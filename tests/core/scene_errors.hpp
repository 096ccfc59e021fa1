#pragma once
// The message with which a scene document is refused, for the scene readers' tests.
#include "core/scene.hpp"
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace terrace::scene_tests {

/// What sceneFromJson says when it refuses `j` with `overrides`; "" when it accepts them.
inline std::string errorOf(const nlohmann::json& j,
                           const std::vector<std::string>& overrides = {}) {
    try {
        sceneFromJson(j, "test.json", overrides);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

} // namespace terrace::scene_tests
