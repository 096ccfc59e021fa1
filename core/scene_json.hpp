#pragma once
// Typed reads of a JSON scene, each error one line naming the source and the key's full dotted
// name: "<origin>: <section.key>: <problem>" (without an origin, "<section.key>: <problem>"). A
// section's reader lists its keys once (onlyKeys), so that an unknown key is refused; repeated
// keys are found on the text, before parsing keeps only the last (firstDuplicateKey). The scene's
// own sections (core/scene_sections.hpp) and the engines' (dmd/section.hpp, smd/parameters.hpp)
// are read with these, so every module words its errors alike.
#include "core/scene.hpp"
#include "core/vec.hpp"
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace terrace {

/// A double as a person reads it (six significant digits, "1e-06", "inf").
std::string showNumber(double x);

/// A JSON value as an error message quotes it. Bytes that are not UTF-8 (a --set value taken as a
/// bare string, a string in a restart file's CBOR) show as U+FFFD: a plain dump() would throw.
std::string showJson(const nlohmann::json& v);

/// One JSON object of a scene and its dotted path ("" for the top level, "dmd.terraces", ...).
class JsonSection {
public:
    /// `object` must outlive the section; `origin` names the source ("" for none).
    JsonSection(const nlohmann::json& object, std::string path, std::string origin);

    /// Refuses `key` of this section, by its full dotted name.
    [[noreturn]] void fail(const std::string& key, const std::string& what) const;
    /// Refuses a key named in full (a cross-check that blames another section's key).
    [[noreturn]] void refuse(const std::string& dottedName, const std::string& what) const;
    /// The key's full dotted name.
    std::string name(const std::string& key) const;
    const std::string& path() const { return path_; }
    const std::string& origin() const { return origin_; }

    const nlohmann::json& object() const { return *object_; }
    bool has(const std::string& key) const { return object_->contains(key); }
    const nlohmann::json& at(const std::string& key) const { return object_->at(key); }
    /// Refuses the section if it is not an object or holds a key outside `known`, naming the known
    /// key nearest it ("did you mean", core/suggest.hpp) or, when none is near, all of them.
    void onlyKeys(std::initializer_list<const char*> known) const;
    /// The object under `key` (an empty one when absent), refused if it is not an object.
    JsonSection section(const std::string& key) const;

    /// A finite number in [lo, hi] (or (lo, hi] when loOpen); `def` when absent.
    double number(const std::string& key, double def, double lo, double hi,
                  bool loOpen = false) const;
    /// An integer in [lo, hi]; `def` when absent.
    long long integer(const std::string& key, long long def, long long lo, long long hi) const;
    /// One of `allowed` (listed in the error in their order, with the nearest); `def` when absent.
    std::string choice(const std::string& key, const std::string& def,
                       std::initializer_list<const char*> allowed) const;
    bool boolean(const std::string& key, bool def) const;
    /// Three finite numbers whose length is finite too.
    Vec3 vec3(const std::string& key) const;
    /// A list of finite numbers (`unit` names them in the error: "kJ/mol").
    std::vector<double> numbers(const std::string& key, const std::string& unit) const;

private:
    const nlohmann::json* object_;
    std::string path_;
    std::string origin_;
};

/// Refuses `value` (in `unit`, of fsPerUnit fs) unless it is a whole multiple k >= 1 of gridFs
/// fs, within limits::gridTolerance, naming the nearest valid values.
void requireOnGrid(const JsonSection& at, const std::string& key, double value, const char* unit,
                   double fsPerUnit, const std::string& gridKey, double gridFs);

/// Applies a "dotted.key=value" override (parseOverride) to `scene`, creating sections on the way.
void applyOverride(nlohmann::json& scene, const std::string& assignment, const std::string& origin);

/// The dotted path of the first key repeated within one object of `text` (state.particles[3].r
/// style), or "" when none is.
std::string firstDuplicateKey(const std::string& text);

} // namespace terrace
